// Words in the user's language, numbers in the machine's (docs/translating.md). Every text a
// person reads goes through tr(): GNU gettext's catalogue of the chosen language (po/<lang>.po,
// compiled into locale/<lang>/LC_MESSAGES/clothlab.mo at build time), or the English text itself.
// The language comes from the locale (LANGUAGE, LC_ALL, LC_MESSAGES, LANG), and --lang or the
// window's panel override it. Only the messages' category changes: LC_NUMERIC stays "C", so every
// number read or written (CSV, OBJ, JSON, the command line) keeps its decimal point.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace clothlab {

// The text `message` (English, as written in the code) in the chosen language; `message` itself
// in English or when the catalogue has no translation of it.
// (format_arg: the compiler checks printf(tr("%d steps"), n) against the English format.)
[[gnu::format_arg(1)]] const char* tr(const char* message);
// The same for a text about a count n: the singular or the plural form, as the language counts.
[[gnu::format_arg(1), gnu::format_arg(2)]] const char* trn(const char* singular, const char* plural,
                                                           unsigned long n);
// ": " in the user's language, between a thing and what is said of it: "--dt 0: must be ...".
// (French puts a no-break space before the colon.)
const char* colon();
// Marks a text for the catalogue where it is written (a table of constants) and translated
// later, where it is shown, with tr(): returns it unchanged.
constexpr const char* N_(const char* message) {
  return message;
}

// printf's formatting into a std::string, for messages made of a translated format string:
// format(tr("diverged at step %ld"), step).
[[gnu::format(printf, 1, 2)]] std::string format(const char* format_string, ...);

// The languages clothlab speaks: English (the code's own), then one per catalogue built from po/
// (catalogue_directory()/<code>/), each named by its catalogue's translation of "English".
struct language {
  std::string_view code;  // "en", "fr": the --lang value, the catalogue's folder
  std::string_view name;  // in the language itself: "English", "Français"
};
std::span<const language> languages();
// "en, fr", for the messages that list them.
std::string language_codes();

// The language a locale name asks for: "fr_FR.UTF-8", "fr_CA", "fr", a browser's "fr-FR" -> "fr";
// English for "C", "POSIX", an empty name or a language clothlab does not speak.
std::string_view language_of_locale(std::string_view locale_name);
// The language of the environment, as gettext reads it: LANGUAGE's first entry (unless the locale
// is C), else the first set of LC_ALL, LC_MESSAGES, LANG; English when none names a language
// clothlab speaks.
std::string_view language_from_environment();

// Where the catalogues are (locale/<lang>/LC_MESSAGES/clothlab.mo), found as the shaders are:
// $CLOTHLAB_DATA_DIR/locale if it exists, else beside the program (share/clothlab/locale for an
// installed copy, locale/ in the build folder), else the build folder fixed at build time.
std::filesystem::path catalogue_directory();

// Opens the catalogues (catalogue_directory()) and chooses the environment's language. Called
// first in each program's main; until then, and without catalogues, every text is English.
void start_messages();
// Chooses the language (one of languages()' codes); false, changing nothing, for another code.
// The window's panel may change it at any time: tr() answers in the new language from then on.
bool set_language(std::string_view code);
std::string_view current_language();
// The language changes counted: whoever keeps translated texts keeps them while this is unchanged.
unsigned language_generation();

}  // namespace clothlab
