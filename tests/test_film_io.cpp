// Film files: the EXR must round-trip bit-exactly (variance feeds convergence tests) and the
// preview must apply the sRGB curve with clamping.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "scene/film.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class FilmIoTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("film_io"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

Film make_film(int width, int height) {
  Film film;
  film.width = width;
  film.height = height;
  for (int i = 0; i < width * height; ++i) {
    // Values that need every mantissa bit, plus extremes half precision could not hold.
    const float f = static_cast<float>(i);
    film.mean.push_back(Rgb(std::sqrt(f + 0.1f), 1e-30f * (f + 1), 7e5f / (f + 3)));
    film.variance_of_mean.push_back(Rgb(1e-9f * std::exp(f * 0.01f), 3.3e-12f, 0.5f + f));
  }
  film.meta.spp = 1234;
  film.meta.min_spp = 1200;
  film.meta.integrator = "snee";
  film.meta.seed = 4000000000u;
  film.meta.render_seconds = 12.345678901234567;
  film.meta.scene = "furnace-sphere";
  return film;
}

bool bit_equal(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST_F(FilmIoTest, ExrRoundTripIsBitExact) {
  const Film film = make_film(7, 5);
  write_exr(film, file("a.exr"));
  const Film back = read_exr(file("a.exr"));
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.mean.size(), film.mean.size());
  ASSERT_EQ(back.variance_of_mean.size(), film.variance_of_mean.size());
  for (size_t i = 0; i < film.mean.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(bit_equal(back.mean[i][c], film.mean[i][c])) << "pixel " << i << " c " << c;
      EXPECT_TRUE(bit_equal(back.variance_of_mean[i][c], film.variance_of_mean[i][c]))
          << "pixel " << i << " c " << c;
    }
  }
  EXPECT_EQ(back.meta.spp, film.meta.spp);
  EXPECT_EQ(back.meta.min_spp, film.meta.min_spp);
  EXPECT_EQ(back.meta.integrator, film.meta.integrator);
  EXPECT_EQ(back.meta.seed, film.meta.seed);
  EXPECT_EQ(back.meta.render_seconds, film.meta.render_seconds);
  EXPECT_EQ(back.meta.scene, film.meta.scene);
}

TEST_F(FilmIoTest, ExrCarriesNamedChannelsAndStandardMetadata) {
  write_exr(make_film(2, 2), file("a.exr"));
  auto in = OIIO::ImageInput::open(file("a.exr"));
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  for (const char* name : {"R", "G", "B", "variance.R", "variance.G", "variance.B"})
    EXPECT_GE(spec.channelindex(name), 0) << name;
  EXPECT_EQ(spec.get_string_attribute("snee:version"), SNEE_VERSION);
  EXPECT_EQ(spec.get_string_attribute("Software"), "snee " SNEE_VERSION);
}

TEST_F(FilmIoTest, ExrWithoutVarianceReadsBackWithoutVariance) {
  Film film = make_film(3, 2);
  film.variance_of_mean.clear();
  write_exr(film, file("a.exr"));
  const Film back = read_exr(file("a.exr"));
  EXPECT_EQ(back.mean.size(), 6u);
  EXPECT_TRUE(back.variance_of_mean.empty());
}

TEST_F(FilmIoTest, PreviewIsClampedSrgb) {
  Film film;
  film.width = 6;
  film.height = 1;
  film.mean = {Rgb(0.0f),  Rgb(1.0f),  Rgb(0.5f),
               Rgb(-3.0f), Rgb(42.0f), Rgb(std::numeric_limits<float>::quiet_NaN())};
  write_preview(film, file("p.png"));

  auto in = OIIO::ImageInput::open(file("p.png"));
  ASSERT_TRUE(in) << OIIO::geterror();
  ASSERT_EQ(in->spec().width, 6);
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<uint8_t> px(18);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  const int expected[] = {0, 255, 188, 0, 255, 0};
  for (int x = 0; x < 6; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(px[x * 3 + c], expected[x]) << "x " << x;
}

TEST_F(FilmIoTest, UnwritablePathThrowsNamingThePath) {
  const std::string path = file("no/such/dir/a.exr");
  try {
    write_exr(make_film(2, 2), path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_preview(make_film(2, 2), file("no/such/dir/a.png")), std::runtime_error);
}

TEST_F(FilmIoTest, MissingFileThrowsNamingThePath) {
  const std::string path = file("missing.exr");
  try {
    read_exr(path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace snee
