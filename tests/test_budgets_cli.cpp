// `snee render --time` and `--noise-target` as a user meets them: the files they write say
// honestly how many samples each pixel holds, and bad values are usage errors.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include "scene/film.h"
#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class BudgetsCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("budgets_cli"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Exit code of `snee ARGS`; its output is in output().
  int snee(const std::string& args) const {
    return test::run_command("cd '" + dir_.string() + "' && '" SNEE_BINARY "' " + args,
                             dir_ / "output.txt");
  }
  std::string output() const { return test::read_text_file(dir_ / "output.txt"); }
  fs::path dir_;
};

bool has_channel(const std::string& exr, const char* name) {
  auto in = OIIO::ImageInput::open(exr);
  return in && in->spec().channelindex(name) >= 0;
}

// Far more spp than a tenth of a second allows: the render stops between rounds, exits 0 and
// every pixel holds the same whole rounds, which the metadata states.
TEST_F(BudgetsCli, TimeBudgetStopsWithWholeRoundsAndHonestMetadata) {
  const std::string exr = path("timed.exr");
  ASSERT_EQ(snee("render builtin:default --resolution 32x24 --spp 100000000 --time 0.1 "
                 "--noise-target 0 "
                 "--samples-per-unit 4 --quiet -o " +
                 exr),
            0)
      << output();
  EXPECT_NE(output().find("of 100000000 spp (time budget spent)"), std::string::npos) << output();
  const Film film = read_exr(exr);
  EXPECT_EQ(film.meta.spp, 100000000);
  EXPECT_GE(film.meta.min_spp, 4);
  EXPECT_LT(film.meta.min_spp, 100000000);
  EXPECT_EQ(film.meta.min_spp % 4, 0) << "whole rounds";
  EXPECT_EQ(film.meta.time_budget_seconds, 0.1);
  // Every pixel has the same count, so no spp channel is needed.
  EXPECT_FALSE(has_channel(exr, "spp"));
  EXPECT_TRUE(film.pixel_spp.empty());
}

TEST_F(BudgetsCli, NoiseTargetWritesTheSampleCountChannel) {
  const std::string exr = path("adaptive.exr");
  ASSERT_EQ(snee("render builtin:sphere-directional-r0.2 --resolution 32x32 --spp 64 "
                 "--noise-target 0.1 --tile-size 8 --quiet -o " +
                 exr),
            0)
      << output();
  EXPECT_NE(output().find("(noise target 0.1)"), std::string::npos) << output();
  ASSERT_TRUE(has_channel(exr, "spp"));
  const Film film = read_exr(exr);
  ASSERT_EQ(film.pixel_spp.size(), film.mean.size());
  EXPECT_EQ(film.meta.noise_target, 0.1);
  EXPECT_EQ(film.meta.spp, 64);
  uint32_t fewest = film.pixel_spp[0], most = 0;
  for (const uint32_t n : film.pixel_spp) {
    fewest = std::min(fewest, n);
    most = std::max(most, n);
  }
  EXPECT_EQ(static_cast<int>(fewest), film.meta.min_spp);
  EXPECT_LT(fewest, most);
  EXPECT_LE(most, 64u);
}

// A small translucent sphere; `render` is the scene's render block.
std::string sphere_scene(const std::string& render) {
  // Wide enough that the corner tiles see only black background and stop early.
  return R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 70,
                        "resolution": [32, 32]},
             "render": )" +
         render + R"(,
             "shapes": [{"type": "sphere", "medium": {"sigma_s": 3, "sigma_a": 0.1},
                         "material": {"type": "dielectric", "ior": 1.5, "roughness": 0.2}}],
             "lights": [{"type": "directional", "direction": [-0.4, 0.7, 0.5],
                         "irradiance": 3}]})";
}

// The scene's render.noise_target is the same target as --noise-target: the same pixels and
// sample counts. --noise-target 0 turns the scene's off, so every pixel takes --spp.
TEST_F(BudgetsCli, SceneNoiseTargetActsAsTheOptionAndZeroTurnsItOff) {
  auto write = [&](const std::string& name, const std::string& render) {
    std::ofstream(path(name)) << sphere_scene(render);
  };
  write("with_target.json", R"({"spp": 64, "integrator": "snee", "noise_target": 0.1})");
  write("without.json", R"({"spp": 64, "integrator": "snee"})");
  const std::string common = " --tile-size 8 --quiet -o ";
  ASSERT_EQ(snee("render with_target.json" + common + path("scene.exr")), 0) << output();
  ASSERT_EQ(snee("render without.json --noise-target 0.1" + common + path("option.exr")), 0)
      << output();
  ASSERT_EQ(snee("render with_target.json --noise-target 0" + common + path("off.exr")), 0)
      << output();

  const Film from_scene = read_exr(path("scene.exr"));
  const Film from_option = read_exr(path("option.exr"));
  EXPECT_EQ(from_scene.meta.noise_target, 0.1);
  ASSERT_FALSE(from_scene.pixel_spp.empty()) << "the target should have stopped some tiles";
  EXPECT_EQ(from_scene.pixel_spp, from_option.pixel_spp);
  EXPECT_EQ(from_scene.mean, from_option.mean);
  EXPECT_EQ(from_scene.variance_of_mean, from_option.variance_of_mean);

  const Film off = read_exr(path("off.exr"));
  EXPECT_EQ(off.meta.noise_target, 0.0);
  EXPECT_EQ(off.meta.min_spp, 64);
  EXPECT_TRUE(off.pixel_spp.empty());
  EXPECT_FALSE(has_channel(path("off.exr"), "spp"));
}

TEST_F(BudgetsCli, BadValuesAreErrors) {
  const std::pair<const char*, std::vector<const char*>> cases[] = {
      {"--time", {"0", "-1", "nan", "inf"}},
      {"--noise-target", {"-1", "nan", "inf"}}};  // 0 turns a scene's target off
  for (const auto& [option, values] : cases) {
    for (const char* value : values) {
      const std::string args =
          std::string("render --resolution 4x4 --quiet ") + option + " " + value;
      EXPECT_NE(snee(args), 0) << args;
      EXPECT_NE(output().find("error"), std::string::npos) << args << "\n" << output();
      EXPECT_FALSE(fs::exists(dir_ / "out")) << args << ": rendered anyway";
    }
  }
}

}  // namespace
}  // namespace snee
