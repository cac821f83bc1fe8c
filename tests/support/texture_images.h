// Texture images that tests write: an 8x8 image of four 4x4 quadrants of known linear colours,
// so lookups inside a quadrant's plateau (between its texel centres) return that colour exactly
// at any bilinear or trilinear filter up to the 2x2 MIP level.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/math.h"
#include "tests/support/test_directory.h"

namespace snee::test {

// Top-left, top-right, bottom-left, bottom-right.
inline constexpr std::array<std::array<float, 3>, 4> kQuadrantColours = {
    {{0.1f, 0.2f, 0.3f}, {0.9f, 0.5f, 0.1f}, {0.3f, 0.7f, 0.2f}, {0.6f, 0.6f, 0.9f}}};

inline Rgb quadrant_colour(int quadrant) {
  const auto& c = kQuadrantColours[static_cast<size_t>(quadrant)];
  return {c[0], c[1], c[2]};
}

// The quadrant image as float RGB at `path` (its extension picks the format; float formats
// keep the values linear).
inline bool write_quadrant_image(const std::string& path) {
  std::vector<float> pixels;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const auto& c = kQuadrantColours[static_cast<size_t>((y / 4) * 2 + x / 4)];
      pixels.insert(pixels.end(), c.begin(), c.end());
    }
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, OIIO::ImageSpec(8, 8, 3, OIIO::TypeDesc::FLOAT))) return false;
  return out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
}

// An 8-bit image of `channels` interleaved values per pixel at `path` (its extension picks the
// format; a PNG stores the values as given).
inline bool write_uint8_image(const std::string& path, int width, int height, int channels,
                              const unsigned char* pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8))) {
    return false;
  }
  return out->write_image(OIIO::TypeDesc::UINT8, pixels) && out->close();
}

// A test with a scratch directory of its own that holds the quadrant image as quadrants.exr.
class QuadrantTextureTest : public ::testing::Test {
 protected:
  explicit QuadrantTextureTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = fresh_test_directory(prefix_);
    ASSERT_TRUE(write_quadrant_image((dir_ / "quadrants.exr").string()));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace snee::test
