// The language choice (core/i18n.hpp): from the locale's names, the environment's variables in
// gettext's order, --lang's codes; and the catalogue read in the language chosen, switched at run
// time as the window's panel does, with the numbers' locale left alone.
#include <gtest/gtest.h>

#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

TEST(LanguageOfLocale, TakesTheLanguageBeforeTheTerritoryCodesetAndModifier) {
  EXPECT_EQ(language_of_locale("fr_FR.UTF-8"), "fr");
  EXPECT_EQ(language_of_locale("fr_CA"), "fr");
  EXPECT_EQ(language_of_locale("fr"), "fr");
  EXPECT_EQ(language_of_locale("fr_BE@euro"), "fr");
  EXPECT_EQ(language_of_locale("fr-FR"), "fr");  // a browser's
  EXPECT_EQ(language_of_locale("FR_fr.utf8"), "fr");
}

TEST(LanguageOfLocale, IsEnglishForTheCLocaleAndForLanguagesClothlabDoesNotSpeak) {
  EXPECT_EQ(language_of_locale("C"), "en");
  EXPECT_EQ(language_of_locale("C.UTF-8"), "en");
  EXPECT_EQ(language_of_locale("POSIX"), "en");
  EXPECT_EQ(language_of_locale(""), "en");
  EXPECT_EQ(language_of_locale("de_DE.UTF-8"), "en");
  EXPECT_EQ(language_of_locale("en_GB.UTF-8"), "en");
}

// The environment, set for one test and restored after it.
class environment : public ::testing::Test {
 protected:
  static constexpr const char* names[] = {"LANGUAGE", "LC_ALL", "LC_MESSAGES", "LANG"};
  void SetUp() override {
    for (const char* name : names) {
      const char* value = std::getenv(name);
      saved_.emplace_back(value != nullptr, value != nullptr ? value : "");
      unsetenv(name);
    }
  }
  void TearDown() override {
    for (std::size_t i = 0; i < saved_.size(); ++i) {
      if (saved_[i].first)
        setenv(names[i], saved_[i].second.c_str(), 1);
      else
        unsetenv(names[i]);
    }
  }
  std::vector<std::pair<bool, std::string>> saved_;
};

TEST_F(environment, NothingSetIsEnglish) {
  EXPECT_EQ(language_from_environment(), "en");
}

TEST_F(environment, LangAloneChoosesTheLanguage) {
  setenv("LANG", "fr_FR.UTF-8", 1);
  EXPECT_EQ(language_from_environment(), "fr");
}

TEST_F(environment, LcAllComesBeforeLcMessagesWhichComesBeforeLang) {
  setenv("LANG", "fr_FR.UTF-8", 1);
  setenv("LC_MESSAGES", "C", 1);
  EXPECT_EQ(language_from_environment(), "en");
  setenv("LC_ALL", "fr_CA.UTF-8", 1);
  EXPECT_EQ(language_from_environment(), "fr");
}

TEST_F(environment, LanguageComesFirstUnlessTheLocaleIsC) {
  setenv("LANG", "en_US.UTF-8", 1);
  setenv("LANGUAGE", "fr", 1);
  EXPECT_EQ(language_from_environment(), "fr");
  setenv("LANG", "C", 1);  // gettext ignores LANGUAGE in the C locale
  EXPECT_EQ(language_from_environment(), "en");
}

TEST_F(environment, LanguageListsPreferencesAndTheFirstSpokenOneIsTaken) {
  setenv("LANG", "de_DE.UTF-8", 1);
  setenv("LANGUAGE", "de:fr_CA:en", 1);
  EXPECT_EQ(language_from_environment(), "fr");
  setenv("LANGUAGE", "en_GB:fr", 1);
  EXPECT_EQ(language_from_environment(), "en");
}

TEST(Languages, EnglishFirstThenTheCatalogues) {
  ASSERT_GE(languages().size(), 2u);
  EXPECT_EQ(languages()[0].code, "en");
  EXPECT_EQ(language_codes().substr(0, 4), "en, ");
  EXPECT_NE(language_codes().find("fr"), std::string::npos);
}

TEST(SetLanguage, RefusesACodeItDoesNotKnowAndKeepsTheLanguage) {
  start_messages();
  ASSERT_TRUE(set_language("en"));
  EXPECT_FALSE(set_language("de"));
  EXPECT_FALSE(set_language(""));
  EXPECT_EQ(current_language(), "en");
}

// The French catalogue, compiled at build time (po/fr.po -> build/locale), read in the process,
// then English again, then French: as the window's panel switches (tr answers at once).
TEST(Catalogue, TranslatesInTheChosenLanguageAndSwitchesAtRunTime) {
  start_messages();
  ASSERT_TRUE(set_language("fr"));
  EXPECT_STREQ(tr("Q8 springs: three stiffnesses"), "Q8 ressorts\u00a0: trois raideurs")
      << "the French catalogue was not read from " << catalogue_directory();
  EXPECT_STREQ(trn("%d step, each:", "%d steps, each:", 1), "%d pas, chacun\u00a0:");
  EXPECT_STREQ(colon(), "\u00a0: ");
  const unsigned before = language_generation();
  ASSERT_TRUE(set_language("en"));
  EXPECT_NE(language_generation(), before);
  EXPECT_STREQ(tr("Q8 springs: three stiffnesses"), "Q8 springs: three stiffnesses");
  EXPECT_STREQ(trn("%d step, each:", "%d steps, each:", 2), "%d steps, each:");
  ASSERT_TRUE(set_language("fr"));
  EXPECT_STREQ(tr("Q9 ground"), "Q9 sol");
  EXPECT_STREQ(tr("a text the catalogue does not have"), "a text the catalogue does not have");
  set_language("en");
}

// Words in the user's language, numbers in the machine's: whatever the language, the numbers'
// category stays "C" (CSV, OBJ, the command line's values).
TEST(Catalogue, LeavesTheNumbersInTheCLocale) {
  start_messages();
  ASSERT_TRUE(set_language("fr"));
  EXPECT_STREQ(std::setlocale(LC_NUMERIC, nullptr), "C");
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 0.5);
  EXPECT_STREQ(text, "0.5");
  EXPECT_EQ(format("%g", 0.002), "0.002");
  set_language("en");
}

}  // namespace
}  // namespace clothlab
