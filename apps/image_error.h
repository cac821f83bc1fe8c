// How far a render is from a reference: the relative mean squared error used by `snee
// compare`, and a false-colour map of the per-pixel error for looking at where it lives.
#pragma once

#include "scene/film.h"

namespace snee {

struct ImageError {
  // Mean over pixels of ((x - ref)^2 - var_ref) / (ref^2 + kRelativeMseFloor), channel-averaged
  // luminance-free (each RGB channel counts once). Subtracting the reference's own variance of
  // the mean (from its variance channel, when it has one) removes the reference's noise from
  // the expectation, so the figure estimates the render's error alone.
  double relative_mse = 0;
  // The same without subtracting the reference's variance (an upper bound).
  double relative_mse_raw = 0;
  // Reference noise alone, mean of var_ref / (ref^2 + floor): what the raw figure includes.
  double reference_noise = 0;
  // relative_mse without the kTrimmedFraction of pixels with the largest error (at least one):
  // a few fireflies can carry most of a short render's squared error, and this figure shows
  // what the rest of the image looks like. A biased summary, reported beside the full one.
  double relative_mse_trimmed = 0;
};
inline constexpr double kTrimmedFraction = 1e-3;
// Keeps near-black pixels from dominating the relative error (as in Rousselle et al. 2011).
inline constexpr double kRelativeMseFloor = 1e-2;

// Throws std::invalid_argument when the sizes differ.
ImageError image_error(const Film& render, const Film& reference);

// The false-colour scale of the error maps: log10 of a pixel's relative squared error (the
// channel mean of (x - ref)^2 / (ref^2 + kRelativeMseFloor)) from kErrorMapLowest (black) to
// kErrorMapHighest (white) through a perceptual ramp (dark blue, magenta, orange, yellow).
// Linear RGB, so the preview writer's sRGB encoding shows the ramp's intended colours.
inline constexpr int kErrorMapLowestDecade = -4;
inline constexpr int kErrorMapHighestDecade = 2;
Rgb error_colour(double squared_relative_error);

// Each pixel's error_colour.
Film error_image(const Film& render, const Film& reference);

}  // namespace snee
