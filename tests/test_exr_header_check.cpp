// The EXR header walk made before OpenImageIO reads a file: every EXR that OpenImageIO writes
// (scanline, tiled, deep, multi-part, long names) passes; a declared attribute size beyond the
// file, a truncated header or a field OpenEXR 2 does not define is an error naming the file,
// the attribute and the sizes.
#include <gtest/gtest.h>

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scene/exr_header_check.h"
#include "scene/scene_error.h"
#include "tests/support/exr_reproducers.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

const std::string kPath = "sky.exr";

std::string error_of(const std::string& bytes) {
  return test::scene_error_of([&] { check_exr_header(bytes, kPath); });
}

// The message of the SceneError check_exr_header throws, or "" when it passes.
std::string error_of_if_any(const std::string& bytes) {
  try {
    check_exr_header(bytes, kPath);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void put_u32(std::string& bytes, size_t at, uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>(value >> (8 * i) & 0xff);
}

uint32_t little_endian(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

// The offset of the size field of the `occurrence`-th attribute named `name` of type `type`.
size_t size_field_of(const std::string& bytes, const std::string& name, const std::string& type,
                     int occurrence = 0) {
  const std::string key = name + '\0' + type + '\0';
  size_t at = bytes.find(key);
  for (int i = 0; i < occurrence && at != std::string::npos; ++i) at = bytes.find(key, at + 1);
  EXPECT_NE(at, std::string::npos) << name;
  return at + key.size();
}

class ExrHeaderCheckTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("test_exr_header_check"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // A 4x2 RGB float EXR with `specs.size()` parts.
  std::string write_exr(const std::string& name, std::vector<OIIO::ImageSpec> specs) {
    const std::string path = (dir_ / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out) << OIIO::geterror();
    EXPECT_TRUE(out->open(path, static_cast<int>(specs.size()), specs.data())) << out->geterror();
    for (size_t part = 0; part < specs.size(); ++part) {
      if (part > 0) {
        EXPECT_TRUE(out->open(path, specs[part], OIIO::ImageOutput::AppendSubimage));
      }
      const OIIO::ImageSpec& spec = specs[part];
      if (spec.deep) {
        OIIO::DeepData deep(spec);
        for (int64_t pixel = 0; pixel < static_cast<int64_t>(spec.image_pixels()); ++pixel) {
          deep.set_samples(pixel, 1);
          for (int c = 0; c < spec.nchannels; ++c) deep.set_deep_value(pixel, c, 0, 0.5f);
        }
        EXPECT_TRUE(out->write_deep_image(deep)) << out->geterror();
      } else {
        const std::vector<float> pixels(spec.image_pixels() * spec.nchannels, 0.5f);
        EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
      }
    }
    out->close();
    return bytes_of(path);
  }

  fs::path dir_;
};

OIIO::ImageSpec rgb_spec() {
  return OIIO::ImageSpec(4, 2, 3, OIIO::TypeDesc::FLOAT);
}

TEST_F(ExrHeaderCheckTest, EveryKindOfExrOpenImageIoWritesPasses) {
  OIIO::ImageSpec scanline = rgb_spec();
  OIIO::ImageSpec tiled = rgb_spec();
  tiled.tile_width = tiled.tile_height = 16;
  OIIO::ImageSpec long_names = rgb_spec();
  long_names.attribute("an_attribute_name_longer_than_thirty_one_bytes", "set");
  // Values of types the walk measures by their layout (m44f, v2f, int, float, stringvector).
  OIIO::ImageSpec typed = rgb_spec();
  const float matrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  typed.attribute("worldToCamera", OIIO::TypeDesc::TypeMatrix44, matrix);
  const char* views[] = {"left", "right", ""};
  typed.attribute("multiView", OIIO::TypeDesc(OIIO::TypeDesc::STRING, 3), views);
  OIIO::ImageSpec deep(4, 2, 0, OIIO::TypeDesc::FLOAT);
  deep.channelnames.clear();
  for (const char* channel : {"R", "G", "B", "A", "Z"}) deep.channelnames.push_back(channel);
  deep.nchannels = 5;
  deep.alpha_channel = 3;
  deep.z_channel = 4;
  deep.deep = true;
  const std::vector<std::pair<std::string, std::vector<OIIO::ImageSpec>>> files = {
      {"scanline.exr", {scanline}}, {"typed.exr", {typed}},
      {"tiled.exr", {tiled}},       {"long_names.exr", {long_names}},
      {"deep.exr", {deep}},         {"multipart.exr", {scanline, scanline, scanline}},
  };
  for (const auto& [name, specs] : files) {
    const std::string bytes = write_exr(name, specs);
    ASSERT_TRUE(has_exr_magic(bytes)) << name;
    EXPECT_NO_THROW(check_exr_header(bytes, name)) << name;
  }
  // The attribute types the walk measures are really in these files.
  const std::string with_types = write_exr("typed.exr", {typed});
  for (const char* type : {"m44f", "stringvector", "chlist", "box2i", "compression", "v2f"}) {
    EXPECT_NE(with_types.find(std::string(type) + '\0'), std::string::npos) << type;
  }
  // The flags the walk must honour are really set in these files.
  EXPECT_NE(write_exr("long_names.exr", {long_names})[5] & 0x04, 0);
  EXPECT_NE(write_exr("deep.exr", {deep})[5] & 0x08, 0);
  EXPECT_NE(write_exr("multipart.exr", {scanline, scanline})[5] & 0x10, 0);
}

TEST_F(ExrHeaderCheckTest, OtherFormatsAreLeftAlone) {
  EXPECT_FALSE(has_exr_magic("#?RADIANCE\n"));
  EXPECT_NO_THROW(check_exr_header("#?RADIANCE\n", kPath));
  EXPECT_NO_THROW(check_exr_header("", kPath));
}

TEST_F(ExrHeaderCheckTest, TheFuzzerReproducerIsRefused) {
  const std::string bytes = test::exr_huge_string_attribute();
  ASSERT_EQ(bytes.size(), 379u);
  // The size field ends at byte 8 + "capDate\0" + "string\0" + 4 = 27.
  EXPECT_EQ(error_of(bytes), kPath +
                                 ": EXR header: attribute 'capDate' (string) declares "
                                 "1467572588 bytes, but only 352 bytes follow in the file");
}

TEST_F(ExrHeaderCheckTest, TheChannelListReproducerIsRefused) {
  const std::string bytes = test::exr_channel_list_shorter_than_declared();
  ASSERT_EQ(bytes.size(), 375u);
  EXPECT_EQ(error_of(bytes), kPath +
                                 ": EXR header: attribute '9v/1\x01"
                                 "996cha0/v\x13s' (chlist) "
                                 "declares 55 bytes, but its channel list takes 19");
}

// OpenEXR reads a value of a type it knows by that type's layout and carries on from where the
// layout ended, so a declared size that differs from it is refused, for each kind of layout.
TEST_F(ExrHeaderCheckTest, ValuesMustTakeTheirDeclaredSize) {
  const std::string valid = write_exr("valid.exr", {rgb_spec()});
  // A fixed-size type: dataWindow (box2i) is 16 bytes; declaring 8 is refused (the 8 that
  // follow must still be in the file, so only a smaller size reaches this check).
  std::string box = valid;
  put_u32(box, size_field_of(valid, "dataWindow", "box2i"), 8);
  EXPECT_EQ(error_of(box), kPath +
                               ": EXR header: attribute 'dataWindow' (box2i) declares 8 bytes, "
                               "but a value of its type takes 16");
  // A channel list: RGB takes 3 * (2 + 16) + 1 = 55 bytes.
  std::string channels = valid;
  const size_t chlist = size_field_of(valid, "channels", "chlist");
  EXPECT_EQ(little_endian(valid, chlist), 55u);
  put_u32(channels, chlist, 60);
  EXPECT_EQ(error_of(channels), kPath +
                                    ": EXR header: attribute 'channels' (chlist) declares 60 "
                                    "bytes, but its channel list takes 55");

  // Hand-made headers for the types OpenImageIO does not write here.
  const auto header = [](const std::string& type, const std::string& value, uint32_t declared) {
    std::string bytes("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
    bytes += std::string("a") + '\0' + type + '\0' + "????" + value + '\0';
    put_u32(bytes, 8 + 2 + type.size() + 1, declared);
    return bytes;
  };
  const auto u32 = [](uint32_t v) {
    std::string out(4, '\0');
    put_u32(out, 0, v);
    return out;
  };
  // A preview: width, height and 4 bytes per pixel, allocated by OpenEXR before it reads them.
  const std::string preview = u32(2) + u32(1) + std::string(8, '\x7f');
  EXPECT_NO_THROW(check_exr_header(header("preview", preview, 16), kPath));
  EXPECT_EQ(error_of(header("preview", u32(65535) + u32(65535) + std::string(8, '\x7f'), 16)),
            kPath +
                ": EXR header: attribute 'a' (preview) declares 16 bytes, but its "
                "65535x65535 preview takes 17179344908");
  // A string vector: each string's 32-bit length must stay within the declared size.
  const std::string strings = u32(4) + "left" + u32(5) + "right";
  EXPECT_NO_THROW(check_exr_header(header("stringvector", strings, 17), kPath));
  EXPECT_EQ(error_of(header("stringvector", u32(4) + "left" + u32(0x7fffffff), 12)),
            kPath +
                ": EXR header: attribute 'a' (stringvector) holds a string of 2147483647 "
                "bytes where only 0 are left of its 12");
  EXPECT_EQ(error_of(header("stringvector", u32(0xffffffff) + "left", 8)),
            kPath +
                ": EXR header: attribute 'a' (stringvector) holds a string of -1 bytes "
                "where only 4 are left of its 8");
  // A float vector is a whole number of floats.
  EXPECT_NO_THROW(check_exr_header(header("floatvector", std::string(8, '\0'), 8), kPath));
  EXPECT_EQ(error_of(header("floatvector", std::string(8, '\0'), 6)),
            kPath +
                ": EXR header: attribute 'a' (floatvector) declares 6 bytes, but a whole "
                "number of floats takes 4");
  // A type OpenEXR does not know is opaque bytes of any declared size.
  EXPECT_NO_THROW(check_exr_header(header("snee_private", std::string(5, 'x'), 5), kPath));
}

TEST_F(ExrHeaderCheckTest, DeclaredSizesBeyondTheFileAreErrors) {
  const std::string valid = write_exr("valid.exr", {rgb_spec()});
  std::string oversized = valid;
  const size_t field = size_field_of(valid, "compression", "compression");
  put_u32(oversized, field, 1000000);
  EXPECT_EQ(error_of(oversized),
            kPath +
                ": EXR header: attribute 'compression' (compression) declares 1000000 bytes, "
                "but only " +
                std::to_string(valid.size() - field - 4) + " bytes follow in the file");

  std::string negative = valid;
  put_u32(negative, field, 0xffffff00u);
  EXPECT_EQ(error_of(negative), kPath +
                                    ": EXR header: attribute 'compression' (compression) "
                                    "declares a negative size (-256)");

  // In a multi-part file the part is named too.
  const std::string parts = write_exr("parts.exr", {rgb_spec(), rgb_spec()});
  std::string second = parts;
  put_u32(second, size_field_of(parts, "compression", "compression", 1), 0x7fffffff);
  EXPECT_NE(error_of(second).find(kPath + ": EXR header of part 1: attribute 'compression' "
                                          "(compression) declares 2147483647 bytes"),
            std::string::npos)
      << error_of(second);
}

TEST_F(ExrHeaderCheckTest, TruncatedHeadersAreErrors) {
  const std::string valid = write_exr("valid.exr", {rgb_spec()});
  const size_t field = size_field_of(valid, "compression", "compression");
  EXPECT_EQ(error_of(valid.substr(0, 6)), kPath + ": EXR header: the file ends inside the version");
  EXPECT_EQ(error_of(valid.substr(0, field + 2)),
            kPath +
                ": EXR header: the file ends inside the size of attribute 'compression' "
                "(compression)");
  EXPECT_EQ(error_of(valid.substr(0, field - 3)),
            kPath + ": EXR header: the file ends inside the type name of attribute 'compression'");
  EXPECT_EQ(error_of(valid.substr(0, 10)),
            kPath + ": EXR header: the file ends inside the attribute name");
  // Every cut inside the header is refused. The header ends where the offset table begins: its
  // one entry (ZIP holds both scanlines in one chunk) points just past itself.
  size_t header_end = 8;
  while (header_end < valid.size() && !error_of_if_any(valid.substr(0, header_end)).empty()) {
    ++header_end;
  }
  uint64_t first_chunk = 0;
  for (int i = 7; i >= 0; --i) {
    first_chunk = first_chunk << 8 | static_cast<unsigned char>(valid[header_end + i]);
  }
  EXPECT_EQ(first_chunk, header_end + 8);
  for (size_t cut = 4; cut < header_end; ++cut) {  // shorter: no EXR magic, left alone
    EXPECT_NE(error_of_if_any(valid.substr(0, cut)).find(kPath + ": EXR header"), std::string::npos)
        << "cut at " << cut;
  }
}

TEST_F(ExrHeaderCheckTest, FieldsOpenExr2DoesNotDefineAreErrors) {
  const std::string valid = write_exr("valid.exr", {rgb_spec()});
  std::string version3 = valid;
  version3[4] = 3;
  EXPECT_EQ(error_of(version3), kPath + ": EXR header: version 3 (expected 2)");

  std::string unknown_flag = valid;
  unknown_flag[5] = static_cast<char>(unknown_flag[5] | 0x20);
  EXPECT_EQ(error_of(unknown_flag),
            kPath + ": EXR header: unknown flags 0x2000 in the version field");

  // Names are limited to 31 bytes unless the long-names flag is set.
  std::string long_name("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  long_name += std::string(32, 'n') + '\0' + "int" + '\0' + std::string("\4\0\0\0\0\0\0\0\0", 9);
  EXPECT_EQ(error_of(long_name),
            kPath + ": EXR header: the attribute name is longer than 31 bytes");
  long_name[5] = 0x04;
  EXPECT_NO_THROW(check_exr_header(long_name, kPath));
}

}  // namespace
}  // namespace snee
