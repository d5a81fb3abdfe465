// Screenshot regression of the renderer, off-screen (OSMesa): every stage is simulated a fixed
// number of steps, drawn at 320 x 240 with its default camera and compared with the reference
// PNGs of tests/render/reference/. Regenerate them on purpose with
//   CLOTHLAB_UPDATE_REFERENCES=1 ctest --test-dir build -L render
// and look at every image before committing it.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "build_paths.hpp"
#include "gl/camera.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth.hpp"
#include "gl/renderer.hpp"
#include "gl/shader.hpp"
#include "image.hpp"

namespace clothlab {
namespace {

using image_testing::compare_images;
using image_testing::rgba_image;

constexpr int width = 320;
constexpr int height = 240;

// A pixel differs from the reference when one of its channels is off by more than this (of 255);
// an image matches when at most this fraction of its pixels differ. Loose enough for another
// Mesa version's rounding on edges, tight enough to catch a shift of two pixels or wrong lighting
// (both checked below).
constexpr int pixel_tolerance = 24;
constexpr double allowed_differing_fraction = 0.005;

const std::filesystem::path reference_directory = clothlab_test::render_reference_directory;

// A folder that this test alone writes in, under the working directory: the tests of this file
// run in two programs (the off-screen build's and EGL's), one process per test, side by side
// under ctest -j, all in the same working directory. Named after what it holds, the program, the
// process and the test: "<what>-<program>-<process>-<test>", made empty.
std::filesystem::path own_folder(const std::string& what) {
#if defined(CLOTHLAB_GL_EGL)
  const std::string program = "egl";
#elif defined(CLOTHLAB_GL_OSMESA)
  const std::string program = "osmesa";
#else
  const std::string program = "window";
#endif
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto folder = std::filesystem::current_path() /
                      (what + "-" + program + "-" + std::to_string(::getpid()) + "-" + test);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

bool updating_references() {
  const char* update = std::getenv("CLOTHLAB_UPDATE_REFERENCES");
  return update != nullptr && std::string(update) == "1";
}

// The default cloth after 400 steps (0.8 s): it is swinging down from its two pinned corners,
// s(0, 0) and s(N-1, 0) as in the references, whichever two corners question 7 pins (any two
// are right): the test pins these itself, a cloth without pins and two vertices marked fixed,
// which apply_force never moves.
spring_mesh simulated_cloth() {
  cloth_parameters parameters;
  parameters.pins = pin_mode::none;
  spring_mesh cloth(parameters);
  const int n = cloth.grid_size();
  cloth.particles().is_fixed[spring_mesh::index(0, 0, n)] = 1;
  cloth.particles().is_fixed[spring_mesh::index(n - 1, 0, n)] = 1;
  for (int s = 0; s < 400; ++s)
    cloth.step();
  return cloth;
}

// Uploads an N x N field of 3-vectors (3k + c) into an RGBA32F texture, texel (ku, kv) =
// particle ku + N kv, as the GPU path keeps its state.
GLuint make_state_texture(int n, std::span<const double> values, double sign = 1.0) {
  std::vector<float> texels(4 * static_cast<std::size_t>(n) * n, 1.0f);
  for (std::size_t k = 0; k < static_cast<std::size_t>(n) * n; ++k) {
    for (std::size_t c = 0; c < 3; ++c)
      texels[4 * k + c] = static_cast<float>(sign * values[3 * k + c]);
  }
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, n, 0, GL_RGBA, GL_FLOAT, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    context_ = create_offscreen_context(width, height, error);
    ASSERT_NE(context_, nullptr) << error;
    ASSERT_TRUE(renderer_.init(error)) << error;
  }

  rgba_image render_spring() {
    single_spring stage;
    for (int s = 0; s < 50; ++s)
      stage.step();
    renderer_.draw(stage, camera::default_for(stage_kind::spring), {}, width, height);
    return image_testing::read_framebuffer(width, height);
  }

  rgba_image render_coupled() {
    coupled_springs stage;
    for (int s = 0; s < 100; ++s)
      stage.step();
    renderer_.draw(stage, camera::default_for(stage_kind::coupled), {}, width, height);
    return image_testing::read_framebuffer(width, height);
  }

  rgba_image render_cloth(const render_settings& settings = {}) {
    const spring_mesh cloth = simulated_cloth();
    renderer_.draw(cloth, camera::default_for(stage_kind::cloth), settings, width, height);
    return image_testing::read_framebuffer(width, height);
  }

  // The same cloth drawn by the GPU path from state textures; normal_sign = -1 flips every
  // normal (a wrongly lit cloth).
  rgba_image render_cloth_from_textures(double normal_sign = 1.0,
                                        const render_settings& settings = {}) {
    spring_mesh cloth = simulated_cloth();
    cloth.compute_normals();
    const int n = cloth.grid_size();
    const GLuint positions = make_state_texture(n, cloth.particles().position);
    const GLuint normals = make_state_texture(n, cloth.normals(), normal_sign);
    renderer_.draw_from_textures(positions, normals, cloth, camera::default_for(stage_kind::cloth),
                                 settings, width, height);
    rgba_image image = image_testing::read_framebuffer(width, height);
    glDeleteTextures(1, &positions);
    glDeleteTextures(1, &normals);
    return image;
  }

  // Compares with reference/<name>.png (or rewrites it when updating). On a mismatch writes
  // <name>.actual.png and <name>.diff.png into a folder of the working directory of this test's
  // own, render-failures-<program>-<process>-<test> (own_folder), and names them.
  static void expect_matches_reference(const rgba_image& actual, const std::string& name) {
    const auto reference_path = reference_directory / (name + ".png");
    if (updating_references()) {
      ASSERT_TRUE(image_testing::write_png(reference_path, actual)) << reference_path;
      std::cout << "updated " << reference_path << "\n";
      return;
    }
    const rgba_image expected = image_testing::load_png(reference_path);
    ASSERT_GT(expected.width, 0) << reference_path << ": cannot read the reference image";
    const auto difference = compare_images(actual, expected, pixel_tolerance);
    if (difference.differing_fraction <= allowed_differing_fraction)
      return;
    const auto failures = own_folder("render-failures");
    const auto actual_path = failures / (name + ".actual.png");
    const auto diff_path = failures / (name + ".diff.png");
    image_testing::write_png(actual_path, actual);
    image_testing::write_png(diff_path,
                             image_testing::difference_image(actual, expected, pixel_tolerance));
    ADD_FAILURE() << name << ": " << std::setprecision(3) << 100.0 * difference.differing_fraction
                  << "% of the pixels differ from " << reference_path << " by more than "
                  << pixel_tolerance << " (allowed: " << 100.0 * allowed_differing_fraction
                  << "%; largest difference " << difference.largest_channel_difference
                  << ").\n  actual image: " << actual_path << "\n  difference: " << diff_path;
  }

  // The fraction of the pixels of `actual` that differ from reference/<name>.png.
  static double differing_fraction(const rgba_image& actual, const std::string& reference_name) {
    const rgba_image expected =
        image_testing::load_png(reference_directory / (reference_name + ".png"));
    const double fraction = compare_images(actual, expected, pixel_tolerance).differing_fraction;
    std::cout << "  " << 100.0 * fraction << "% of the pixels differ from " << reference_name
              << ".png\n";
    return fraction;
  }

  std::unique_ptr<gl_context> context_;
  renderer renderer_;
};

// The pictures of the chain and the cloth need the lab's solution (questions 5 to 9): in the
// student copy they fail until every question is answered (label render-solution).
using SolutionRender = RenderTest;

TEST_F(RenderTest, SpringAfter50StepsMatchesReference) {
  expect_matches_reference(render_spring(), "spring_50_steps");
}

TEST_F(SolutionRender, CoupledSpringsAfter100StepsMatchReference) {
  expect_matches_reference(render_coupled(), "coupled_100_steps");
}

TEST_F(SolutionRender, ClothAfter400StepsMatchesReference) {
  expect_matches_reference(render_cloth(), "cloth_400_steps");
}

TEST_F(SolutionRender, ClothWireframeAndSpringsOverlayMatchesReference) {
  expect_matches_reference(render_cloth({.wireframe = true, .show_springs = true}),
                           "cloth_400_steps_wireframe_springs");
}

// The GPU path draws the same image as the CPU path when its textures hold the same state.
TEST_F(SolutionRender, ClothFromStateTexturesMatchesTheCpuClothReference) {
  if (updating_references())
    GTEST_SKIP() << "compared with cloth_400_steps.png, not its own";
  expect_matches_reference(render_cloth_from_textures(), "cloth_400_steps");
}

TEST_F(SolutionRender, ClothFromStateTexturesWithOverlayMatchesTheCpuReference) {
  if (updating_references())
    GTEST_SKIP() << "compared with cloth_400_steps_wireframe_springs.png, not its own";
  expect_matches_reference(
      render_cloth_from_textures(1.0, {.wireframe = true, .show_springs = true}),
      "cloth_400_steps_wireframe_springs");
}

// The comparison must be able to fail.
TEST_F(SolutionRender, ComparisonFailsOnABlankImage) {
  if (updating_references())
    GTEST_SKIP();
  rgba_image blank = render_cloth();
  const rgba_image rendered = blank;
  for (std::size_t i = 0; i < blank.pixels.size(); ++i)
    blank.pixels[i] = rendered.pixels[i % 4];
  EXPECT_LE(differing_fraction(rendered, "cloth_400_steps"), allowed_differing_fraction);
  EXPECT_GT(differing_fraction(blank, "cloth_400_steps"), allowed_differing_fraction);
}

TEST_F(SolutionRender, ComparisonFailsOnAnImageShiftedByTwoPixels) {
  if (updating_references())
    GTEST_SKIP();
  const rgba_image cloth = render_cloth();
  EXPECT_LE(differing_fraction(cloth, "cloth_400_steps"), allowed_differing_fraction);
  EXPECT_GT(differing_fraction(image_testing::shifted(cloth, 2, 0), "cloth_400_steps"),
            allowed_differing_fraction);
  EXPECT_GT(differing_fraction(image_testing::shifted(cloth, 0, 2), "cloth_400_steps"),
            allowed_differing_fraction);
  const rgba_image coupled = render_coupled();
  EXPECT_LE(differing_fraction(coupled, "coupled_100_steps"), allowed_differing_fraction);
  EXPECT_GT(differing_fraction(image_testing::shifted(coupled, 2, 0), "coupled_100_steps"),
            allowed_differing_fraction);
}

TEST_F(RenderTest, ComparisonFailsOnAWronglyLitCloth) {
  if (updating_references())
    GTEST_SKIP();
  EXPECT_GT(differing_fraction(render_cloth_from_textures(-1.0), "cloth_400_steps"),
            allowed_differing_fraction);
}

TEST_F(RenderTest, ComparisonFailsWhenTheOverlayIsMissing) {
  if (updating_references())
    GTEST_SKIP();
  EXPECT_GT(differing_fraction(render_cloth(), "cloth_400_steps_wireframe_springs"),
            allowed_differing_fraction);
}

// Independent of the references: the pictures are not blank and show the cloth's texture.
TEST_F(SolutionRender, ClothImageShowsTheTexturedLitCloth) {
  const rgba_image image = render_cloth();
  EXPECT_GT(image_testing::count_distinct_colours(image), 2000u);
  std::size_t crimson = 0;  // the red threads of assets/cloth.png, lit
  std::size_t cream = 0;    // the cream threads
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int r = image.channel(x, y, 0);
      const int g = image.channel(x, y, 1);
      const int b = image.channel(x, y, 2);
      if (r > 110 && r > g + 70 && r > b + 60)
        ++crimson;
      if (r > 170 && g > 150 && b > 120 && r > b + 25)
        ++cream;
    }
  }
  const double pixels = double{width} * height;
  std::cout << "  " << crimson << " crimson and " << cream << " cream pixels of " << pixels << "\n";
  EXPECT_GT(static_cast<double>(crimson) / pixels, 0.015) << crimson << " crimson pixels";
  EXPECT_GT(static_cast<double>(cream) / pixels, 0.01) << cream << " cream pixels";
}

// Two-sided: the flat initial cloth seen from below shows its back, tinted, not the background.
TEST_F(RenderTest, ClothBackFacesAreDrawnWithTheirTint) {
  const spring_mesh cloth;  // flat at z = 0, front (normal) facing +z
  camera view;
  view.target = {0.19f, 0.19f, 0.0f};  // inside a cream check of the texture
  view.distance = 1.5f;
  const auto centre_pixel = [&](float pitch) {
    view.pitch = pitch;
    renderer_.draw(cloth, view, {.show_ground = false}, width, height);
    const rgba_image image = image_testing::read_framebuffer(width, height);
    return glm::vec3(image.channel(width / 2, height / 2, 0),
                     image.channel(width / 2, height / 2, 1),
                     image.channel(width / 2, height / 2, 2));
  };
  const glm::vec3 front = centre_pixel(0.7f);
  const glm::vec3 back = centre_pixel(-0.7f);
  const glm::vec3 background = centre_pixel(0.0f);  // edge-on: the cloth has no area
  std::cout << "  front " << front.r << " " << front.g << " " << front.b << ", back " << back.r
            << " " << back.g << " " << back.b << "\n";
  EXPECT_GT(glm::length(back - background), 30.0f);
  // The back's tint is bluer than the front's colour of the same thread.
  EXPECT_GT(back.b / back.r, 1.1f * front.b / front.r);
}

// A cloth folded flat on the ground (issue 19: the draped cloth dropped by the sphere, a stiff
// cloth whose lower edge lies down): the ground contact puts both layers at z = z_g exactly, so
// their depths tie, and the rasteriser's rounding picked the layer pixel by pixel, differently
// from frame to frame (the layers flickered through each other). The renderer breaks the tie
// the same way everywhere: the layer folded over (its back side up) is in front. The fold drawn
// flat must look like the same fold with its lower layer 1 cm lower.
TEST_F(RenderTest, AClothFoldedFlatShowsItsUpperLayerWhole) {
  const auto folded = [](double lower_layer_drop) {
    spring_mesh cloth;  // N = 20, 1 m
    particle_system& particles = cloth.particles();
    const int n = cloth.grid_size();
    const double h = cloth.parameters.side_length / (n - 1);
    for (int kv = 0; kv < n; ++kv) {
      // Rows 0 to 9 lie flat from y = 0; rows 10 to 19 are folded back over them (row 19 on
      // row 0), back side up.
      const int row = kv < n / 2 ? kv : n - 1 - kv;
      const double z = -1.0 - (kv < n / 2 ? lower_layer_drop : 0.0);
      for (int ku = 0; ku < n; ++ku)
        particles.set_position(spring_mesh::index(ku, kv, n), {ku * h - 0.5, row * h, z});
    }
    return cloth;
  };
  camera view;
  view.target = {0.0f, 0.25f, -1.0f};
  view.distance = 1.6f;
  view.yaw = 0.8f;
  view.pitch = 0.9f;
  const render_settings settings = {.show_ground = false};
  renderer_.draw(folded(0.0), view, settings, width, height);
  const rgba_image flat = image_testing::read_framebuffer(width, height);
  renderer_.draw(folded(0.01), view, settings, width, height);
  const rgba_image apart = image_testing::read_framebuffer(width, height);
  const double fraction = compare_images(flat, apart, pixel_tolerance).differing_fraction;
  std::cout << "  " << 100.0 * fraction << "% of the pixels differ\n";
  EXPECT_LT(fraction, 0.01) << "the two layers of the flat fold show through each other";
}

// The obstacle sphere (model.md, "sphere") is drawn with the cloth when it is on: lit, in its
// own colour, with a soft shadow on the ground; not drawn when it is off.
TEST_F(RenderTest, ClothSphereIsDrawnLitWithItsShadow) {
  spring_mesh cloth;  // flat at z = 0, beside the sphere
  cloth.parameters.sphere = {.enabled = true, .centre = {1.2, 0.0, -0.5}, .radius = 0.3};
  camera view;
  view.target = glm::vec3(cloth.parameters.sphere.centre);
  view.pitch = 0.1f;  // from below the cloth's plane: nothing between the eye and the sphere
  const auto draw = [&](bool sphere_on) {
    cloth.parameters.sphere.enabled = sphere_on;
    renderer_.draw(cloth, view, {}, width, height);
    return image_testing::read_framebuffer(width, height);
  };
  const rgba_image with = draw(true);
  const rgba_image without = draw(false);
  const auto is_obstacle = [](const rgba_image& image, int x, int y) {
    const int r = image.channel(x, y, 0);
    const int g = image.channel(x, y, 1);
    const int b = image.channel(x, y, 2);
    return r > 40 && 10 * r > 16 * g && r > 2 * b;  // terracotta, lit or in its own shade
  };
  EXPECT_TRUE(is_obstacle(with, width / 2, height / 2)) << "no sphere at the centre of the view";
  EXPECT_FALSE(is_obstacle(without, width / 2, height / 2)) << "a sphere drawn while off";
  // Lit: its shading varies across the disc (a flat disc would have one colour).
  int darkest = 255;
  int brightest = 0;
  std::size_t shadowed = 0;  // grey ground pixels darker with the sphere than without it
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (is_obstacle(with, x, y)) {
        darkest = std::min<int>(darkest, with.channel(x, y, 0));
        brightest = std::max<int>(brightest, with.channel(x, y, 0));
      } else if (!is_obstacle(without, x, y) &&
                 with.channel(x, y, 1) + 12 < without.channel(x, y, 1)) {
        ++shadowed;
      }
    }
  }
  EXPECT_GT(brightest - darkest, 50) << "the sphere is not shaded";
  EXPECT_GT(shadowed, 300u) << "no shadow under the sphere";
}

TEST_F(RenderTest, SpringStagesAreNotBlank) {
  EXPECT_GT(image_testing::count_distinct_colours(render_spring()), 300u);
  EXPECT_GT(image_testing::count_distinct_colours(render_coupled()), 300u);
}

TEST_F(RenderTest, SavedPngHoldsTheFramebufferTopRowFirst) {
  const rgba_image rendered = render_cloth();
  const auto folder = own_folder("render-output");
  const auto path = folder / "saved.png";
  std::string error;
  ASSERT_TRUE(save_framebuffer_png(path.string(), width, height, error)) << error;
  const rgba_image saved = image_testing::load_png(path);
  ASSERT_EQ(saved.width, width);
  ASSERT_EQ(saved.height, height);
  EXPECT_EQ(saved.pixels, rendered.pixels);
  // Top row first: the top of the picture is blue sky, the bottom grey ground.
  const auto blueness = [&saved](int y) {
    return saved.channel(width / 2, y, 2) - saved.channel(width / 2, y, 0);
  };
  EXPECT_GT(blueness(0), blueness(height - 1) + 15);
  std::filesystem::remove_all(folder);
}

// The web build's P key downloads the PNG from memory: the same bytes as the saved file.
TEST_F(RenderTest, PngInMemoryHasTheBytesOfTheSavedFile) {
  render_cloth();
  std::vector<unsigned char> png;
  std::string error;
  ASSERT_TRUE(framebuffer_png(width, height, png, error)) << error;
  const auto folder = own_folder("render-output");
  const auto path = folder / "in-memory.png";
  ASSERT_TRUE(save_framebuffer_png(path.string(), width, height, error)) << error;
  std::ifstream file(path, std::ios::binary);
  const std::vector<unsigned char> saved((std::istreambuf_iterator<char>(file)),
                                         std::istreambuf_iterator<char>());
  EXPECT_EQ(png, saved);
  file.close();
  std::filesystem::remove_all(folder);
  EXPECT_FALSE(framebuffer_png(0, height, png, error));
  EXPECT_NE(error.find("0x" + std::to_string(height)), std::string::npos) << error;
}

TEST_F(RenderTest, SavingToAnUnwritablePathNamesThePath) {
  std::string error;
  EXPECT_FALSE(save_framebuffer_png("/nonexistent-folder/x.png", width, height, error));
  EXPECT_NE(error.find("/nonexistent-folder/x.png"), std::string::npos) << error;
}

// init() fails loudly, naming the file, when a shader or the texture is missing or broken.
class BrokenDataTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    context_ = create_offscreen_context(width, height, error);
    ASSERT_NE(context_, nullptr) << error;
    const auto real_data = data_directory();
    data_ = own_folder("broken-data");
    std::filesystem::copy(real_data / "shaders", data_ / "shaders");
    std::filesystem::copy(real_data / "assets", data_ / "assets");
    setenv("CLOTHLAB_DATA_DIR", data_.c_str(), 1);
  }
  void TearDown() override {
    unsetenv("CLOTHLAB_DATA_DIR");
    std::filesystem::remove_all(data_);
  }
  static void overwrite(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  }

  std::unique_ptr<gl_context> context_;
  std::filesystem::path data_;
};

TEST_F(BrokenDataTest, MissingShaderIsNamed) {
  std::filesystem::remove(data_ / "shaders" / "draw_lit.frag");
  renderer r;
  std::string error;
  EXPECT_FALSE(r.init(error));
  EXPECT_NE(error.find("draw_lit.frag"), std::string::npos) << error;
}

TEST_F(BrokenDataTest, ShaderThatDoesNotCompileIsNamedWithItsLog) {
  overwrite(data_ / "shaders" / "draw_ground.frag", "void main() { oops; }\n");
  renderer r;
  std::string error;
  EXPECT_FALSE(r.init(error));
  EXPECT_NE(error.find("draw_ground.frag"), std::string::npos) << error;
  EXPECT_NE(error.find("oops"), std::string::npos) << error;
}

// The loader puts the #version line before the file: the compiler's line numbers are still the
// file's own, each message at its file ("draw_ground.frag:3(" from Mesa's "0:3(",
// "draw_ground.frag(3)" from others' "0(3)"), also below an #include.
TEST_F(BrokenDataTest, ShaderErrorsGiveTheFilesOwnLineNumbers) {
  const auto names_line = [](const std::string& log, int line) {
    const std::string n = std::to_string(line);
    return log.find(".frag:" + n + "(") != std::string::npos ||
           log.find(".frag(" + n + ")") != std::string::npos;
  };
  overwrite(data_ / "shaders" / "draw_ground.frag", "// line 1\n\nvoid main() { oops; }\n");
  renderer r;
  std::string error;
  EXPECT_FALSE(r.init(error));
  EXPECT_NE(error.find("draw_ground.frag"), std::string::npos) << error;
  EXPECT_TRUE(names_line(error, 3)) << error;

  overwrite(data_ / "shaders" / "gpu_step.frag",
            "// line 1\n#include \"gpu_cloth_common.glsl\"\nvoid main() {\n  oops;\n}\n");
  gpu_cloth gpu;
  spring_mesh cloth(cloth_parameters{});
  EXPECT_FALSE(gpu.load(cloth, error));
  EXPECT_NE(error.find("gpu_step.frag"), std::string::npos) << error;
  EXPECT_TRUE(names_line(error, 4)) << error;
}

TEST_F(BrokenDataTest, ShaderWithItsOwnVersionLineIsRefusedSayingSo) {
  overwrite(data_ / "shaders" / "draw_ground.frag", "#version 330 core\nvoid main() {}\n");
  renderer r;
  std::string error;
  EXPECT_FALSE(r.init(error));
  EXPECT_NE(error.find("draw_ground.frag: begins with a #version line"), std::string::npos)
      << error;
}

TEST_F(BrokenDataTest, BrokenTextureIsNamed) {
  overwrite(data_ / "assets" / "cloth.png", "not a png");
  renderer r;
  std::string error;
  EXPECT_FALSE(r.init(error));
  EXPECT_NE(error.find("cloth.png"), std::string::npos) << error;
}

}  // namespace
}  // namespace clothlab

namespace clothlab {
namespace {

// A screenshot that cannot be written whole (a full disk, simulated with a 2000-byte file size
// limit in a child process) is reported as failed and leaves no file: the window's P and --png
// both save through save_framebuffer_png, and stb's writer says nothing of a failed write.
TEST_F(RenderTest, AScreenshotThatCannotBeWrittenWholeFailsAndLeavesNoFile) {
  render_spring();
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("clothlab-truncated-" + std::to_string(::getpid()) + ".png");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{2000, 2000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string error;
    ::_exit(save_framebuffer_png(path.string(), width, height, error) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << "status " << status;
  EXPECT_FALSE(std::filesystem::exists(path)) << path << " was left behind";
  std::filesystem::remove(path);
  // Without the limit the same save succeeds.
  std::string error;
  EXPECT_TRUE(save_framebuffer_png(path.string(), width, height, error)) << error;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace clothlab
