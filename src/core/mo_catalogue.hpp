// A compiled message catalogue (GNU gettext's .mo file, what msgfmt makes of po/<lang>.po), read
// whole: the browser build's gettext. Emscripten's C library (musl) has dcngettext, but the one of
// Debian 12's emscripten 3.1.6 reads out of bounds when it looks a text up in a catalogue of the
// page's virtual file system (a memory access out of bounds in __mo_lookup; a ten-line program
// under node does it too). The desktop keeps glibc's (or GNU libintl's) gettext; the tests check
// this reader against it, text by text.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace clothlab {

class mo_catalogue {
 public:
  // Reads `path`; false, with `error` set, for a file that is missing or not a catalogue.
  bool load(const std::filesystem::path& path, std::string& error);

  // The translation of `message`, or nullptr when the catalogue has none (or an empty one).
  const char* find(std::string_view message) const;
  // The form of `singular` / `plural` for the count n, by the catalogue's Plural-Forms, or
  // nullptr when it has no translation.
  const char* find_plural(std::string_view singular, unsigned long n) const;

  std::size_t size() const { return translations_.size(); }
  // The form's index for n by the catalogue's plural expression ("n > 1"; "n != 1" without one).
  unsigned long plural_index(unsigned long n) const;

 private:
  // The catalogue's texts (kept: find() returns pointers into them), by their English (for a
  // text with a plural, its singular), each with its forms.
  std::unordered_map<std::string, std::vector<std::string>> translations_;
  std::string plural_expression_ = "n != 1";
  unsigned long plural_count_ = 2;
};

}  // namespace clothlab
