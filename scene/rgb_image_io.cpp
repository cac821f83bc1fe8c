#include "scene/rgb_image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/exr_header_check.h"
#include "scene/input_file.h"
#include "scene/memory_reader.h"
#include "scene/scene_error.h"

namespace snee {

namespace {

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

bool is_srgb_encoded(const OIIO::ImageSpec& spec) {
  const std::string color_space = spec.get_string_attribute("oiio:ColorSpace");
  if (OIIO::Strutil::iequals(color_space, "sRGB")) return true;
  if (OIIO::Strutil::iequals(color_space, "Linear")) return false;
  return !spec.format.is_floating_point();
}

// Decodes every pixel to float, a band at a time so that no buffer is sized by anything but the
// image's own size. OpenImageIO's read_image converts through a buffer of a whole number of TIFF
// strips, sized by the RowsPerStrip tag and not by the image's height: a 4x4 deflate TIFF
// claiming 2^31 rows per strip made it ask for gigabytes or decode for half an hour. Reading one
// scanline (or one row of tiles) at a time converts through a buffer of that one band;
// decoded_what and decoded_bytes describe the float pixels and the image made from them, already
// checked against the budget; a row of tiles is read while they are held.
std::vector<float> decode_as_float(OIIO::ImageInput& input, const std::string& path,
                                   std::string_view what, const MemoryBudget& budget,
                                   const std::string& decoded_what, uint64_t decoded_bytes) {
  const OIIO::ImageSpec& spec = input.spec();
  const size_t row_values = static_cast<size_t>(spec.width) * spec.nchannels;
  std::vector<float> data(row_values * spec.height);
  const auto fail = [&](int row) {
    return SceneError(path + ": cannot decode " + std::string(what) + " at row " +
                      std::to_string(row) + ": " + input.geterror());
  };
  if (spec.tile_width <= 0) {
    for (int row = 0; row < spec.height; ++row) {
      if (!input.read_scanline(spec.y + row, spec.z, OIIO::TypeDesc::FLOAT,
                               &data[row * row_values])) {
        throw fail(row);
      }
    }
    return data;
  }
  // OpenImageIO reads a row of tiles whole, in the file's own format, before converting it.
  const uint64_t tiles_across = (static_cast<uint64_t>(spec.width) + spec.tile_width - 1) /
                                static_cast<uint64_t>(spec.tile_width);
  const uint64_t needed =
      saturating_add(decoded_bytes, saturating_multiply(tiles_across, spec.tile_bytes(true)));
  if (!budget.allows(needed)) {
    throw SceneError(path + ": " +
                     budget.exceeded(decoded_what + " and a row of " +
                                         std::to_string(spec.tile_width) + "x" +
                                         std::to_string(spec.tile_height) + " tiles",
                                     needed));
  }
  for (int row = 0; row < spec.height; row += spec.tile_height) {
    const int rows = std::min(spec.tile_height, spec.height - row);
    if (!input.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + row, spec.y + row + rows,
                          spec.z, spec.z + 1, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                          &data[row * row_values])) {
      throw fail(row);
    }
  }
  return data;
}

}  // namespace

RgbImage decode_rgb_image(const std::string& bytes, const std::string& path, std::string_view what,
                          const MemoryBudget& budget, PixelValues values) {
  // OpenEXR would allocate what an attribute's size claims before reading it.
  check_exr_header(bytes, path);
  MemoryReader memory(bytes);
  // The colour channels as stored: a PNG's alpha would otherwise be multiplied into them (a
  // texel of alpha 0 reading black), while snee ignores alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // With a configuration the readers take the proxy from it, not from open's argument (without
  // it they would open `path` as a file: an image inside a .glb has no file).
  OIIO::Filesystem::IOProxy* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto input = OIIO::ImageInput::open(path, &config, &memory);
  if (!input) {
    throw SceneError(path + ": cannot read " + std::string(what) + ": " + OIIO::geterror());
  }
  const OIIO::ImageSpec spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw SceneError(path + ": the " + std::string(what) + " is empty");
  }
  // read_image cannot read deep pixels into a flat buffer and would fail with a message about
  // its own internals.
  if (spec.deep) {
    throw SceneError(path + ": the " + std::string(what) +
                     " is a deep image (a list of samples per pixel; "
                     "expected a flat image)");
  }
  // read_image would write every slice of a volume into a buffer sized for one.
  if (spec.depth != 1) {
    throw SceneError(path + ": the " + std::string(what) + " is a volume of " +
                     std::to_string(spec.depth) + " slices (expected a flat image)");
  }
  const int channels = spec.nchannels;
  const uint64_t pixels =
      saturating_multiply(static_cast<uint64_t>(spec.width), static_cast<uint64_t>(spec.height));
  // A compressed file may rightly decode to far more than its own size, so only the budget
  // bounds the decoded channels and the RGB image made from them.
  const uint64_t decoded_bytes =
      saturating_multiply(pixels, channels * sizeof(float) + sizeof(Rgb));
  const std::string decoded_what = "the decoded " + std::to_string(spec.width) + "x" +
                                   std::to_string(spec.height) + " pixels of " +
                                   std::to_string(channels) + " channels";
  if (!budget.allows(decoded_bytes)) {
    throw SceneError(path + ": " + budget.exceeded(decoded_what, decoded_bytes));
  }
  const std::vector<float> data =
      decode_as_float(*input, path, what, budget, decoded_what, decoded_bytes);
  const bool srgb = values == PixelValues::kColour && is_srgb_encoded(spec);

  RgbImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.source = path;
  image.pixels.resize(static_cast<size_t>(spec.width) * spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* p = &data[i * channels];
    Rgb c = channels >= 3 ? Rgb(p[0], p[1], p[2]) : Rgb(p[0]);
    if (!is_finite(c)) {
      throw SceneError(path + ": pixel (" + std::to_string(i % spec.width) + ", " +
                       std::to_string(i / spec.width) + ") is not a finite number");
    }
    if (srgb) c = Rgb(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z));
    // Filtered HDR captures sometimes hold tiny negative values; radiance cannot be negative.
    image.pixels[i] = vmax(c, Rgb(0.0f));
  }
  return image;
}

RgbImage read_rgb_image(const std::string& path, std::string_view what, const MemoryBudget& budget,
                        PixelValues values) {
  // OpenImageIO reads the bytes from memory, so it sees exactly the file that was checked to
  // be a regular one and never opens a FIFO or a device itself.
  return decode_rgb_image(read_input_file(path, what, budget), path, what, budget, values);
}

RgbImage read_env_image(const std::string& path, const MemoryBudget& budget) {
  return read_rgb_image(path, "environment image", budget);
}

}  // namespace snee
