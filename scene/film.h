// A finished (or partial) image: per-pixel mean radiance and the variance of that mean, plus
// the metadata written beside it. Pure data; film_io.cpp writes it through OpenImageIO.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "scene/tone_map.h"

namespace snee {

struct FilmMetadata {
  int spp = 0;      // samples per pixel the render was asked for
  int min_spp = 0;  // the fewest samples any pixel holds: spp unless the render was cut short
  std::string integrator;
  uint32_t seed = 0;
  double render_seconds = 0;
  std::string scene;
  // Samples that were NaN or infinite and went into the image as 0 (a sign of a numerical
  // fault: a correct image has none).
  uint64_t nonfinite_samples = 0;
  // The budgets the render ran under (docs/budgets.md); 0 where none was given.
  double time_budget_seconds = 0;
  double noise_target = 0;
};

struct Film {
  int width = 0;
  int height = 0;
  std::vector<Rgb> mean;              // row-major, top row first
  std::vector<Rgb> variance_of_mean;  // per channel, sample variance / spp
  // Samples each pixel holds; empty when the image does not say (every pixel has meta.min_spp).
  std::vector<uint32_t> pixel_spp;
  // Denoiser AOVs of the first non-specular hit, each the mean over the pixel's samples like
  // `mean` (docs/output-images.md); each empty when the render was not asked for it.
  std::vector<Rgb> albedo;
  std::vector<Vec3> normal;  // world space, facing the arriving ray
  std::vector<float> depth;  // distance along the camera ray and its specular chain
  FilmMetadata meta;
  Rgb& at(int x, int y) { return mean[static_cast<size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return mean[static_cast<size_t>(y) * width + x]; }
};

// Further string attributes of an EXR (name, value), e.g. the settings a render was made with.
using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// Writes a linear float EXR with channels R,G,B and variance.R/G/B, a channel "spp" when the
// pixels' sample counts differ, albedo.R/G/B, N.X/Y/Z and Z for the AOVs the film holds, and
// the metadata as "snee:*" attributes, then `extra`. Throws
// std::runtime_error naming the file on failure.
void write_exr(const Film& film, const std::string& path, const ExrAttributes& extra = {});
// Writes an 8-bit preview through `tone` (default: clamped, exposure 0, sRGB encoded); format
// from the extension (PNG, JPEG...).
void write_preview(const Film& film, const std::string& path, const ToneMap& tone = {});
// Writes the mean radiance as linear float RGB (Radiance .hdr): no variance, no metadata.
void write_hdr(const Film& film, const std::string& path);
// Reads an EXR written by write_exr (variance channels optional). Throws on failure.
Film read_exr(const std::string& path);

}  // namespace snee
