// `snee error` as a user meets it: the relative MSE of images whose error is known exactly, the
// render's sample counts from its spp channel or, without one, its metadata, and the inputs it
// cannot measure refused naming the file.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/film.h"
#include "tests/support/snee_directory.h"

namespace snee {
namespace {

// As apps/image_error.h: the constant that keeps dark pixels from dominating.
constexpr double kFloor = 1e-2;

// A width x height image of one colour, with one variance of the mean in every channel (none
// when `variance` is negative) and `spp` samples in every pixel.
Film flat_film(int width, int height, float value, float variance, int spp) {
  Film film;
  film.width = width;
  film.height = height;
  film.mean.assign(static_cast<size_t>(width) * height, Rgb(value));
  if (variance >= 0) film.variance_of_mean.assign(film.mean.size(), Rgb(variance));
  film.meta.spp = spp;
  film.meta.min_spp = spp;
  film.meta.integrator = "pt";
  film.meta.scene = "flat";
  return film;
}

class ErrorCli : public test::SneeDirectoryTest {
 protected:
  ErrorCli() : SneeDirectoryTest("error_cli") {}
  int snee(const std::string& args) const { return run(SNEE_BINARY, args); }
  nlohmann::json json(const std::string& name) const {
    return nlohmann::json::parse(std::ifstream(path(name)));
  }
};

// An image against itself: no raw error at all, and the reference's noise is what its variance
// channels say.
TEST_F(ErrorCli, AnImageAgainstItselfHasNoError) {
  const float value = 0.5f, variance = 4e-4f;
  write_exr(flat_film(8, 6, value, variance, 64), path("image.exr"));
  ASSERT_EQ(snee("error image.exr image.exr --json self.json"), 0) << output();
  const nlohmann::json j = json("self.json");
  EXPECT_EQ(j["relative_mse_raw"].get<double>(), 0.0);
  EXPECT_EQ(j["relative_mse"].get<double>(), 0.0) << "raw minus noise, never below 0";
  EXPECT_EQ(j["relative_mse_trimmed"].get<double>(), 0.0);
  const double noise = double{variance} / (double{value} * value + kFloor);
  EXPECT_NEAR(j["reference_noise"].get<double>(), noise, 1e-12);
  EXPECT_EQ(j["resolution"], nlohmann::json::array({8, 6}));
  EXPECT_EQ(j["render"]["spp"]["mean"].get<double>(), 64.0) << "from snee:min_spp";
  EXPECT_EQ(j["render"]["spp"]["min"].get<int>(), 64);
  EXPECT_EQ(j["render"]["spp"]["max"].get<int>(), 64);
  EXPECT_TRUE(said("raw         0.000000e+00")) << output();
}

// A render 10% too bright everywhere against a flat noisy reference: every pixel's error is
// the same, so the figures are known to float precision, and the trimmed one equals the full
// one. The render's per-pixel sample counts give its mean, fewest and most.
TEST_F(ErrorCli, KnownOffsetAndSampleCounts) {
  const float ref = 1.0f, variance = 1e-3f, value = 1.1f;
  write_exr(flat_film(8, 8, ref, variance, 4096), path("reference.exr"));
  Film render = flat_film(8, 8, value, 0.0f, 64);
  render.pixel_spp.assign(render.mean.size(), 16);
  for (size_t i = 0; i < render.pixel_spp.size(); i += 4) render.pixel_spp[i] = 64;
  render.meta.min_spp = 16;
  render.meta.noise_target = 0.05;
  write_exr(render, path("render.exr"));

  ASSERT_EQ(snee("error render.exr reference.exr --json error.json"), 0) << output();
  const nlohmann::json j = json("error.json");
  const double diff = double{value} - ref, scale = double{ref} * ref + kFloor;
  const double raw = diff * diff / scale, noise = variance / scale;
  EXPECT_NEAR(j["relative_mse_raw"].get<double>(), raw, 1e-9);
  EXPECT_NEAR(j["reference_noise"].get<double>(), noise, 1e-12);
  EXPECT_NEAR(j["relative_mse"].get<double>(), raw - noise, 1e-9);
  EXPECT_NEAR(j["relative_mse_trimmed"].get<double>(), raw - noise, 1e-9);
  EXPECT_EQ(j["relative_mse_floor"].get<double>(), kFloor);
  // A quarter of the pixels hold 64 samples, the rest 16: a mean of 28.
  EXPECT_EQ(j["render"]["spp"]["mean"].get<double>(), 28.0);
  EXPECT_EQ(j["render"]["spp"]["min"].get<int>(), 16);
  EXPECT_EQ(j["render"]["spp"]["max"].get<int>(), 64);
  EXPECT_EQ(j["render"]["spp"]["requested"].get<int>(), 64);
  EXPECT_EQ(j["render"]["noise_target"].get<double>(), 0.05);
  EXPECT_EQ(j["reference"]["spp"]["mean"].get<double>(), 4096.0);
  EXPECT_EQ(j["render"]["file"], "render.exr");
  EXPECT_TRUE(said("mean 28.00 spp (16 to 64)")) << output();
  EXPECT_FALSE(said("warning")) << output();
}

// Without variance channels the reference's noise cannot be subtracted: the figure is the raw
// one, and a warning says so.
TEST_F(ErrorCli, ReferenceWithoutVarianceIsWarnedAbout) {
  write_exr(flat_film(4, 4, 1.0f, -1.0f, 16), path("reference.exr"));
  write_exr(flat_film(4, 4, 1.1f, 0.0f, 16), path("render.exr"));
  ASSERT_EQ(snee("error render.exr reference.exr --json error.json"), 0) << output();
  EXPECT_TRUE(said("warning: reference.exr has no variance channels")) << output();
  const nlohmann::json j = json("error.json");
  EXPECT_EQ(j["reference_noise"].get<double>(), 0.0);
  EXPECT_EQ(j["relative_mse"].get<double>(), j["relative_mse_raw"].get<double>());
}

TEST_F(ErrorCli, SizeMismatchNamesBothFilesAndSizes) {
  write_exr(flat_film(8, 8, 1.0f, 0.0f, 16), path("reference.exr"));
  write_exr(flat_film(8, 4, 1.0f, 0.0f, 16), path("render.exr"));
  EXPECT_EQ(snee("error render.exr reference.exr --json error.json"), 1) << output();
  EXPECT_TRUE(
      said("error: render.exr against reference.exr: the reference is 8x8 but the "
           "render is 8x4"))
      << output();
  EXPECT_FALSE(std::ifstream(path("error.json")).good()) << "no report of a failed measurement";
}

TEST_F(ErrorCli, UnreadableOrMissingFilesAreNamed) {
  write_exr(flat_film(4, 4, 1.0f, 0.0f, 16), path("reference.exr"));
  std::ofstream(path("broken.exr")) << "not an image";
  EXPECT_EQ(snee("error broken.exr reference.exr"), 1) << output();
  EXPECT_TRUE(said("error: cannot read image 'broken.exr'")) << output();
  EXPECT_EQ(snee("error reference.exr missing.exr"), 1) << output();
  EXPECT_TRUE(said("error: cannot read image 'missing.exr'")) << output();
  EXPECT_NE(snee("error reference.exr"), 0) << "two images are needed";
  EXPECT_TRUE(said("REFERENCE is required")) << output();
}

}  // namespace
}  // namespace snee
