// The lab runner's protocol: what a question test (the checker) and the runner (the student's
// code, in a process of its own) say to each other, one line each way per request, on the
// runner's file descriptor 3 (a socket pair: the student's prints go to its standard output and
// error, which are another pipe).
//
//   request:  <operation> <arguments...>\n
//   answer:   ok <results...>\n     or     error <what, hex>\n   (an exception of the student's
//   code)
//
// Numbers are written in their shortest exact decimal form (std::to_chars), so that a double
// crosses unchanged; parameter structs cross as their bytes in hex (the checker and the runner
// are built from the same headers). A particle state is
//   <grid size N (0: not a cloth)> <count n> <3n positions> <3n velocities> <3n forces> <n fixed>
// Both sides use this header; neither trusts the other's numbers more than it must: the checker
// reads the runner's answers with bounds (an answer is data, never a verdict).
#pragma once

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace clothlab::lab_protocol {

// The runner's answer channel (the checker's end of the socket pair is passed as this fd).
inline constexpr int channel_fd = 3;

inline void put(std::string& line, double x) {
  char buffer[40];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  line += ' ';
  line.append(buffer, end);
}

inline void put(std::string& line, long long n) {
  char buffer[24];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, n).ptr;
  line += ' ';
  line.append(buffer, end);
}

inline void put_word(std::string& line, std::string_view word) {
  line += ' ';
  line += word;
}

inline void put_hex(std::string& line, const void* bytes, std::size_t size) {
  static const char digits[] = "0123456789abcdef";
  line += ' ';
  if (size == 0)
    line += '-';
  const auto* b = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < size; ++i) {
    line += digits[b[i] >> 4];
    line += digits[b[i] & 15];
  }
}

inline void put_text(std::string& line, std::string_view text) {
  put_hex(line, text.data(), text.size());
}

// A struct of plain values (cloth_parameters, ...), byte for byte.
template <class T>
void put_struct(std::string& line, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  put_hex(line, &value, sizeof value);
}

// Reads the words of one line in order; any malformed or missing word makes ok() false (and
// every later read returns 0 or empty).
class reader {
 public:
  explicit reader(std::string_view line) : rest_(line) {}

  bool ok() const { return ok_; }
  bool at_end() {
    skip_spaces();
    return rest_.empty();
  }

  std::string_view word() {
    skip_spaces();
    const std::size_t end = std::min(rest_.find(' '), rest_.size());
    const std::string_view w = rest_.substr(0, end);
    rest_.remove_prefix(end);
    if (w.empty())
      ok_ = false;
    return w;
  }

  double number() {
    const std::string_view w = word();
    double x = 0.0;
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), x);
    if (!ok_ || error != std::errc() || end != w.data() + w.size())
      return fail(), 0.0;
    return x;
  }

  long long integer(long long lowest, long long highest) {
    const std::string_view w = word();
    long long n = 0;
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), n);
    if (!ok_ || error != std::errc() || end != w.data() + w.size() || n < lowest || n > highest)
      return fail(), 0;
    return n;
  }

  // At most `limit` bytes.
  std::string text(std::size_t limit) {
    const std::string_view w = word();
    std::string bytes;
    if (!ok_ || w == "-")
      return bytes;
    if (w.size() % 2 != 0 || w.size() / 2 > limit)
      return fail(), bytes;
    for (std::size_t i = 0; i < w.size(); i += 2) {
      const int high = digit(w[i]), low = digit(w[i + 1]);
      if (high < 0 || low < 0)
        return fail(), std::string();
      bytes += static_cast<char>(high * 16 + low);
    }
    return bytes;
  }

  template <class T>
  T parse_struct() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value{};
    const std::string bytes = text(sizeof(T));
    if (ok_ && bytes.size() == sizeof(T))
      std::memcpy(&value, bytes.data(), sizeof(T));
    else
      fail();
    return value;
  }

  void fail() {
    ok_ = false;
    rest_ = {};
  }

 private:
  std::string_view rest_;
  bool ok_ = true;

  void skip_spaces() {
    while (!rest_.empty() && rest_.front() == ' ')
      rest_.remove_prefix(1);
  }
  static int digit(char c) {
    if (c >= '0' && c <= '9')
      return c - '0';
    if (c >= 'a' && c <= 'f')
      return c - 'a' + 10;
    return -1;
  }
};

// The particle arrays as they cross (the same fields as clothlab::particle_system).
struct particle_arrays {
  int grid_size = 0;  // N of a cloth; 0 for the chain and a bare particle set
  std::vector<double> position, velocity, force;
  std::vector<std::uint8_t> is_fixed;
};

inline void put_particles(std::string& line, int grid_size, const std::vector<double>& position,
                          const std::vector<double>& velocity, const std::vector<double>& force,
                          const std::vector<std::uint8_t>& is_fixed) {
  put(line, static_cast<long long>(grid_size));
  put(line, static_cast<long long>(is_fixed.size()));
  for (const std::vector<double>* array : {&position, &velocity, &force})
    for (double x : *array)
      put(line, x);
  for (std::uint8_t f : is_fixed)
    put(line, static_cast<long long>(f));
}

// At most max_count particles; the three arrays must hold 3n numbers each (the sender's own
// arrays: a sender whose arrays disagree with their count is wrong, and read as malformed).
inline particle_arrays read_particles(reader& in, std::size_t max_count) {
  particle_arrays p;
  p.grid_size = static_cast<int>(in.integer(0, 1 << 15));
  const std::size_t n = static_cast<std::size_t>(in.integer(0, static_cast<long long>(max_count)));
  for (std::vector<double>* array : {&p.position, &p.velocity, &p.force}) {
    array->resize(3 * n);
    for (double& x : *array)
      x = in.number();
  }
  p.is_fixed.resize(n);
  for (std::uint8_t& f : p.is_fixed)
    f = static_cast<std::uint8_t>(in.integer(0, 255));
  return p;
}

}  // namespace clothlab::lab_protocol
