#include "core/mo_catalogue.hpp"

#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

// The file's 32-bit words, in the byte order its magic number says.
class words {
 public:
  explicit words(const std::string& bytes) : bytes_(bytes) {}
  bool read(std::size_t offset, std::uint32_t& value) const {
    if (offset + 4 > bytes_.size())
      return false;
    const auto byte = [&](std::size_t i) {
      return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes_[offset + i]));
    };
    value = swapped_ ? byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3)
                     : byte(3) << 24 | byte(2) << 16 | byte(1) << 8 | byte(0);
    return true;
  }
  void swap(bool swapped) { swapped_ = swapped; }

 private:
  const std::string& bytes_;
  bool swapped_ = false;
};

// A Plural-Forms expression of n, as C writes it ("n > 1", "(n==1 ? 0 : n%10>=2 && ... ? 1 : 2)"),
// evaluated by recursive descent; 0 for what it cannot read.
class plural_expression {
 public:
  plural_expression(std::string_view text, unsigned long n) : text_(text), n_(n) {}
  unsigned long value() { return ternary(); }

 private:
  void blanks() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_])))
      ++at_;
  }
  bool take(std::string_view token) {
    blanks();
    if (text_.substr(at_, token.size()) != token)
      return false;
    // ("<" is not "<=", "!" is not "!=")
    if (token.size() == 1 && at_ + 1 < text_.size() && text_[at_ + 1] == '=' &&
        (token == "<" || token == ">" || token == "!" || token == "="))
      return false;
    at_ += token.size();
    return true;
  }
  unsigned long ternary() {
    const unsigned long condition = either();
    if (!take("?"))
      return condition;
    const unsigned long if_true = ternary();
    take(":");
    const unsigned long if_false = ternary();
    return condition != 0 ? if_true : if_false;
  }
  unsigned long either() {
    unsigned long value = both();
    while (take("||")) {
      const unsigned long other = both();
      value = (value != 0 || other != 0) ? 1 : 0;
    }
    return value;
  }
  unsigned long both() {
    unsigned long value = equality();
    while (take("&&")) {
      const unsigned long other = equality();
      value = (value != 0 && other != 0) ? 1 : 0;
    }
    return value;
  }
  unsigned long equality() {
    unsigned long value = relation();
    for (;;) {
      if (take("=="))
        value = value == relation() ? 1 : 0;
      else if (take("!="))
        value = value != relation() ? 1 : 0;
      else
        return value;
    }
  }
  unsigned long relation() {
    unsigned long value = sum();
    for (;;) {
      if (take("<="))
        value = value <= sum() ? 1 : 0;
      else if (take(">="))
        value = value >= sum() ? 1 : 0;
      else if (take("<"))
        value = value < sum() ? 1 : 0;
      else if (take(">"))
        value = value > sum() ? 1 : 0;
      else
        return value;
    }
  }
  unsigned long sum() {
    unsigned long value = product();
    for (;;) {
      if (take("+"))
        value += product();
      else if (take("-"))
        value -= product();
      else
        return value;
    }
  }
  unsigned long product() {
    unsigned long value = unary();
    for (;;) {
      if (take("*")) {
        value *= unary();
      } else if (take("/")) {
        const unsigned long d = unary();
        value = d != 0 ? value / d : 0;
      } else if (take("%")) {
        const unsigned long d = unary();
        value = d != 0 ? value % d : 0;
      } else {
        return value;
      }
    }
  }
  unsigned long unary() {
    if (take("!"))
      return unary() == 0 ? 1 : 0;
    if (take("(")) {
      const unsigned long value = ternary();
      take(")");
      return value;
    }
    if (take("n"))
      return n_;
    blanks();
    unsigned long value = 0;
    while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_])))
      value = 10 * value + static_cast<unsigned long>(text_[at_++] - '0');
    return value;
  }

  std::string_view text_;
  unsigned long n_;
  std::size_t at_ = 0;
};

}  // namespace

bool mo_catalogue::load(const std::filesystem::path& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = format(tr("%s: cannot read the catalogue"), path.string().c_str());
    return false;
  }
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  words file(bytes);
  std::uint32_t magic = 0, count = 0, originals = 0, translated = 0;
  if (!file.read(0, magic) || (magic != 0x950412de && magic != 0xde120495)) {
    error = format(tr("%s: not a compiled message catalogue (.mo)"), path.string().c_str());
    return false;
  }
  file.swap(magic == 0xde120495);
  if (!file.read(8, count) || !file.read(12, originals) || !file.read(16, translated)) {
    error = format(tr("%s: the catalogue is cut short"), path.string().c_str());
    return false;
  }
  // Table i of each: the length and offset of the i-th original text and of its translation.
  const auto text = [&](std::uint32_t table, std::uint32_t i, std::string& out) {
    std::uint32_t length = 0, offset = 0;
    if (!file.read(table + 8 * i, length) || !file.read(table + 8 * i + 4, offset) ||
        std::size_t(offset) + length > bytes.size())
      return false;
    out.assign(bytes, offset, length);
    return true;
  };
  translations_.clear();
  for (std::uint32_t i = 0; i < count; ++i) {
    std::string original, translation;
    if (!text(originals, i, original) || !text(translated, i, translation)) {
      error = format(tr("%s: the catalogue is cut short"), path.string().c_str());
      return false;
    }
    // A text with a plural is "singular\0plural", its translation the forms, each ended by \0.
    std::vector<std::string> forms;
    for (std::size_t start = 0;;) {
      const std::size_t end = translation.find('\0', start);
      forms.push_back(translation.substr(start, end - start));
      if (end == std::string::npos)
        break;
      start = end + 1;
    }
    translations_[original.substr(0, original.find('\0'))] = std::move(forms);
  }
  // The header (the translation of ""): "Plural-Forms: nplurals=2; plural=(n > 1);".
  if (const auto header = translations_.find(""); header != translations_.end()) {
    const std::string& h = header->second.front();
    const std::size_t forms = h.find("nplurals=");
    const std::size_t rule = h.find("plural=", forms == std::string::npos ? 0 : forms + 9);
    if (forms != std::string::npos && rule != std::string::npos) {
      plural_count_ = std::stoul(h.substr(forms + 9));
      plural_expression_ = h.substr(rule + 7, h.find_first_of(";\n", rule) - rule - 7);
    }
  }
  return true;
}

const char* mo_catalogue::find(std::string_view message) const {
  const auto found = translations_.find(std::string(message));
  if (found == translations_.end() || found->second.front().empty() || message.empty())
    return nullptr;
  return found->second.front().c_str();
}

unsigned long mo_catalogue::plural_index(unsigned long n) const {
  const unsigned long index = plural_expression(plural_expression_, n).value();
  return index < plural_count_ ? index : 0;
}

const char* mo_catalogue::find_plural(std::string_view singular, unsigned long n) const {
  const auto found = translations_.find(std::string(singular));
  if (found == translations_.end())
    return nullptr;
  const unsigned long index = plural_index(n);
  if (index >= found->second.size() || found->second[index].empty())
    return nullptr;
  return found->second[index].c_str();
}

}  // namespace clothlab
