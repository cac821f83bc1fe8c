#include "apps/image_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace snee {

namespace {

double squared_relative_error(const Film& render, const Film& reference, size_t i, int c) {
  const double ref = reference.mean[i][c], diff = render.mean[i][c] - ref;
  return diff * diff / (ref * ref + kRelativeMseFloor);
}

double reference_variance(const Film& reference, size_t i, int c) {
  if (reference.variance_of_mean.size() != reference.mean.size()) return 0;
  const double ref = reference.mean[i][c];
  return reference.variance_of_mean[i][c] / (ref * ref + kRelativeMseFloor);
}

void check_sizes(const Film& render, const Film& reference) {
  if (render.width != reference.width || render.height != reference.height) {
    throw std::invalid_argument("the reference is " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height) + " but the render is " +
                                std::to_string(render.width) + "x" + std::to_string(render.height));
  }
}

float srgb_to_linear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// A ramp through dark blue, magenta, orange and yellow (sRGB stops), t in [0, 1].
Rgb ramp(float t) {
  static constexpr std::array<std::array<float, 3>, 5> kStops = {{{0.0f, 0.0f, 0.0f},
                                                                  {0.15f, 0.1f, 0.55f},
                                                                  {0.75f, 0.15f, 0.55f},
                                                                  {0.98f, 0.55f, 0.15f},
                                                                  {1.0f, 1.0f, 0.75f}}};
  const float x = std::clamp(t, 0.0f, 1.0f) * (kStops.size() - 1);
  const size_t k = std::min(static_cast<size_t>(x), kStops.size() - 2);
  const float f = x - static_cast<float>(k);
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[c] = srgb_to_linear(kStops[k][c] * (1 - f) + kStops[k + 1][c] * f);
  return out;
}

}  // namespace

ImageError image_error(const Film& render, const Film& reference) {
  check_sizes(render, reference);
  ImageError e;
  const size_t n = render.mean.size();
  std::vector<double> pixel_error(n);
  for (size_t i = 0; i < n; ++i) {
    double raw = 0, noise = 0;
    for (int c = 0; c < 3; ++c) {
      raw += squared_relative_error(render, reference, i, c);
      noise += reference_variance(reference, i, c);
    }
    e.relative_mse_raw += raw;
    e.reference_noise += noise;
    pixel_error[i] = raw - noise;
  }
  const double count = 3.0 * static_cast<double>(n);
  e.relative_mse_raw /= count;
  e.reference_noise /= count;
  e.relative_mse = std::max(0.0, e.relative_mse_raw - e.reference_noise);
  const size_t dropped = std::max<size_t>(1, static_cast<size_t>(kTrimmedFraction * n));
  if (n > dropped) {
    std::nth_element(pixel_error.begin(), pixel_error.end() - dropped, pixel_error.end());
    double kept = 0;
    for (auto it = pixel_error.begin(); it != pixel_error.end() - dropped; ++it) kept += *it;
    e.relative_mse_trimmed = std::max(0.0, kept / (3.0 * static_cast<double>(n - dropped)));
  }
  return e;
}

Rgb error_colour(double squared_relative_error) {
  constexpr double kLowest = kErrorMapLowestDecade, kHighest = kErrorMapHighestDecade;
  const double decade = std::log10(std::max(squared_relative_error, std::pow(10.0, kLowest)));
  return ramp(static_cast<float>((decade - kLowest) / (kHighest - kLowest)));
}

Film error_image(const Film& render, const Film& reference) {
  check_sizes(render, reference);
  Film out;
  out.width = render.width;
  out.height = render.height;
  out.mean.resize(render.mean.size());
  for (size_t i = 0; i < render.mean.size(); ++i) {
    double e = 0;
    for (int c = 0; c < 3; ++c) e += squared_relative_error(render, reference, i, c) / 3.0;
    out.mean[i] = error_colour(e);
  }
  return out;
}

}  // namespace snee
