#include "core/i18n.hpp"

#include <libintl.h>

#include <algorithm>
#include <cctype>
#include <clocale>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

#include "core/executable_path.hpp"

namespace clothlab {
namespace {

constexpr const char* text_domain = "clothlab";  // the catalogues' name: clothlab.mo
// English first: the code's own language, the default.
constexpr language known_languages[] = {{"en", "English"}, {"fr", "Français"}};

std::string_view chosen = "en";
unsigned generation = 0;
bool catalogues_open = false;

const char* environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : nullptr;
}

bool is_c_locale(std::string_view name) {
  return name.empty() || name == "C" || name == "POSIX";
}

#if !defined(__EMSCRIPTEN__)
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
  return dgettext(text_domain, message);
}

const char* trn(const char* singular, const char* plural, unsigned long n) {
  if (chosen == "en" || !catalogues_open)
    return n == 1 ? singular : plural;
  return dngettext(text_domain, singular, plural, n);
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
  return known_languages;
}

std::string language_codes() {
  std::string codes;
  for (const language& l : known_languages)
    codes += (codes.empty() ? "" : ", ") + std::string(l.code);
  return codes;
}

std::string_view language_of_locale(std::string_view locale_name) {
  // "fr_FR.UTF-8@euro", a browser's "fr-FR": the language is what comes before the territory,
  // codeset and modifier.
  std::string code(locale_name.substr(0, locale_name.find_first_of("_-.@")));
  std::transform(code.begin(), code.end(), code.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const language& l : known_languages) {
    if (l.code == code)
      return l.code;
  }
  return known_languages[0].code;
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
  bindtextdomain(text_domain, catalogue_directory().string().c_str());
  bind_textdomain_codeset(text_domain, "UTF-8");
#if !defined(__EMSCRIPTEN__)
  set_messages_locale();
#endif
  catalogues_open = true;
  set_language(language_from_environment());
}

bool set_language(std::string_view code) {
  const auto found = std::find_if(std::begin(known_languages), std::end(known_languages),
                                  [&](const language& l) { return l.code == code; });
  if (found == std::end(known_languages))
    return false;
  chosen = found->code;
  const std::string name(chosen);
#if defined(__EMSCRIPTEN__)
  // musl's gettext reads the catalogue of the messages' locale, whatever its name:
  // <dir>/fr/LC_MESSAGES/clothlab.mo.
  std::setlocale(LC_MESSAGES, name.c_str());
#else
  // The catalogue gettext reads is LANGUAGE's; setting the locale again makes it forget the
  // translations it has looked up in the language before.
  setenv("LANGUAGE", name.c_str(), 1);
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
