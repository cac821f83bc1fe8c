// Environment images: channel handling and colour decoding for each kind of file OIIO writes.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "scene/rgb_image_io.h"
#include "scene/scene_error.h"
#include "tests/support/exr_reproducers.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class EnvImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("test_env_image_io"); }
  void TearDown() override { fs::remove_all(dir_); }

  template <typename T>
  std::string write_image(const std::string& name, int width, int height, int channels,
                          OIIO::TypeDesc format, const std::vector<T>& pixels) {
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out) << OIIO::geterror();
    const OIIO::ImageSpec spec(width, height, channels, format);
    EXPECT_TRUE(out->open(path, spec));
    EXPECT_TRUE(out->write_image(OIIO::BaseTypeFromC<T>::value, pixels.data()));
    out->close();
    return path;
  }

  fs::path dir_;
};

long peak_rss_kib() {
  struct rusage usage {};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// A little-endian 8-bit RGB TIFF of one deflate-compressed strip whose RowsPerStrip tag says
// rows_per_strip, whatever the height. Every byte is 128. With valid_stream false the strip is
// not a zlib stream at all.
std::string deflate_tiff(uint32_t width, uint32_t height, uint32_t rows_per_strip,
                         bool valid_stream) {
  std::string out;
  const auto put16 = [&out](uint32_t v) {
    for (int i = 0; i < 2; ++i) out.push_back(static_cast<char>(v >> (8 * i) & 0xff));
  };
  const auto put32 = [&out](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(v >> (8 * i) & 0xff));
  };
  const std::string pixels(width * height * 3, '\x80');
  std::string strip;
  if (valid_stream) {
    // A zlib stream of one stored (uncompressed) deflate block, which needs no compressor.
    const auto size = static_cast<uint32_t>(pixels.size());
    uint32_t a = 1, b = 0;
    for (const char c : pixels) {
      a = (a + static_cast<unsigned char>(c)) % 65521;
      b = (b + a) % 65521;
    }
    const uint32_t adler = b << 16 | a;
    strip = {'\x78', '\x01', '\x01'};
    for (const uint32_t v : {size & 0xff, size >> 8 & 0xff, ~size & 0xff, ~size >> 8 & 0xff}) {
      strip.push_back(static_cast<char>(v));
    }
    strip += pixels;
    for (int i = 3; i >= 0; --i) strip.push_back(static_cast<char>(adler >> (8 * i) & 0xff));
  } else {
    strip = pixels;
  }
  struct Entry {
    uint16_t tag, type;
    uint32_t value;
  };
  constexpr uint16_t kShort = 3, kLong = 4;
  constexpr uint32_t kEntries = 10;
  const uint32_t strip_offset = 8 + 2 + 12 * kEntries + 4;
  const Entry entries[kEntries] = {{256, kLong, width},
                                   {257, kLong, height},
                                   {258, kShort, 8},
                                   {259, kShort, 8},  // bits per sample; deflate
                                   {262, kShort, 2},
                                   {273, kLong, strip_offset},  // RGB; strip offset
                                   {277, kShort, 3},
                                   {278, kLong, rows_per_strip},
                                   {279, kLong, static_cast<uint32_t>(strip.size())},
                                   {284, kShort, 1}};  // contiguous
  out = "II*";
  out.push_back('\0');
  put32(8);
  put16(kEntries);
  for (const Entry& e : entries) {
    put16(e.tag);
    put16(e.type);
    put32(1);
    if (e.type == kShort) {
      put16(e.value);
      put16(0);
    } else {
      put32(e.value);
    }
  }
  put32(0);
  return out + strip;
}

std::string error_of(const std::string& path, const MemoryBudget& budget = {}) {
  try {
    read_env_image(path, budget);
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for " << path;
  return "";
}

TEST_F(EnvImageIoTest, FloatExrIsLinearAndKeepsFirstThreeChannels) {
  const std::vector<float> rgba = {0.5f, 2.0f, 100.0f, 0.1f, 0.0f, 0.25f, 7.0f, 1.0f,
                                   1.0f, 3.0f, 0.125f, 0.3f, 4.0f, 5.0f,  6.0f, 0.0f};
  const RgbImage image =
      read_env_image(write_image("rgba.exr", 2, 2, 4, OIIO::TypeDesc::FLOAT, rgba));
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.pixels.size(), 4u);
  EXPECT_EQ(image.pixels[0], Rgb(0.5f, 2.0f, 100.0f));
  EXPECT_EQ(image.pixels[1], Rgb(0.0f, 0.25f, 7.0f));
  EXPECT_EQ(image.pixels[3], Rgb(4.0f, 5.0f, 6.0f));  // bottom right: row-major, top row first
}

TEST_F(EnvImageIoTest, OneChannelBecomesGrey) {
  const std::vector<float> grey = {0.25f, 8.0f, 1.5f};
  const RgbImage image =
      read_env_image(write_image("grey.exr", 3, 1, 1, OIIO::TypeDesc::FLOAT, grey));
  EXPECT_EQ(image.pixels[1], Rgb(8.0f));
  EXPECT_EQ(image.pixels[2], Rgb(1.5f));
}

TEST_F(EnvImageIoTest, EightBitPngIsSrgbDecoded) {
  const std::vector<unsigned char> rgb = {0, 128, 255, 255, 255, 255};
  const RgbImage image =
      read_env_image(write_image("srgb.png", 2, 1, 3, OIIO::TypeDesc::UINT8, rgb));
  EXPECT_EQ(image.pixels[0].x, 0.0f);
  // sRGB 128/255 = 0.50196 decodes to ((0.50196 + 0.055) / 1.055)^2.4 = 0.21586.
  EXPECT_NEAR(image.pixels[0].y, 0.215861f, 1e-5f);
  EXPECT_NEAR(image.pixels[0].z, 1.0f, 1e-6f);
  EXPECT_NEAR(image.pixels[1].x, 1.0f, 1e-6f);
}

TEST_F(EnvImageIoTest, RadianceHdrIsLinear) {
  const std::vector<float> rgb = {1.0f, 0.5f, 4.0f};
  const RgbImage image =
      read_env_image(write_image("sky.hdr", 1, 1, 3, OIIO::TypeDesc::FLOAT, rgb));
  // RGBE keeps 8 mantissa bits per channel relative to the largest.
  EXPECT_NEAR(image.pixels[0].x, 1.0f, 0.02f);
  EXPECT_NEAR(image.pixels[0].y, 0.5f, 0.02f);
  EXPECT_NEAR(image.pixels[0].z, 4.0f, 0.02f);
}

TEST_F(EnvImageIoTest, ErrorsNameTheFile) {
  const std::string missing = (dir_ / "missing.exr").string();
  const std::string message = error_of(missing);
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;

  const std::string garbage = (dir_ / "garbage.exr").string();
  std::ofstream(garbage) << "this is not an image";
  EXPECT_NE(error_of(garbage).find(garbage), std::string::npos);

  const std::vector<float> nan = {1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f};
  const std::string bad = write_image("nan.exr", 1, 1, 3, OIIO::TypeDesc::FLOAT, nan);
  const std::string nan_message = error_of(bad);
  EXPECT_NE(nan_message.find("nan.exr"), std::string::npos) << nan_message;
  EXPECT_NE(nan_message.find("pixel (0, 0)"), std::string::npos) << nan_message;
}

// Every format snee's scenes use is read from memory (the file checked to be a regular one).
TEST_F(EnvImageIoTest, CommonFormatsLoad) {
  const std::vector<unsigned char> rgb = {10, 20, 30, 40, 50, 60};
  for (const char* name : {"sky.tif", "sky.jpg", "sky.bmp", "sky.tga"}) {
    const RgbImage image = read_env_image(write_image(name, 2, 1, 3, OIIO::TypeDesc::UINT8, rgb));
    EXPECT_EQ(image.width, 2) << name;
    EXPECT_GT(image.pixels[1].z, image.pixels[0].x) << name;
  }
}

// A 60-byte Radiance header claiming 10^10 pixels made the reader ask for 120 GB at once.
TEST_F(EnvImageIoTest, DecodedSizeBeyondTheMemoryBudgetIsAnError) {
  const std::string path = (dir_ / "huge.hdr").string();
  std::ofstream(path) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n";
  try {
    read_env_image(path, MemoryBudget{uint64_t{1} << 30});
    ADD_FAILURE() << "no error for " << path;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  path + ": the decoded 100000x100000 pixels of 3 channels need 223.5 GiB, more "
                         "than the memory budget of 1.0 GiB (--max-memory)"),
              std::string::npos)
        << e.what();
  }

  const std::vector<float> rgb(64 * 64 * 3, 0.5f);
  const std::string small = write_image("small.exr", 64, 64, 3, OIIO::TypeDesc::HALF, rgb);
  EXPECT_EQ(read_env_image(small, MemoryBudget{200 << 10}).pixels.size(), 64u * 64u);
  EXPECT_NE(error_of(small, MemoryBudget{64 << 10}).find("need 96.0 KiB"), std::string::npos);
}

// OpenImageIO opened the path itself, so a FIFO there blocked the load for ever.
TEST_F(EnvImageIoTest, OnlyRegularFilesAreRead) {
  const std::string fifo = (dir_ / "sky.exr").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  EXPECT_NE(error_of(fifo).find(fifo + ": cannot read environment image: it is a FIFO"),
            std::string::npos);
}

// The 379-byte fuzzer reproducer made OpenEXR allocate about 1.4 GB for one string attribute
// and read it for minutes; the 375-byte one made it read a 1.9 GB string size from inside a
// channel list shorter than declared. Both are refused from the header walk before OpenImageIO
// allocates anything; the peak resident size grows by less than the files could ever justify.
TEST_F(EnvImageIoTest, ExrAttributeSizeBeyondTheFileIsRefusedBeforeAllocating) {
  const std::string path = (dir_ / "huge-string-attribute.exr").string();
  std::ofstream(path, std::ios::binary) << test::exr_huge_string_attribute();
  const long peak_before_kib = peak_rss_kib();
  EXPECT_EQ(error_of(path), path +
                                ": EXR header: attribute 'capDate' (string) declares "
                                "1467572588 bytes, but only 352 bytes follow in the file");
  const std::string channels = (dir_ / "short-channel-list.exr").string();
  std::ofstream(channels, std::ios::binary) << test::exr_channel_list_shorter_than_declared();
  EXPECT_NE(error_of(channels).find(channels + ": EXR header: attribute "), std::string::npos)
      << error_of(channels);
  EXPECT_LT(peak_rss_kib() - peak_before_kib, 64 * 1024);
}

// The fuzzer's 8 GB allocation: a 4x4 deflate TIFF claiming 2^31 - 1 rows per strip made
// read_image convert through a buffer of whole strips sized by that claim, and made a render
// with it as the environment decode for half an hour. Valid strips read right whatever the
// claim; a broken one is an error naming the row; neither grows the peak resident size.
TEST_F(EnvImageIoTest, RowsPerStripBeyondTheImageSizesNoBuffer) {
  const long peak_before_kib = peak_rss_kib();
  for (const uint32_t rows_per_strip : {100000u, 2147483647u}) {
    const std::string name = "rps" + std::to_string(rows_per_strip);
    const std::string valid = (dir_ / (name + ".tif")).string();
    std::ofstream(valid, std::ios::binary) << deflate_tiff(4, 3, rows_per_strip, true);
    const RgbImage image = read_env_image(valid);
    ASSERT_EQ(image.pixels.size(), 12u) << valid;
    const float expected = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
    for (const Rgb& p : image.pixels) EXPECT_FLOAT_EQ(p.y, expected) << valid;

    const std::string broken = (dir_ / (name + "-broken.tif")).string();
    std::ofstream(broken, std::ios::binary) << deflate_tiff(4, 4, rows_per_strip, false);
    EXPECT_NE(error_of(broken).find(broken + ": cannot decode environment image at row 0: "),
              std::string::npos)
        << error_of(broken);
  }
  EXPECT_LT(peak_rss_kib() - peak_before_kib, 64 * 1024);
}

// Tiled files are read a row of tiles at a time, partial tiles at the right and bottom included.
TEST_F(EnvImageIoTest, TiledImagesReadRowsOfTiles) {
  constexpr int kWidth = 40, kHeight = 20;
  std::vector<float> rgb(kWidth * kHeight * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(i);
  for (const char* name : {"tiled.exr", "tiled.tif"}) {
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(kWidth, kHeight, 3, OIIO::TypeDesc::FLOAT);
    spec.tile_width = spec.tile_height = 16;
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data())) << out->geterror();
    out->close();
    ASSERT_GT(OIIO::ImageInput::open(path)->spec().tile_width, 0) << path;

    const RgbImage image = read_env_image(path);
    ASSERT_EQ(image.pixels.size(), static_cast<size_t>(kWidth * kHeight)) << path;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      ASSERT_EQ(image.pixels[i].x, rgb[3 * i]) << path << " pixel " << i;
      ASSERT_EQ(image.pixels[i].z, rgb[3 * i + 2]) << path << " pixel " << i;
    }
    // 19200 bytes of decoded pixels and 9216 of tiles (three across, 16x16 of 12 bytes).
    const std::string message = error_of(path, MemoryBudget{kWidth * kHeight * 24 + 1000});
    EXPECT_NE(message.find(path + ": the decoded 40x20 pixels of 3 channels and a row of 16x16 "
                                  "tiles need 27.8 KiB, more than the memory budget of 19.7 KiB"),
              std::string::npos)
        << message;
  }
}

// The fuzzer found an EXR whose line offset table points before the start of the file: OpenEXR
// seeks there (offsets are unsigned; -1 passes its check that they are not zero) and
// OpenImageIO 2.4's in-memory reader then copied from before its buffer, whose bounds check
// wraps around for a negative position. Every offset is tried: the first and last row, and
// positions before, at and beyond both ends of the file. Each one either reads the right pixels
// (OpenEXR rebuilds a table it finds wrong by walking the rows) or is an error naming the file
// and row; under AddressSanitizer no read leaves the file's bytes.
TEST_F(EnvImageIoTest, ExrLineOffsetsOutsideTheFileAreErrors) {
  constexpr int kRows = 2;
  // Uncompressed, so that each row is a chunk with its own offset.
  const std::string path = (dir_ / "offsets.exr").string();
  std::string file;
  {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(1, kRows, 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "none");
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    const std::vector<float> pixels(3 * kRows, 0.5f);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    out->close();
    ASSERT_EQ(read_env_image(path).pixels.size(), size_t{kRows});
    std::ifstream in(path, std::ios::binary);
    file.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The table is the kRows eight-byte offsets just before the first row, which the first of
  // them points at.
  const auto offset_at = [&file](size_t at) {
    uint64_t value = 0;
    for (int i = 7; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(file[at + i]);
    return value;
  };
  size_t table = 0;
  while (table + 8 * kRows <= file.size() && offset_at(table) != table + 8 * kRows) ++table;
  ASSERT_LT(table + 8 * kRows, file.size()) << "no line offset table in " << path;
  const auto size = static_cast<int64_t>(file.size());
  for (int row = 0; row < kRows; ++row) {
    for (const int64_t offset : {int64_t{-1}, int64_t{-4}, int64_t{-1} << 40, size - 1, size,
                                 size + 3, int64_t{1} << 40}) {
      std::string corrupt = file;
      for (int i = 0; i < 8; ++i) {
        corrupt[table + 8 * row + i] = static_cast<char>(static_cast<uint64_t>(offset) >> (8 * i));
      }
      const std::string name =
          (dir_ / ("row" + std::to_string(row) + "-at" + std::to_string(offset) + ".exr")).string();
      std::ofstream(name, std::ios::binary) << corrupt;
      try {
        const RgbImage image = read_env_image(name);
        for (const Rgb& p : image.pixels) EXPECT_EQ(p, Rgb(0.5f)) << name;
      } catch (const SceneError& e) {
        EXPECT_EQ(
            std::string(e.what()).rfind(name + ": cannot decode environment image at row ", 0), 0u)
            << e.what();
      }
    }
  }
}

// Images snee cannot use as a lat-long map are refused by name, not read into a wrong layout.
// OpenImageIO 2.4 writes no volume that reads back as one (its TIFF volumes read back flat),
// so the volume is a hand-made 4x4x3 DDS volume texture (the DDS reader keeps the depth).
TEST_F(EnvImageIoTest, VolumesAndDeepImagesAreRefused) {
  std::string dds = "DDS ";
  const auto put = [&dds](std::initializer_list<uint32_t> words) {
    for (const uint32_t w : words) {
      for (int i = 0; i < 4; ++i) dds.push_back(static_cast<char>(w >> (8 * i) & 0xff));
    }
  };
  constexpr uint32_t kCapsHeightWidthPixelFormatDepth = 0x1 | 0x2 | 0x4 | 0x1000 | 0x800000;
  put({124, kCapsHeightWidthPixelFormatDepth, 4, 4, 16, 3, 0});  // size, flags, h, w, pitch, d
  dds.append(44, '\0');                                          // reserved
  put({32, 0x40, 0, 32, 0xff0000, 0xff00, 0xff, 0});  // pixel format: 32-bit RGB with masks
  put({0x1008, 0x200000, 0, 0, 0});                   // caps: complex texture; caps2: volume
  dds.append(4 * 4 * 3 * 4, '\x80');
  const std::string volume = (dir_ / "volume.dds").string();
  std::ofstream(volume, std::ios::binary) << dds;
  EXPECT_EQ(error_of(volume),
            volume + ": the environment image is a volume of 3 slices (expected a flat image)");

  const std::string deep = (dir_ / "deep.exr").string();
  auto out = OIIO::ImageOutput::create(deep);
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(2, 2, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "Z"};
  spec.z_channel = 3;
  spec.deep = true;
  ASSERT_TRUE(out->open(deep, spec)) << out->geterror();
  OIIO::DeepData samples(spec);
  for (int64_t pixel = 0; pixel < 4; ++pixel) {
    samples.set_samples(pixel, 1);
    for (int c = 0; c < 4; ++c) samples.set_deep_value(pixel, c, 0, 1.0f);
  }
  ASSERT_TRUE(out->write_deep_image(samples)) << out->geterror();
  out->close();
  EXPECT_EQ(error_of(deep), deep +
                                ": the environment image is a deep image (a list of samples "
                                "per pixel; expected a flat image)");
}

}  // namespace
}  // namespace snee
