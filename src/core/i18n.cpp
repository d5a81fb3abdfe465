#include "core/i18n.hpp"

#if !defined(__EMSCRIPTEN__)
#include <libintl.h>
#endif

#include <algorithm>
#include <cctype>
#include <clocale>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "core/executable_path.hpp"
#include "core/mo_catalogue.hpp"

namespace clothlab {
namespace {

constexpr const char* text_domain = "clothlab";  // the catalogues' name: clothlab.mo

std::string chosen = "en";
unsigned generation = 0;
bool catalogues_open = false;

const char* environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : nullptr;
}

bool is_c_locale(std::string_view name) {
  return name.empty() || name == "C" || name == "POSIX";
}

std::filesystem::path catalogue_file(std::string_view code) {
  return catalogue_directory() / std::string(code) / "LC_MESSAGES" /
         (std::string(text_domain) + ".mo");
}

// The languages: English, the code's own, then one per catalogue built (locale/<code>/), each
// named in itself by its catalogue's translation of "English". A new po/<code>.po is a new
// language, with nothing else to change.
using language_names = std::vector<std::pair<std::string, std::string>>;  // (code, name)

const language_names& discovered_names() {
  static const language_names list = [] {
    language_names l;
    // TRANSLATORS: the name of your language, in your language ("Français", "Deutsch"): the
    // window's list of languages shows it.
    l.emplace_back("en", N_("English"));
    std::vector<std::string> codes;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(catalogue_directory(), ec)) {
      const std::string code = entry.path().filename().string();
      if (code != "en" && std::filesystem::is_regular_file(catalogue_file(code), ec))
        codes.push_back(code);
    }
    std::sort(codes.begin(), codes.end());
    for (const std::string& code : codes) {
      mo_catalogue catalogue;
      std::string error;
      const char* name =
          catalogue.load(catalogue_file(code), error) ? catalogue.find("English") : nullptr;
      l.emplace_back(code, name != nullptr ? name : code);
    }
    return l;
  }();
  return list;
}

// The same as views of the names, which stay where they are.
const std::vector<language>& discovered_languages() {
  static const std::vector<language> views = [] {
    std::vector<language> v;
    for (const auto& [code, name] : discovered_names())
      v.push_back({code, name});
    return v;
  }();
  return views;
}

const language* find_language(std::string_view code) {
  for (const language& l : discovered_languages()) {
    if (l.code == code)
      return &l;
  }
  return nullptr;
}

#if defined(__EMSCRIPTEN__)
// The browser: the catalogues read whole by mo_catalogue (mo_catalogue.hpp says why not musl's
// gettext), one per language once chosen, kept (tr() returns pointers into them).
std::map<std::string, mo_catalogue, std::less<>> loaded;
const mo_catalogue* catalogue = nullptr;
#else
// glibc's gettext (and GNU libintl's) reads the catalogue of LANGUAGE's language, whatever the
// locale of the messages' category, as long as that locale is not "C". The user's own locale
// where it is installed; else C.UTF-8, which glibc always has, and which needs no French locale
// installed to show French; else en_US.UTF-8 (macOS). Only LC_MESSAGES: the numbers' category
// (LC_NUMERIC) stays "C" in every language.
std::string messages_locale;

void set_messages_locale() {
  for (const char* name : {"", "C.UTF-8", "en_US.UTF-8"}) {
    const char* set = std::setlocale(LC_MESSAGES, name);
    if (set != nullptr && !is_c_locale(set)) {
      messages_locale = set;
      return;
    }
  }
  messages_locale.clear();  // every language shows as English
}
#endif

}  // namespace

const char* tr(const char* message) {
  if (chosen == "en" || !catalogues_open)
    return message;
#if defined(__EMSCRIPTEN__)
  const char* found = catalogue != nullptr ? catalogue->find(message) : nullptr;
  return found != nullptr ? found : message;
#else
  return dgettext(text_domain, message);
#endif
}

const char* trn(const char* singular, const char* plural, unsigned long n) {
  if (chosen == "en" || !catalogues_open)
    return n == 1 ? singular : plural;
#if defined(__EMSCRIPTEN__)
  const char* found = catalogue != nullptr ? catalogue->find_plural(singular, n) : nullptr;
  return found != nullptr ? found : n == 1 ? singular : plural;
#else
  return dngettext(text_domain, singular, plural, n);
#endif
}

const char* colon() {
  // TRANSLATORS: the colon between a thing and what is said of it ("--dt 0: must be between
  // ..."), with the spaces your language puts around it.
  return tr(": ");
}

std::string format(const char* format_string, ...) {
  std::va_list arguments;
  va_start(arguments, format_string);
  std::va_list again;
  va_copy(again, arguments);
  const int size = std::vsnprintf(nullptr, 0, format_string, arguments);
  va_end(arguments);
  std::string text(static_cast<std::size_t>(std::max(size, 0)), '\0');
  if (size > 0)
    std::vsnprintf(text.data(), text.size() + 1, format_string, again);
  va_end(again);
  return text;
}

std::span<const language> languages() {
  return discovered_languages();
}

std::string language_codes() {
  std::string codes;
  for (const language& l : languages())
    codes += (codes.empty() ? "" : ", ") + std::string(l.code);
  return codes;
}

std::string_view language_of_locale(std::string_view locale_name) {
  // "fr_FR.UTF-8@euro", a browser's "fr-FR": the language and territory ("fr_FR", for a
  // catalogue of its own), else the language alone ("fr"), before the codeset and modifier.
  std::string name(locale_name.substr(0, locale_name.find_first_of(".@")));
  std::replace(name.begin(), name.end(), '-', '_');
  const std::size_t territory = name.find('_');
  std::transform(name.begin(), name.begin() + std::min(territory, name.size()), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const std::string& code : {name, name.substr(0, territory)}) {
    if (const language* found = find_language(code))
      return found->code;
  }
  return languages().front().code;
}

std::string_view language_from_environment() {
  const char* locale = environment("LC_ALL");
  if (locale == nullptr)
    locale = environment("LC_MESSAGES");
  if (locale == nullptr)
    locale = environment("LANG");
  const std::string_view locale_name = locale != nullptr ? locale : "";
  // LANGUAGE lists languages in order of preference, "fr_CA:fr:en"; gettext ignores it in the C
  // locale.
  if (const char* preferred = environment("LANGUAGE");
      preferred != nullptr && !is_c_locale(locale_name)) {
    std::string_view list = preferred;
    while (!list.empty()) {
      const std::string_view entry = list.substr(0, list.find(':'));
      list.remove_prefix(std::min(list.size(), entry.size() + 1));
      const std::string_view code = language_of_locale(entry);
      if (code != "en" || entry.starts_with("en"))
        return code;
    }
  }
  return language_of_locale(locale_name);
}

std::filesystem::path catalogue_directory() {
  std::error_code ec;
  if (const char* data = environment("CLOTHLAB_DATA_DIR");
      data != nullptr && std::filesystem::is_directory(std::filesystem::path(data) / "locale", ec))
    return std::filesystem::path(data) / "locale";
  if (const std::filesystem::path program = executable_path(); !program.empty()) {
    for (const auto& beside : {program.parent_path() / "share" / "clothlab" / "locale",
                               program.parent_path() / "locale"}) {
      if (std::filesystem::is_directory(beside, ec))
        return beside;
    }
  }
  return CLOTHLAB_CATALOGUE_DIR;
}

void start_messages() {
#if !defined(__EMSCRIPTEN__)
  bindtextdomain(text_domain, catalogue_directory().string().c_str());
  bind_textdomain_codeset(text_domain, "UTF-8");
  set_messages_locale();
#endif
  catalogues_open = true;
  set_language(language_from_environment());
}

bool set_language(std::string_view code) {
  const language* found = find_language(code);
  if (found == nullptr)
    return false;
  chosen = found->code;
#if defined(__EMSCRIPTEN__)
  catalogue = nullptr;
  if (chosen != "en") {
    auto [entry, first_time] = loaded.try_emplace(chosen);
    std::string error;
    if (first_time && !entry->second.load(catalogue_file(chosen), error))
      std::fprintf(stderr, "clothlab: %s\n", error.c_str());
    catalogue = &entry->second;
  }
#else
  // The catalogue gettext reads is LANGUAGE's; setting the locale again makes it forget the
  // translations it has looked up in the language before.
  setenv("LANGUAGE", chosen.c_str(), 1);
  if (!messages_locale.empty())
    std::setlocale(LC_MESSAGES, messages_locale.c_str());
#endif
  ++generation;
  return true;
}

std::string_view current_language() {
  return chosen;
}

unsigned language_generation() {
  return generation;
}

}  // namespace clothlab
