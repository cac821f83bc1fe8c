// Film <-> image files through OpenImageIO. The EXR keeps 32-bit floats: the variance channels
// feed convergence tests and half precision would quantise small variances to zero.
//
// EXR layout: channels "R", "G", "B" (mean radiance) and "variance.R", "variance.G",
// "variance.B" (variance of the mean), all FLOAT; metadata attributes snee:spp (int),
// snee:min_spp (int, the fewest samples of any pixel: below snee:spp in a partial image),
// snee:integrator (string), snee:seed (string, decimal: EXR has no unsigned 32-bit attribute),
// snee:render_seconds (double), snee:scene (string), snee:nonfinite_samples (string, decimal:
// EXR has no 64-bit integer attribute), snee:version (string) and "Software". When the pixels'
// sample counts differ (adaptive sampling, an interrupted render) a FLOAT channel "spp" holds
// each pixel's (exact up to 2^24); snee:time_budget_seconds and snee:noise_target (double) are
// written only for a render that ran under them (docs/budgets.md). The denoiser AOVs, when the
// film holds them, are FLOAT channels "albedo.R/G/B" (layer albedo), "N.X/Y/Z" (layer N, the
// world-space normal) and "Z" (the depth, the EXR convention's depth channel).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "scene/film.h"

namespace snee {
namespace {

constexpr std::array<const char*, 6> kChannels = {"R",          "G",          "B",
                                                  "variance.R", "variance.G", "variance.B"};
constexpr const char* kSppChannel = "spp";
constexpr std::array<const char*, 3> kAlbedoChannels = {"albedo.R", "albedo.G", "albedo.B"};
constexpr std::array<const char*, 3> kNormalChannels = {"N.X", "N.Y", "N.Z"};
constexpr const char* kDepthChannel = "Z";

[[noreturn]] void fail(const std::string& what, const std::string& path, const std::string& why) {
  throw std::runtime_error(what + " '" + path + "': " + (why.empty() ? "unknown error" : why));
}

std::unique_ptr<OIIO::ImageOutput> create_output(const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) fail("cannot write image", path, OIIO::geterror());
  return out;
}

void write_pixels(OIIO::ImageOutput& out, const OIIO::ImageSpec& spec, const std::string& path,
                  OIIO::TypeDesc type, const void* pixels) {
  if (!out.open(path, spec)) fail("cannot write image", path, out.geterror());
  const bool written = out.write_image(type, pixels);
  const bool closed = out.close();
  if (!written || !closed) fail("cannot write image", path, out.geterror());
}

// A sample count per pixel is written only where it says more than snee:min_spp.
bool spp_varies(const Film& film) {
  return !film.pixel_spp.empty() &&
         std::adjacent_find(film.pixel_spp.begin(), film.pixel_spp.end(), std::not_equal_to<>()) !=
             film.pixel_spp.end();
}

void set_optional_double(OIIO::ImageSpec& spec, const char* name, const double& value) {
  if (value != 0) spec.attribute(name, OIIO::TypeDesc::DOUBLE, &value);
}

size_t pixel_count(const Film& film) {
  return static_cast<size_t>(film.width) * static_cast<size_t>(film.height);
}

std::array<int, 3> channel_indices(const OIIO::ImageSpec& spec,
                                   const std::array<const char*, 3>& names) {
  return {spec.channelindex(names[0]), spec.channelindex(names[1]), spec.channelindex(names[2])};
}

void check_film(const Film& film, const std::string& path) {
  if (film.width <= 0 || film.height <= 0 || film.mean.size() != pixel_count(film))
    fail("cannot write image", path, "film has no pixels or inconsistent size");
}

// The film's mean radiance as interleaved R,G,B values, each channel through `encode`.
template <typename T, typename Encode>
std::vector<T> interleaved_mean(const Film& film, Encode encode) {
  std::vector<T> pixels;
  pixels.reserve(pixel_count(film) * 3);
  for (const Rgb& rgb : film.mean)
    for (int c = 0; c < 3; ++c) pixels.push_back(encode(rgb[c]));
  return pixels;
}

}  // namespace

void write_exr(const Film& film, const std::string& path, const ExrAttributes& extra) {
  check_film(film, path);
  const bool has_variance = film.variance_of_mean.size() == film.mean.size();
  const bool has_spp = film.pixel_spp.size() == film.mean.size() && spp_varies(film);
  const int colour_channels = has_variance ? 6 : 3;
  const bool has_albedo = film.albedo.size() == film.mean.size();
  const bool has_normal = film.normal.size() == film.mean.size();
  const bool has_depth = film.depth.size() == film.mean.size();
  const int nchannels = colour_channels + (has_spp ? 1 : 0) + (has_albedo ? 3 : 0) +
                        (has_normal ? 3 : 0) + (has_depth ? 1 : 0);
  OIIO::ImageSpec spec(film.width, film.height, nchannels, OIIO::TypeDesc::FLOAT);
  spec.channelnames.assign(kChannels.begin(), kChannels.begin() + colour_channels);
  if (has_spp) spec.channelnames.emplace_back(kSppChannel);
  if (has_albedo)
    spec.channelnames.insert(spec.channelnames.end(), kAlbedoChannels.begin(),
                             kAlbedoChannels.end());
  if (has_normal)
    spec.channelnames.insert(spec.channelnames.end(), kNormalChannels.begin(),
                             kNormalChannels.end());
  if (has_depth) spec.channelnames.emplace_back(kDepthChannel);
  spec.attribute("compression", "zip");
  spec.attribute("Software", "snee " SNEE_VERSION);
  spec.attribute("snee:version", SNEE_VERSION);
  spec.attribute("snee:spp", film.meta.spp);
  spec.attribute("snee:min_spp", film.meta.min_spp);
  spec.attribute("snee:integrator", film.meta.integrator);
  spec.attribute("snee:seed", std::to_string(film.meta.seed));
  spec.attribute("snee:render_seconds", OIIO::TypeDesc::DOUBLE, &film.meta.render_seconds);
  spec.attribute("snee:scene", film.meta.scene);
  spec.attribute("snee:nonfinite_samples", std::to_string(film.meta.nonfinite_samples));
  set_optional_double(spec, "snee:time_budget_seconds", film.meta.time_budget_seconds);
  set_optional_double(spec, "snee:noise_target", film.meta.noise_target);
  for (const auto& [name, value] : extra) spec.attribute(name, value);

  std::vector<float> pixels;
  pixels.reserve(pixel_count(film) * nchannels);
  for (size_t i = 0; i < pixel_count(film); ++i) {
    for (int c = 0; c < 3; ++c) pixels.push_back(film.mean[i][c]);
    if (has_variance)
      for (int c = 0; c < 3; ++c) pixels.push_back(film.variance_of_mean[i][c]);
    if (has_spp) pixels.push_back(static_cast<float>(film.pixel_spp[i]));
    if (has_albedo)
      for (int c = 0; c < 3; ++c) pixels.push_back(film.albedo[i][c]);
    if (has_normal)
      for (int c = 0; c < 3; ++c) pixels.push_back(film.normal[i][c]);
    if (has_depth) pixels.push_back(film.depth[i]);
  }
  auto out = create_output(path);
  write_pixels(*out, spec, path, OIIO::TypeDesc::FLOAT, pixels.data());
}

void write_preview(const Film& film, const std::string& path, const ToneMap& tone) {
  check_film(film, path);
  OIIO::ImageSpec spec(film.width, film.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Software", "snee " SNEE_VERSION);
  const std::vector<uint8_t> pixels = interleaved_mean<uint8_t>(
      film, [&](float v) { return static_cast<uint8_t>(std::lround(tone.encode(v) * 255.0f)); });
  auto out = create_output(path);
  write_pixels(*out, spec, path, OIIO::TypeDesc::UINT8, pixels.data());
}

void write_hdr(const Film& film, const std::string& path) {
  check_film(film, path);
  OIIO::ImageSpec spec(film.width, film.height, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("Software", "snee " SNEE_VERSION);
  const std::vector<float> pixels = interleaved_mean<float>(film, [](float v) { return v; });
  auto out = create_output(path);
  write_pixels(*out, spec, path, OIIO::TypeDesc::FLOAT, pixels.data());
}

Film read_exr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) fail("cannot read image", path, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();

  // The EXR reader may reorder channels, so they are looked up by name.
  std::array<int, 6> index{};
  for (size_t c = 0; c < kChannels.size(); ++c) {
    index[c] = spec.channelindex(kChannels[c]);
    if (c < 3 && index[c] < 0)
      fail("cannot read image", path, std::string("no channel ") + kChannels[c]);
  }
  const bool has_variance = index[3] >= 0 && index[4] >= 0 && index[5] >= 0;
  const int spp_index = spec.channelindex(kSppChannel);
  const std::array<int, 3> albedo_index = channel_indices(spec, kAlbedoChannels);
  const std::array<int, 3> normal_index = channel_indices(spec, kNormalChannels);
  const bool has_albedo = albedo_index[0] >= 0 && albedo_index[1] >= 0 && albedo_index[2] >= 0;
  const bool has_normal = normal_index[0] >= 0 && normal_index[1] >= 0 && normal_index[2] >= 0;
  const int depth_index = spec.channelindex(kDepthChannel);

  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail("cannot read image", path, in->geterror());

  Film film;
  film.width = spec.width;
  film.height = spec.height;
  film.mean.resize(pixel_count(film));
  if (has_variance) film.variance_of_mean.resize(pixel_count(film));
  if (spp_index >= 0) film.pixel_spp.resize(pixel_count(film));
  if (has_albedo) film.albedo.resize(pixel_count(film));
  if (has_normal) film.normal.resize(pixel_count(film));
  if (depth_index >= 0) film.depth.resize(pixel_count(film));
  for (size_t i = 0; i < pixel_count(film); ++i) {
    const float* px = &pixels[i * spec.nchannels];
    for (int c = 0; c < 3; ++c) {
      film.mean[i][c] = px[index[c]];
      if (has_variance) film.variance_of_mean[i][c] = px[index[c + 3]];
      if (has_albedo) film.albedo[i][c] = px[albedo_index[c]];
      if (has_normal) film.normal[i][c] = px[normal_index[c]];
    }
    if (depth_index >= 0) film.depth[i] = px[depth_index];
    if (spp_index >= 0) {
      const float spp = px[spp_index];
      if (!(spp >= 0 && spp < 4294967296.0f) || spp != std::floor(spp))
        fail("cannot read image", path, "channel spp holds a value that is not a sample count");
      film.pixel_spp[i] = static_cast<uint32_t>(spp);
    }
  }

  film.meta.spp = spec.get_int_attribute("snee:spp");
  // Images written before min_spp existed were always complete.
  film.meta.min_spp = spec.get_int_attribute("snee:min_spp", film.meta.spp);
  film.meta.integrator = spec.get_string_attribute("snee:integrator");
  const std::string_view seed = spec.get_string_attribute("snee:seed", "0");
  if (std::from_chars(seed.data(), seed.data() + seed.size(), film.meta.seed).ec != std::errc())
    fail("cannot read image", path, "snee:seed is not an unsigned integer");
  film.meta.scene = spec.get_string_attribute("snee:scene");
  const std::string_view nonfinite = spec.get_string_attribute("snee:nonfinite_samples", "0");
  if (std::from_chars(nonfinite.data(), nonfinite.data() + nonfinite.size(),
                      film.meta.nonfinite_samples)
          .ec != std::errc())
    fail("cannot read image", path, "snee:nonfinite_samples is not an unsigned integer");
  spec.getattribute("snee:render_seconds", OIIO::TypeDesc::DOUBLE, &film.meta.render_seconds);
  spec.getattribute("snee:time_budget_seconds", OIIO::TypeDesc::DOUBLE,
                    &film.meta.time_budget_seconds);
  spec.getattribute("snee:noise_target", OIIO::TypeDesc::DOUBLE, &film.meta.noise_target);
  return film;
}

}  // namespace snee
