// `snee render --aov` as a user meets it: the chosen layers appear in the EXR under their
// channel names (albedo.R/G/B, N.X/Y/Z, Z) and are recorded in the settings, a render without
// --aov has none of them, an unknown or repeated name is refused with the valid names, and so
// is --aov with --resume.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "scene/film.h"
#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTiny = "builtin:sphere-cone-r0.2 --spp 2 --resolution 12x8 --quiet";

class AovCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("aov-cli"); }
  void TearDown() override { fs::remove_all(dir_); }
  int snee(const std::string& args) {
    return test::run_in_directory(dir_, SNEE_BINARY, args, output_);
  }
  std::vector<std::string> channels(const std::string& name) const {
    auto in = OIIO::ImageInput::open((dir_ / name).string());
    EXPECT_TRUE(in) << OIIO::geterror();
    return in ? in->spec().channelnames : std::vector<std::string>{};
  }
  static bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  }
  fs::path dir_;
  std::string output_;
};

TEST_F(AovCli, ChosenLayersAreWrittenAndReadBack) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " --aov depth,albedo,normal -o all.exr"), 0)
      << output_;
  const std::vector<std::string> all = channels("all.exr");
  for (const char* name :
       {"R", "G", "B", "variance.R", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"})
    EXPECT_TRUE(has(all, name)) << name;
  const Film film = read_exr((dir_ / "all.exr").string());
  ASSERT_EQ(film.albedo.size(), film.mean.size());
  ASSERT_EQ(film.normal.size(), film.mean.size());
  ASSERT_EQ(film.depth.size(), film.mean.size());
  // The camera sees the sphere in the middle of the image: a hit at a positive distance.
  EXPECT_GT(film.depth[film.mean.size() / 2 + 6], 0.0f);
  auto in = OIIO::ImageInput::open((dir_ / "all.exr").string());
  ASSERT_TRUE(in);
  EXPECT_NE(in->spec()
                .get_string_attribute("snee:render_options")
                .find("\"aovs\":\"albedo,normal,depth\""),
            std::string::npos);

  ASSERT_EQ(snee(std::string("render ") + kTiny + " --aov normal -o normal.exr"), 0) << output_;
  const std::vector<std::string> some = channels("normal.exr");
  EXPECT_TRUE(has(some, "N.X"));
  EXPECT_FALSE(has(some, "albedo.R"));
  EXPECT_FALSE(has(some, "Z"));
}

TEST_F(AovCli, WithoutAovTheExrHasNoLayersAndTheSamePixels) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o plain.exr"), 0) << output_;
  ASSERT_EQ(snee(std::string("render ") + kTiny + " --aov albedo,normal,depth -o aov.exr"), 0)
      << output_;
  const std::vector<std::string> plain = channels("plain.exr");
  EXPECT_FALSE(has(plain, "albedo.R") || has(plain, "N.X") || has(plain, "Z"));
  const Film a = read_exr((dir_ / "plain.exr").string());
  const Film b = read_exr((dir_ / "aov.exr").string());
  ASSERT_EQ(a.mean.size(), b.mean.size());
  for (size_t i = 0; i < a.mean.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a.mean[i][c], b.mean[i][c]);
      EXPECT_EQ(a.variance_of_mean[i][c], b.variance_of_mean[i][c]);
    }
  }
}

TEST_F(AovCli, BadListsAreRefused) {
  EXPECT_NE(snee(std::string("render ") + kTiny + " --aov albedo,shadow -o x.exr"), 0);
  EXPECT_NE(output_.find("unknown AOV 'shadow'"), std::string::npos) << output_;
  EXPECT_NE(output_.find("albedo, normal, depth"), std::string::npos) << output_;
  EXPECT_NE(snee(std::string("render ") + kTiny + " --aov normal,normal -o x.exr"), 0);
  EXPECT_NE(output_.find("given twice"), std::string::npos) << output_;
  EXPECT_NE(snee(std::string("render ") + kTiny + " --aov '' -o x.exr"), 0);
  EXPECT_NE(output_.find("unknown AOV ''"), std::string::npos) << output_;
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

// The checkpoint state holds no layers, so a resumed render could only average them over part
// of its samples: refused before anything renders.
TEST_F(AovCli, ResumeWithAovIsRefused) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " --checkpoint 100 -o c.exr"), 0) << output_;
  ASSERT_TRUE(fs::exists(dir_ / "c.exr.checkpoint"));
  const auto before = fs::last_write_time(dir_ / "c.exr");
  EXPECT_NE(snee(std::string("render ") + kTiny + " --resume c.exr --aov albedo"), 0);
  EXPECT_NE(output_.find("--aov is not available with --resume"), std::string::npos) << output_;
  EXPECT_EQ(fs::last_write_time(dir_ / "c.exr"), before);
}

}  // namespace
}  // namespace snee
