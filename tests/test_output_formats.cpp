// `snee render -o FILE.{exr,png,jpg,hdr}` as a user meets it: every file is read back with
// OpenImageIO, the 8-bit preview must be the tone map of the EXR's pixels code value for code
// value, the .hdr its linear radiance, and the EXR must record the settings it was made with.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/film.h"
#include "scene/tone_map.h"
#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTiny = "builtin:sphere-cone-r0.2 --spp 4 --resolution 24x16 --quiet";

struct Image {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // as floats in the file's own scale (8-bit: 0..1)
};

Image read_image(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  Image image;
  if (!in) return image;
  image.spec = in->spec();
  image.pixels.resize(static_cast<size_t>(image.spec.width) * image.spec.height *
                      image.spec.nchannels);
  EXPECT_TRUE(
      in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
      << path;
  return image;
}

class OutputFormats : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("formats"); }
  void TearDown() override { fs::remove_all(dir_); }

  int snee(const std::string& args) {
    const fs::path log = dir_ / "output.txt";
    const int code =
        test::run_command("cd '" + dir_.string() + "' && '" SNEE_BINARY "' " + args, log);
    output_ = test::read_text_file(log);
    return code;
  }
  fs::path file(const std::string& name) const { return dir_ / name; }

  // Every 8-bit code value of `preview` is the tone map of the EXR's mean radiance.
  void expect_preview_of(const fs::path& preview, const fs::path& exr, const ToneMap& tone) {
    const Film film = read_exr(exr.string());
    const Image png = read_image(preview);
    ASSERT_EQ(png.spec.width, film.width);
    ASSERT_EQ(png.spec.height, film.height);
    ASSERT_EQ(png.spec.nchannels, 3);
    EXPECT_EQ(png.spec.format, OIIO::TypeDesc::UINT8);
    int bright = 0;
    for (size_t i = 0; i < film.mean.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const long expected = std::lround(tone.encode(film.mean[i][c]) * 255.0f);
        const long actual = std::lround(png.pixels[i * 3 + c] * 255.0f);
        ASSERT_EQ(actual, expected) << preview << " pixel " << i << " channel " << c;
        bright += actual > 0;
      }
    }
    EXPECT_GT(bright, 0) << "the preview is black: the test would show nothing";
  }

  fs::path dir_;
  std::string output_;
};

TEST_F(OutputFormats, ExrKeepsItsPngPreviewWithTheFilmicCurveByDefault) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o a.exr"), 0) << output_;
  EXPECT_TRUE(fs::is_regular_file(file("a.exr")));
  expect_preview_of(file("a.png"), file("a.exr"), ToneMap{0.0f, ToneCurve::kFilmic});
}

TEST_F(OutputFormats, PngIsTheToneMapOfTheExrWrittenBeside) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o b.png --exposure 1.5"), 0) << output_;
  EXPECT_NE(output_.find("wrote b.exr"), std::string::npos) << output_;
  EXPECT_NE(output_.find("wrote b.png"), std::string::npos) << output_;
  expect_preview_of(file("b.png"), file("b.exr"), ToneMap{1.5f, ToneCurve::kFilmic});
}

TEST_F(OutputFormats, ClampCurveAndNegativeExposure) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o c.png --tone-curve clamp --exposure -1"), 0)
      << output_;
  expect_preview_of(file("c.png"), file("c.exr"), ToneMap{-1.0f, ToneCurve::kClamp});
}

TEST_F(OutputFormats, JpegIsWrittenAsJpegWithTheExrBeside) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o d.jpg"), 0) << output_;
  const Image jpg = read_image(file("d.jpg"));
  auto in = OIIO::ImageInput::open(file("d.jpg").string());
  ASSERT_TRUE(in);
  EXPECT_STREQ(in->format_name(), "jpeg");
  EXPECT_EQ(jpg.spec.width, 24);
  EXPECT_EQ(jpg.spec.height, 16);
  EXPECT_EQ(read_exr(file("d.exr").string()).width, 24);
}

TEST_F(OutputFormats, HdrHoldsTheLinearRadianceOfTheExr) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " -o e.hdr --exposure 3"), 0) << output_;
  auto in = OIIO::ImageInput::open(file("e.hdr").string());
  ASSERT_TRUE(in);
  EXPECT_STREQ(in->format_name(), "hdr");
  const Image hdr = read_image(file("e.hdr"));
  const Film film = read_exr(file("e.exr").string());
  ASSERT_EQ(hdr.spec.width, film.width);
  ASSERT_EQ(hdr.spec.nchannels, 3);
  double sum = 0;
  for (size_t i = 0; i < film.mean.size(); ++i) {
    // RGBE shares one 8-bit exponent per pixel: each channel is exact to 1/256 of the largest.
    const float largest = std::max({film.mean[i][0], film.mean[i][1], film.mean[i][2]});
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(hdr.pixels[i * 3 + c], film.mean[i][c], largest / 128.0f + 1e-30f)
          << "pixel " << i << " channel " << c << ": exposure must not touch .hdr";
      sum += film.mean[i][c];
    }
  }
  EXPECT_GT(sum, 0.0);
}

TEST_F(OutputFormats, ExrRecordsTheSettingsOfTheRender) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " --seed 7 -o f.png --exposure 0.5"), 0)
      << output_;
  auto in = OIIO::ImageInput::open(file("f.exr").string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  const std::string command = spec.get_string_attribute("snee:command_line");
  EXPECT_NE(command.find("render builtin:sphere-cone-r0.2 --spp 4"), std::string::npos) << command;
  EXPECT_NE(command.find("--exposure 0.5"), std::string::npos) << command;
  const std::string hash = spec.get_string_attribute("snee:scene_hash");
  EXPECT_TRUE(hash.starts_with("fnv1a64:")) << hash;
  EXPECT_EQ(spec.get_string_attribute("snee:sample_clamp"), "off");
  const std::string simd = spec.get_string_attribute("snee:simd");
  EXPECT_NE(simd.find(" float lanes), the widest this machine runs"), std::string::npos) << simd;
  const auto options = nlohmann::json::parse(spec.get_string_attribute("snee:render_options"));
  EXPECT_EQ(options["integrator"], "pt");
  EXPECT_EQ(options["spp"], 4);
  EXPECT_EQ(options["seed"], 7);
  EXPECT_EQ(options["resolution"]["width"], 24);
  EXPECT_EQ(options["schedule"], "local");
  EXPECT_EQ(options["preview"]["tone_curve"], "filmic");
  EXPECT_DOUBLE_EQ(options["preview"]["exposure_ev"].get<double>(), 0.5);
  EXPECT_TRUE(options.contains("snee_options"));
}

// 64-bit FNV-1a, written out here again so the EXR's hash is checked against the formula.
std::string fnv1a64(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

TEST_F(OutputFormats, SceneFileHashIsOfItsBytes) {
  const fs::path scene =
      fs::path(SNEE_PROJECT_DATA_DIR).parent_path() / "docs/examples/example.json";
  std::ifstream in(scene, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_FALSE(bytes.empty()) << scene;
  ASSERT_EQ(snee("render '" + scene.string() + "' --spp 1 --resolution 8x8 -q -o g.exr"), 0)
      << output_;
  auto exr = OIIO::ImageInput::open(file("g.exr").string());
  ASSERT_TRUE(exr);
  EXPECT_EQ(exr->spec().get_string_attribute("snee:scene_hash"),
            "fnv1a64:" + fnv1a64(bytes) + " of the bytes of " + scene.string());
}

TEST_F(OutputFormats, SampleClampBoundsEveryPixelAndIsRecordedAsBiased) {
  ASSERT_EQ(snee(std::string("render ") + kTiny + " --clamp 0.05 -o h.exr"), 0) << output_;
  const Film film = read_exr(file("h.exr").string());
  for (const Rgb& rgb : film.mean)
    for (int c = 0; c < 3; ++c) ASSERT_LE(rgb[c], 0.05f);
  auto in = OIIO::ImageInput::open(file("h.exr").string());
  ASSERT_TRUE(in);
  const std::string clamp = in->spec().get_string_attribute("snee:sample_clamp");
  EXPECT_NE(clamp.find("0.05"), std::string::npos) << clamp;
  EXPECT_NE(clamp.find("biased"), std::string::npos) << clamp;
  ASSERT_EQ(snee("render --help"), 0);
  EXPECT_NE(output_.find("BIASED"), std::string::npos) << output_;
}

TEST_F(OutputFormats, BadOutputOptionsFailBeforeRendering) {
  for (const std::string args :
       {"-o x.tif", "--exposure nan", "--clamp 0", "--clamp nan", "--tone-curve aces"}) {
    EXPECT_NE(snee(std::string("render ") + kTiny + " " + args), 0) << args;
    EXPECT_NE(output_.find("error"), std::string::npos) << args << "\n" << output_;
    EXPECT_EQ(output_.find("rendered"), std::string::npos) << args << "\n" << output_;
    if (args == "-o x.tif") {
      EXPECT_NE(output_.find(".exr, .png, .jpg, .jpeg or .hdr"), std::string::npos) << output_;
      EXPECT_FALSE(fs::exists(file("x.tif")));
      EXPECT_FALSE(fs::exists(file("x.exr")));
    }
  }
}

}  // namespace
}  // namespace snee
