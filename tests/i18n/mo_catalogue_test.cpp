// The browser's reader of the compiled catalogues (core/mo_catalogue.hpp) against glibc's gettext,
// text by text of the template, and the plural rules of languages with three forms.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/i18n.hpp"
#include "core/mo_catalogue.hpp"

namespace clothlab {
namespace {

// The msgids (and msgid_plurals) of po/clothlab.pot, written one a line (--no-wrap).
struct template_text {
  std::string id, plural;
};
std::vector<template_text> template_texts() {
  std::ifstream in(std::string(CLOTHLAB_SOURCE_DIR) + "/po/clothlab.pot");
  std::vector<template_text> texts;
  std::string line;
  const auto unquote = [](const std::string& quoted) {
    std::string text;
    for (std::size_t i = 1; i + 1 < quoted.size(); ++i) {
      if (quoted[i] == '\\' && i + 2 < quoted.size()) {
        const char c = quoted[++i];
        text += c == 'n' ? '\n' : c == 't' ? '\t' : c;
      } else {
        text += quoted[i];
      }
    }
    return text;
  };
  while (std::getline(in, line)) {
    if (line.starts_with("msgid \"") && line != "msgid \"\"")
      texts.push_back({unquote(line.substr(6)), ""});
    else if (line.starts_with("msgid_plural \"") && !texts.empty())
      texts.back().plural = unquote(line.substr(13));
  }
  return texts;
}

TEST(MoCatalogue, ReadsEveryTextAsGettextDoes) {
  start_messages();
  ASSERT_TRUE(set_language("fr"));
  mo_catalogue catalogue;
  std::string error;
  ASSERT_TRUE(catalogue.load(catalogue_directory() / "fr" / "LC_MESSAGES" / "clothlab.mo", error))
      << error;
  const std::vector<template_text> texts = template_texts();
  ASSERT_GT(texts.size(), 400u);
  for (const template_text& t : texts) {
    if (t.plural.empty()) {
      const char* read = catalogue.find(t.id);
      EXPECT_STREQ(read != nullptr ? read : t.id.c_str(), tr(t.id.c_str())) << t.id;
    } else {
      for (unsigned long n : {0ul, 1ul, 2ul, 7ul}) {
        const char* read = catalogue.find_plural(t.id, n);
        EXPECT_STREQ(read != nullptr ? read : (n == 1 ? t.id : t.plural).c_str(),
                     trn(t.id.c_str(), t.plural.c_str(), n))
            << t.id << " for n = " << n;
      }
    }
  }
  EXPECT_EQ(catalogue.find("a text the catalogue does not have"), nullptr);
  set_language("en");
}

TEST(MoCatalogue, RefusesAFileThatIsNotACatalogue) {
  mo_catalogue catalogue;
  std::string error;
  EXPECT_FALSE(catalogue.load(std::string(CLOTHLAB_SOURCE_DIR) + "/po/fr.po", error));
  EXPECT_NE(error.find("not a compiled message catalogue"), std::string::npos) << error;
  EXPECT_FALSE(catalogue.load("/no/such/catalogue.mo", error));
  EXPECT_NE(error.find("cannot read"), std::string::npos) << error;
}

// French: one form for 0 and 1, another above (nplurals=2; plural=(n > 1)).
TEST(MoCatalogue, FrenchCountsZeroAndOneAsSingular) {
  mo_catalogue catalogue;
  std::string error;
  ASSERT_TRUE(catalogue.load(catalogue_directory() / "fr" / "LC_MESSAGES" / "clothlab.mo", error))
      << error;
  EXPECT_EQ(catalogue.plural_index(0), 0u);
  EXPECT_EQ(catalogue.plural_index(1), 0u);
  EXPECT_EQ(catalogue.plural_index(2), 1u);
  EXPECT_EQ(catalogue.plural_index(1000), 1u);
}

// Polish's three forms (one; few: 2-4, 22-24, ...; many: 0, 5-21, 25-31, ...), compiled here by
// msgfmt: the header's rule is C, with ?:, &&, ||, %.
TEST(MoCatalogue, EvaluatesThePluralRuleOfItsHeader) {
  const std::string folder = ::testing::TempDir();
  const std::string po = folder + "/clothlab-pl.po", mo = folder + "/clothlab-pl.mo";
  std::ofstream(po) << "msgid \"\"\nmsgstr \"\"\n\"Content-Type: text/plain; charset=UTF-8\\n\"\n"
                       "\"Plural-Forms: nplurals=3; plural=(n==1 ? 0 : n%10>=2 && n%10<=4 && "
                       "(n%100<10 || n%100>=20) ? 1 : 2);\\n\"\n\n"
                       "msgid \"%d step\"\nmsgid_plural \"%d steps\"\n"
                       "msgstr[0] \"%d krok\"\nmsgstr[1] \"%d kroki\"\nmsgstr[2] \"%d kroków\"\n";
  ASSERT_EQ(std::system(("msgfmt -o '" + mo + "' '" + po + "'").c_str()), 0) << "msgfmt " << po;
  mo_catalogue catalogue;
  std::string error;
  ASSERT_TRUE(catalogue.load(mo, error)) << error;
  const std::pair<unsigned long, unsigned long> expected[] = {
      {1, 0}, {2, 1}, {4, 1}, {5, 2}, {12, 2}, {14, 2}, {22, 1}, {25, 2}, {0, 2}, {104, 1}};
  for (const auto& [n, form] : expected)
    EXPECT_EQ(catalogue.plural_index(n), form) << "n = " << n;
  EXPECT_STREQ(catalogue.find_plural("%d step", 5), "%d kroków");
  EXPECT_STREQ(catalogue.find_plural("%d step", 3), "%d kroki");
}

}  // namespace
}  // namespace clothlab
