// The command line in the user's language (docs/cli.md, --lang; docs/translating.md): the locale
// or --lang choose the words of --help and of every message; the numbers of every file written
// and of every value read stay the machine's (a French locale must not write 0,5 for 0.5).
#include "cli_support.hpp"

namespace clothlab_cli_test {
namespace {

// clothlab in `folder` with the environment's language variables cleared (the C locale, as
// English as can be) and then `environment`'s.
ended run_in(const fs::path& folder, const arguments& args,
             const std::vector<std::string>& environment = {}) {
  spawn_settings how{clothlab_command(args), folder};
  how.environment = {"LANGUAGE=", "LC_ALL=", "LC_MESSAGES=", "LANG=C"};
  how.environment.insert(how.environment.end(), environment.begin(), environment.end());
  return wait_for(spawn(how), folder);
}

bool holds(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(cli, TheLocaleChoosesTheLanguageOfTheMessages) {
  const ended english = run_in(work(), {"--headless", "--dt", "0"});
  EXPECT_TRUE(english.exited && english.code == 2) << english.err;
  EXPECT_TRUE(holds(english.err, "--dt 0: must be between 1e-09 and 10 s")) << english.err;

  const ended french = run_in(work(), {"--headless", "--dt", "0"}, {"LANG=fr_FR.UTF-8"});
  EXPECT_TRUE(french.exited && french.code == 2) << french.err;
  // (French puts a no-break space before a colon.)
  EXPECT_TRUE(holds(french.err, "--dt 0\u00a0: doit être entre 1e-09 et 10 s")) << french.err;

  for (const char* variable : {"LC_ALL=fr_CA.UTF-8", "LC_MESSAGES=fr", "LANGUAGE=fr"}) {
    // (LANGUAGE counts outside the C locale only, as for gettext)
    const ended also =
        run_in(work(), {"--headless", "--steps", "-1"}, {variable, "LANG=en_US.UTF-8"});
    EXPECT_TRUE(holds(also.err, "doit être entre")) << variable << ": " << also.err;
  }
}

TEST_F(cli, LangOverridesTheLocale) {
  const ended english =
      run_in(work(), {"--lang", "en", "--headless", "--dt", "0"}, {"LANG=fr_FR.UTF-8"});
  EXPECT_TRUE(holds(english.err, "--dt 0: must be between")) << english.err;
  const ended french = run_in(work(), {"--headless", "--lang=fr", "--dt", "0"});
  EXPECT_TRUE(holds(french.err, "doit être entre")) << french.err;
  // CLI11's own messages too.
  const ended unknown = run_in(work(), {"--lang", "fr", "--no-such-option"});
  EXPECT_TRUE(unknown.exited && unknown.code == 2) << unknown.err;
  EXPECT_TRUE(holds(unknown.err, "argument inattendu\u00a0: --no-such-option (voir --help)"))
      << unknown.err;
}

TEST_F(cli, AnUnknownLanguageIsRefusedNamingItAndTheLanguages) {
  const ended refused = run_in(work(), {"--lang", "de", "--headless"});
  EXPECT_TRUE(refused.exited && refused.code == 2) << refused.err;
  EXPECT_TRUE(holds(refused.err, "--lang de")) << refused.err;
  EXPECT_TRUE(holds(refused.err, "en, fr")) << refused.err;
  EXPECT_EQ(count_lines(refused.err), 1u) << refused.err;
  EXPECT_EQ(read_file(root() / "stdout.txt"), "");
  EXPECT_EQ(run_in(work(), {"--lang", "", "--headless"}).code, 2);
}

TEST_F(cli, HelpIsInTheChosenLanguage) {
  const ended english = run_in(work(), {"--help"});
  const std::string english_help = read_file(root() / "stdout.txt");
  EXPECT_TRUE(english.exited && english.code == 0) << english.err;
  EXPECT_TRUE(holds(english_help, "Print this help message and exit")) << english_help;
  EXPECT_TRUE(holds(english_help, "--lang")) << english_help;

  const ended french = run_in(work(), {"--lang", "fr", "--help"});
  const std::string help = read_file(root() / "stdout.txt");
  EXPECT_TRUE(french.exited && french.code == 0) << french.err;
  for (const char* words : {"Utilisation", "Affiche cette aide et quitte", "Lance sans fenêtre",
                            "Raideur des ressorts de courbure du tissu", "--K-bend"}) {
    EXPECT_TRUE(holds(help, words)) << words << " is not in:\n" << help;
  }
  EXPECT_FALSE(holds(help, "Print this help message")) << help;
}

// Every file a run writes, byte for byte the same whatever the language: the states, the
// energies, the OBJ, the stability map; and the values read (0.5, 1e-3) read the same.
void expect_same_outputs(const fs::path& base, const std::vector<std::string>& french_locale) {
  for (const char* name : {"en", "fr"}) {
    fs::create_directories(base / name / "run");
    const std::vector<std::string> environment =
        std::string(name) == "fr" ? french_locale : std::vector<std::string>{};
    const ended run = run_in(
        base / name / "run",
        {"--headless", "--N", "5", "--steps", "40", "--dt", "0.0015", "--wind-strength", "2.5",
         "--wind-dir", "0.5,1,0.25", "--csv", "s.csv", "--energy-csv", "e.csv", "--obj", "c.obj"},
        environment);
    EXPECT_TRUE(run.exited && run.code == 0) << name << ": " << run.err;
    const ended sweep = run_in(base / name / "run",
                               {"--headless", "--stage", "spring", "--sweep", "m.csv", "--sweep-dt",
                                "0.01,0.5", "--sweep-K", "10,1e3", "--sweep-time", "0.5"},
                               environment);
    EXPECT_TRUE(sweep.exited && sweep.code == 0) << name << ": " << sweep.err;
  }
  for (const char* file : {"s.csv", "e.csv", "c.obj", "m.csv"}) {
    const std::string english = read_file(base / "en" / "run" / file);
    EXPECT_FALSE(english.empty()) << file;
    EXPECT_EQ(read_file(base / "fr" / "run" / file), english) << file << " differs in French";
  }
  EXPECT_TRUE(holds(read_file(base / "fr" / "run" / "s.csv"), "0.0015,")) << "dt as written";
}

TEST_F(cli, AFrenchLocaleWritesTheSameBytes) {
  expect_same_outputs(root() / "by-name", {"LANG=fr_FR.UTF-8", "LC_ALL=fr_FR.UTF-8"});
}

// The same with a French locale that exists, made here (localedef, into a folder of the test:
// LOCPATH), whose decimal separator is a comma: clothlab takes its messages' category and leaves
// the numbers' alone.
TEST_F(cli, AnInstalledFrenchLocaleWritesTheSameBytes) {
  const fs::path locales = root() / "locales";
  fs::create_directories(locales);
  const std::string make =
      "localedef -i fr_FR -f UTF-8 '" + (locales / "fr_FR.UTF-8").string() + "' >/dev/null 2>&1";
  if (std::system(make.c_str()) != 0)
    GTEST_SKIP() << "localedef cannot make fr_FR.UTF-8 here (Debian's package locales)";
  const std::vector<std::string> french = {"LOCPATH=" + locales.string(), "LC_ALL=fr_FR.UTF-8"};
  // The locale is real: a program that takes it whole writes 0,5.
  const std::string printf_in_french = "env LOCPATH='" + locales.string() +
                                       "' LC_ALL=fr_FR.UTF-8 /usr/bin/printf '%.1f' 0.5 > '" +
                                       (root() / "printf.txt").string() + "'";
  ASSERT_EQ(std::system(printf_in_french.c_str()), 0);
  ASSERT_EQ(read_file(root() / "printf.txt"), "0,5") << "the locale made is not French";
  expect_same_outputs(root() / "installed", french);
  const ended message = run_in(work(), {"--headless", "--dt", "0"}, french);
  EXPECT_TRUE(holds(message.err, "doit être entre 1e-09 et 10 s")) << message.err;
}

}  // namespace
}  // namespace clothlab_cli_test
