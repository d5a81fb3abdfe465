// Bad usage and the edges of every input (docs/cli.md "Exit status", docs/limits.md): exit 2
// with one line naming the option and nothing written, the ranges of every value, empty values,
// control characters, and divergence (exit 3, the CSV up to it).
#include "cli_support.hpp"

namespace {

using namespace clothlab_cli_test;

// Bad usage: exit 2, exactly one line on stderr naming the option, nothing written.
struct bad_usage {
  std::string label;
  arguments args;
  std::string option;  // what the error line must name
};

void PrintTo(const bad_usage& c, std::ostream* os) {
  *os << c.label;
}

class cli_refuses : public cli, public ::testing::WithParamInterface<bad_usage> {};

TEST_P(cli_refuses, BadUsage) {
  arguments args = {"--headless", "--csv", "out.csv", "--obj", "out.obj"};
  const arguments with_defaults = headless_run(GetParam().args);
  args.insert(args.end(), with_defaults.begin() + 1, with_defaults.end());
  const run_result result = run(args);
  EXPECT_EQ(result.exit_code, 2) << join(args) << "\nstderr: " << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\nstderr: " << result.err;
  EXPECT_FALSE(result.err.empty() || result.err.back() != '\n') << result.err;
  EXPECT_NE(result.err.find(GetParam().option), std::string::npos)
      << join(args) << "\nstderr does not name " << GetParam().option << ": " << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
}

INSTANTIATE_TEST_SUITE_P(
    EveryKindOfBadInput, cli_refuses,
    ::testing::Values(
        bad_usage{"UnknownOption", {"--frobnicate", "3"}, "--frobnicate"},
        bad_usage{"MissingValue", {"--dt"}, "--dt"},
        bad_usage{"MalformedNumber", {"--dt", "abc"}, "--dt"},
        bad_usage{"TrailingGarbage", {"--dt", "0.01x"}, "--dt"},
        bad_usage{"NonIntegerGridSize", {"--N", "2.5"}, "--N"},
        bad_usage{"ZeroTimeStep", {"--dt", "0"}, "--dt"},
        bad_usage{"NegativeTimeStep", {"--dt", "-1"}, "--dt"},
        bad_usage{"GridOfOne", {"--N", "1"}, "--N"},
        bad_usage{"NegativeSteps", {"--steps", "-5"}, "--steps"},
        bad_usage{"ZeroMass", {"--mass", "0"}, "--mass"},
        bad_usage{"NegativeMass", {"--mass", "-1"}, "--mass"},
        bad_usage{"ZeroCsvEvery", {"--csv-every", "0"}, "--csv-every"},
        bad_usage{"EmptyChain", {"--stage", "coupled", "--chain", "0"}, "--chain"},
        bad_usage{"ZeroWindDirection", {"--wind-dir", "0,0,0"}, "--wind-dir"},
        bad_usage{"TwoComponentWindDirection", {"--wind-dir", "1,2"}, "--wind-dir"},
        bad_usage{"UnknownStage", {"--stage", "foo"}, "--stage"},
        bad_usage{"StageNumberOutOfRange", {"--stage", "3"}, "--stage"},
        bad_usage{"PinsNumberOutOfRange", {"--pins", "2"}, "--pins"},
        bad_usage{"UnknownIntegrator", {"--integrator", "foo"}, "--integrator"},
        bad_usage{"UnknownPins", {"--pins", "foo"}, "--pins"},
        bad_usage{"UnknownBackend", {"--backend", "foo"}, "--backend"},
        bad_usage{"MalformedGroundZ", {"--ground-z", "abc"}, "--ground-z"},
        bad_usage{"NaNTimeStep", {"--dt", "nan"}, "--dt"},
        bad_usage{"InfiniteTimeStep", {"--dt", "inf"}, "--dt"},
        bad_usage{"NaNStiffness", {"--K", "nan"}, "--K"},
        bad_usage{"InfiniteStructuralStiffness", {"--K-struct", "inf"}, "--K-struct"},
        bad_usage{"InfiniteDamping", {"--mu", "inf"}, "--mu"},
        bad_usage{"NaNGravity", {"--gravity", "nan"}, "--gravity"},
        bad_usage{"MinusInfiniteMass", {"--mass", "-inf"}, "--mass"},
        bad_usage{"InfiniteSize", {"--size", "inf"}, "--size"},
        bad_usage{"NaNWindStrength", {"--wind-strength", "nan"}, "--wind-strength"},
        bad_usage{"NaNWindDirection", {"--wind-dir", "nan,0,1"}, "--wind-dir"},
        bad_usage{"NaNGroundZ", {"--ground-z", "nan"}, "--ground-z"},
        bad_usage{"NaNGroundFriction", {"--ground-friction", "nan"}, "--ground-friction"},
        bad_usage{
            "CpuOnlyIntegratorOnGpu", {"--backend", "gpu", "--integrator", "rk4"}, "--integrator"},
        bad_usage{"UnknownScaling", {"--scaling", "foo"}, "--scaling"},
        bad_usage{"ReferenceGridOfOne", {"--reference-N", "1"}, "--reference-N"},
        bad_usage{"DampingFactorNegative", {"--mu", "1000"}, "--mu"},
        bad_usage{"SweepDtWithoutSweep", {"--sweep-dt", "0.1,0.2"}, "--sweep-dt"},
        bad_usage{
            "MalformedSweepList", {"--sweep", "m.csv", "--sweep-dt", "0.1,abc"}, "--sweep-dt"},
        bad_usage{
            "SweepRangeWithoutCount", {"--sweep", "m.csv", "--sweep-dt", "0.1:0.2"}, "--sweep-dt"},
        bad_usage{"SweepNOnTheSingleSpring",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-N", "2,3"},
                  "--sweep-N"},
        bad_usage{"ZeroSweepTime", {"--sweep", "m.csv", "--sweep-time", "0"}, "--sweep-time"},
        // The bounds of docs/limits.md, each message naming the option.
        bad_usage{"HugeMassD1", {"--stage", "cloth", "--mass", "1e308"}, "--mass 1e+308"},
        bad_usage{"HugeTimeStepD2", {"--dt", "1e308"}, "--dt 1e+308"},
        bad_usage{"TimeStepAboveTenSeconds", {"--dt", "15"}, "--dt 15"},
        bad_usage{"SubnormalTimeStepD9", {"--dt", "1e-320"}, "between 1e-09 and 10 s"},
        bad_usage{"TimeStepOverflowingADouble", {"--dt", "1e999"}, "--dt"},
        bad_usage{"HugeSizeD3", {"--size", "1.7976931348623157e308"}, "--size"},
        bad_usage{"LargeSizeD4", {"--size", "1e300"}, "between 0.001 and 1000 m"},
        bad_usage{"SubnormalSizeD4", {"--size", "1e-320"}, "--size"},
        bad_usage{"HugeStiffness", {"--K-struct", "2e9"}, "--K-struct 2e+09"},
        bad_usage{"HugeSpringStiffness", {"--stage", "spring", "--K", "1e10"}, "--K 1e+10"},
        bad_usage{"HugeGravity", {"--gravity", "1e4"}, "--gravity 10000"},
        bad_usage{"HugeWindStrength", {"--wind-strength", "-1e7"}, "--wind-strength"},
        bad_usage{"HugeWindDirection", {"--wind-dir", "1e300,0,0"}, "--wind-dir"},
        bad_usage{"SubnormalWindDirectionD9", {"--wind-dir", "1e-320,0,0"}, "at least 1e-06"},
        bad_usage{"GroundFarAway", {"--ground-z", "-1e4"}, "--ground-z -10000"},
        bad_usage{"TooManySteps", {"--steps", "2000000000"}, "--steps"},
        bad_usage{"HugeSizeInTheMiddleOfASweepD5",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-K", "1e-300:1e300:3"},
                  "--sweep-K 1e+300"},
        bad_usage{"SweepListValueOutOfRangeD5",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-dt", "0.01,50,0.02"},
                  "--sweep-dt 50"},
        bad_usage{"TinySweepTimeStepD6",
                  {"--stage", "spring", "--sweep", "m.csv", "--sweep-dt", "1e-300"},
                  "--sweep-dt 1e-300"},
        bad_usage{"BackendOfNoKind", {"--backend", "quantum"}, "--backend"},
        // An option the chosen stage has no use for is refused, naming its stage.
        bad_usage{"GridSizeOnTheSpring", {"--stage", "spring", "--N", "50"}, "--N"},
        bad_usage{"WindOnTheSpring",
                  {"--stage", "spring", "--wind-strength", "5"},
                  "--wind-strength: the cloth's option"},
        bad_usage{"SpringStiffnessOnTheCloth", {"--K", "50"}, "--K: the spring stages'"},
        bad_usage{"ChainOnTheCloth", {"--chain", "5"}, "--chain: the chain's option"},
        bad_usage{"GroundFrictionOnTheSpring",
                  {"--stage", "spring", "--ground-friction", "2"},
                  "--ground-friction"},
        bad_usage{"UnknownContext", {"--gl", "vulkan"}, "--gl"},
        bad_usage{"ThreadsWithoutParallel", {"--threads", "2"}, "--threads"},
        bad_usage{"StartOnTheCloth", {"--start", "1d"}, "--start"},
        bad_usage{"StartUnknown", {"--stage", "spring", "--start", "2d"}, "--start"},
        // BEGIN TEACHER
        bad_usage{"TooManyThreads",
                  {"--backend", "cpu-parallel", "--threads", "100000"},
                  "--threads 100000"},
        // END TEACHER
        // COPY| bad_usage{"ParallelPathInTheTeachersCopy",
        // COPY|           {"--backend", "cpu-parallel"},
        // COPY|           "--backend cpu-parallel: the parallel CPU path (--backend cpu-parallel) is in the teacher's copy"},
        bad_usage{"ParallelSpring",
                  {"--stage", "spring", "--backend", "cpu-parallel"},
                  "--backend cpu-parallel"},
        bad_usage{"ComputeWithRk4",
                  {"--backend", "gpu-compute", "--integrator", "rk4"},
                  "--integrator rk4"},
        // XPBD's options without XPBD; in the teacher's copy, its ranges, the fragment path that
        // is mass-spring only and the damping factor of a substep (1 - mu h, h = dt / substeps).
        bad_usage{"XpbdOptionWithoutXpbd", {"--xpbd-substeps", "5"}, "--xpbd-substeps: XPBD's"},
        // BEGIN TEACHER
        bad_usage{"XpbdOnTheFragmentPath",
                  {"--integrator", "xpbd", "--backend", "gpu"},
                  "--integrator xpbd: the gpu path"},
        bad_usage{"XpbdWithoutSubsteps",
                  {"--integrator", "xpbd", "--xpbd-substeps", "0"},
                  "--xpbd-substeps 0"},
        bad_usage{"XpbdTooManyIterations",
                  {"--integrator", "xpbd", "--xpbd-iterations", "1001"},
                  "--xpbd-iterations 1001"},
        bad_usage{"XpbdDampingPastOneOverTheSubstep",
                  {"--integrator", "xpbd", "--dt", "0.1", "--xpbd-substeps", "1", "--mu", "20"},
                  "--mu 20: mu h = 2"},
        // END TEACHER
        // COPY| bad_usage{"XpbdInTheTeachersCopy",
        // COPY|           {"--integrator", "xpbd"},
        // COPY|           "--integrator xpbd: XPBD (--integrator xpbd) is in the teacher's copy"},
        bad_usage{"DragOutsideTheGrid", {"--drag", "9,0:0,0,0"}, "outside the 4 x 4 grid"},
        bad_usage{"DragAPinnedCorner", {"--drag", "3,0:0,0,0"}, "is pinned"},
        bad_usage{"DragWithoutTarget", {"--drag", "1,1"}, "--drag 1,1"},
        bad_usage{"DragFarAway", {"--drag", "1,1:0,0,1e5"}, "--drag"},
        // The particle (KU, KV) is the cloth's: the masses of stages 1 and 2 take the mouse only.
        bad_usage{"DragOnTheChain",
                  {"--stage", "coupled", "--drag", "1,1:0,0,0"},
                  "--drag: the cloth's; use it with --stage cloth"},
        bad_usage{"DragOnTheSpring",
                  {"--stage", "spring", "--drag", "0,1:0,0,0"},
                  "--drag: the cloth's; use it with --stage cloth"},
        bad_usage{"DragStiffnessOutOfRangeOnTheChain",
                  {"--stage", "coupled", "--drag-stiffness", "-5"},
                  "--drag-stiffness -5"},
        bad_usage{"SphereWithoutRadius", {"--sphere", "0,0,0"}, "--sphere"},
        bad_usage{"SphereOfNoRadius", {"--sphere", "0,0,0,0"}, "--sphere 0"},
        bad_usage{"SphereFrictionTooHigh",
                  {"--sphere", "0,0,0,1", "--sphere-friction", "1e4"},
                  "--sphere-friction"},
        bad_usage{"NegativeTearStrain", {"--tear-strain", "-0.1"}, "--tear-strain"},
        bad_usage{"SelfCollisionOnTheGpu",
                  {"--self-collision", "0.01", "--backend", "gpu"},
                  "--self-collision"},
        bad_usage{"SphereOnTheSpring", {"--stage", "spring", "--sphere", "0,0,0,1"}, "--sphere"}),
    [](const ::testing::TestParamInfo<bad_usage>& param_info) { return param_info.param.label; });

// K = 1e6 and dt = 0.1 (w dt = 100, far above 2): the spring explodes. Exit 3, one stderr line
// naming the step s at which the state stopped being finite, and the CSV holds steps 0 .. s-1,
// all finite.
TEST_F(cli, DivergenceExitsThreeAndKeepsEveryFiniteStep) {
  const arguments args = {"--headless", "--stage", "spring", "--K",   "1e6",         "--dt",
                          "0.1",        "--steps", "1000",   "--csv", "diverged.csv"};
  const run_result result = run(args);
  EXPECT_EQ(result.exit_code, 3) << "stderr: " << result.err;
  EXPECT_EQ(count_lines(result.err), 1u) << result.err;
  const csv_file csv = read_csv(work() / "diverged.csv");
  EXPECT_EQ(csv.header, csv_header);
  const std::vector<long> steps = written_steps(csv, 2);
  ASSERT_GE(steps.size(), 2u);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i], static_cast<long>(i));
  }
  ASSERT_LT(steps.back(), 999) << "the run must have stopped early";
  for (const csv_row& row : csv.rows) {
    for (const double value : row.value) {
      ASSERT_TRUE(std::isfinite(value)) << "step " << row.step;
    }
  }
  const std::string diverged_step = std::to_string(steps.back() + 1);
  EXPECT_NE(result.err.find("step"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(diverged_step), std::string::npos)
      << "expected the step " << diverged_step << " in: " << result.err;
}

// The shared options set the chosen stage only (issue 11): mu = 300 is fine for the cloth
// (dt = 0.002, mu dt = 0.6), in the window too, whose spring stages keep their own default mu;
// on the spring (dt = 0.01) it would make the damping factor 1 - 300 * 0.01 = -2: refused.
TEST_F(cli, DampingIsCheckedForTheChosenStageOnly) {
  const run_result window = run({"--stage", "cloth", "--mu", "300"}, true);  // no display: exit 1
  EXPECT_EQ(window.exit_code, 1) << window.err;
  EXPECT_EQ(window.err.find("--mu"), std::string::npos) << window.err;
  const run_result headless =
      run({"--headless", "--stage", "cloth", "--N", "4", "--steps", "2", "--mu", "300"});
  EXPECT_EQ(headless.exit_code, 0) << headless.err;
  const run_result spring = run({"--headless", "--stage", "spring", "--steps", "2", "--mu", "300"});
  EXPECT_EQ(spring.exit_code, 2) << spring.err;
  EXPECT_NE(spring.err.find("--mu 300"), std::string::npos) << spring.err;
  EXPECT_NE(spring.err.find("spring"), std::string::npos) << spring.err;
}

// A subnormal value is read as the number it is and then refused by the option's range, naming
// the bound, whatever the option (D9): no option calls it "not a finite number".
TEST_F(cli, SubnormalValuesAreRefusedByTheirRangeAlike) {
  for (const arguments& args : {arguments{"--dt", "1e-320"}, arguments{"--size", "1e-320"},
                                arguments{"--mass", "1e-320"}}) {
    const run_result result = run(headless_run(args));
    EXPECT_EQ(result.exit_code, 2) << join(args);
    EXPECT_NE(result.err.find("must be between"), std::string::npos) << result.err;
  }
  const run_result ground = run(headless_run({"--ground-z", "1e-320"}));
  EXPECT_EQ(ground.exit_code, 0) << "1e-320 is inside --ground-z's range: " << ground.err;
}

// An empty value is an error naming the option, whatever the option: CLI11 used to read ''
// as 0 (--steps '' ran 0 steps, --N '' was "--N 0") and an empty path as no file at all.
TEST_F(cli, EmptyValuesAreRefusedNamingTheOption) {
  const std::vector<arguments> cases = {{"--steps", ""},
                                        {"--N", ""},
                                        {"--dt", ""},
                                        {"--csv", ""},
                                        {"--energy-csv", ""},
                                        {"--obj", ""},
                                        {"--png", ""},
                                        {"--sweep", ""},
                                        {"--stage", ""},
                                        {"--wind-dir", ""},
                                        {"--ground-z", ""},
                                        {"--drag", ""},
                                        {"--sphere", ""},
                                        {"--self-collision", ""},
                                        {"--csv-every", ""},
                                        {"--width", ""},
                                        {"--integrator", ""},
                                        {"--sweep", "m.csv", "--sweep-N", ""},
                                        {"--sweep", "m.csv", "--sweep-dt", ""}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    const std::string option = args[args.size() - 2];
    EXPECT_EQ(result.exit_code, 2) << join(args) << "\n" << result.err;
    EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\n" << result.err;
    EXPECT_TRUE(result.err.find(option + " ''") != std::string::npos ||
                result.err.find(option + ":") != std::string::npos)
        << join(args) << "\n"
        << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
  }
}

// A value with a newline (or another control character) is quoted escaped: the message stays
// one line.
TEST_F(cli, ValuesWithANewlineStayOnOneLine) {
  const std::vector<arguments> cases = {{"--dt", "1\n2"},
                                        {"--stage", "cloth\nspring"},
                                        {"--wind-dir", "1,0,\n0"},
                                        {"--sweep", "m.csv", "--sweep-dt", "0.01,\n0.02"},
                                        {"--csv", "no-such-folder/a\nb.csv"},
                                        {"--frobnicate\n", "1"}};
  for (arguments args : cases) {
    args.insert(args.begin(), "--headless");
    const run_result result = run(args);
    EXPECT_NE(result.exit_code, 0) << join(args);
    EXPECT_EQ(count_lines(result.err), 1u) << join(args) << "\n" << result.err;
    EXPECT_TRUE(fs::is_empty(work())) << join(args) << " wrote a file";
  }
}

}  // namespace
