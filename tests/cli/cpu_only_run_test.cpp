// A run on the CPU paths needs no OpenGL: this program links the headless run's step loops and
// outputs (clothlab_runs) and the core, and no GL library at all, and runs the cloth on both CPU
// paths and the two spring stages, with their CSV and OBJ, as clothlab --headless does. It would
// not link if that code called any GL code.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/command_line.hpp"
#include "app/run_outputs.hpp"
#include "app/stage_runs.hpp"
#include "core/cloth_parallel.hpp"
#include "core/cpu_cloth_paths.hpp"

namespace clothlab {
namespace {

namespace fs = std::filesystem;

class CpuOnlyRun : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "clothlab-cpu-only-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    folder_ = pattern;
  }
  void TearDown() override { fs::remove_all(folder_); }

  // The options of `clothlab --headless ARGS --csv <folder>/states.csv`.
  options parsed(std::vector<std::string> args) const {
    args.insert(args.begin(), {"clothlab", "--headless"});
    args.push_back("--csv");
    args.push_back((folder_ / "states.csv").string());
    std::vector<const char*> argv;
    for (const std::string& a : args)
      argv.push_back(a.c_str());
    const parse_result result = parse_command_line(static_cast<int>(argv.size()), argv.data());
    EXPECT_TRUE(result.parsed.has_value());
    return result.parsed.value_or(options{});
  }
  long lines_of(const std::string& name) const {
    std::ifstream file(folder_ / name);
    long lines = 0;
    for (std::string line; std::getline(file, line);)
      ++lines;
    return lines;
  }

  fs::path folder_;
};

TEST_F(CpuOnlyRun, TheClothOnBothCpuPaths) {
  const std::string obj = (folder_ / "cloth.obj").string();
  for (const std::string backend : {"cpu", "cpu-parallel"}) {
    if (backend == "cpu-parallel" && !cloth_parallel::available())
      continue;  // (a build without OpenMP, or the student copy)
    std::vector<std::string> args = {"--N",       "6",     "--steps", "20",
                                     "--backend", backend, "--obj",   obj};
    if (backend == "cpu-parallel")
      args.insert(args.end(), {"--threads", "2"});
    const options o = parsed(args);
    run_outputs out(o);
    std::string error;
    ASSERT_TRUE(out.open(error)) << error;
    cpu_cloth_paths paths(o.cloth, o.threads);
    int status = 0;
    if (o.backend == cloth_backend::cpu) {
      status = run_cpu(o, paths.cloth, out);
    } else {
      ASSERT_TRUE(paths.load(o.backend, error)) << error;
      status = run_batched(o, paths, out);
    }
    EXPECT_EQ(status, 0) << backend;
    paths.cloth.compute_normals();
    EXPECT_TRUE(out.write_obj_file(paths.cloth, error)) << error;
    EXPECT_TRUE(out.close(true, true, error)) << error;
    EXPECT_EQ(lines_of("states.csv"), 1 + 21 * 36) << backend;  // header, 21 steps of 36
    EXPECT_GT(lines_of("cloth.obj"), 36) << backend;
  }
}

TEST_F(CpuOnlyRun, TheSpringStages) {
  const options o = parsed({"--stage", "coupled", "--chain", "3", "--steps", "10"});
  run_outputs out(o);
  std::string error;
  ASSERT_TRUE(out.open(error)) << error;
  coupled_springs chain(o.coupled);
  EXPECT_EQ(run_cpu(o, chain, out), 0);
  EXPECT_TRUE(out.close(true, true, error)) << error;
  EXPECT_EQ(lines_of("states.csv"), 1 + 11 * 4);  // p0 and the three masses
}

TEST_F(CpuOnlyRun, AGpuPathIsRefusedInWords) {
  cpu_cloth_paths paths(cloth_parameters{});
  std::string error;
  EXPECT_FALSE(paths.load(cloth_backend::gpu, error));
  EXPECT_NE(error.find("OpenGL"), std::string::npos) << error;
  EXPECT_EQ(paths.backend(), cloth_backend::cpu);
}

}  // namespace
}  // namespace clothlab
