// The stopping rule of adaptive sampling (RenderOptions::noise_target, docs/budgets.md): a
// pixel has met a relative noise target when the standard error of its luminance is at most
// target x max(luminance, kNoiseFloor). A tile stops once every one of its pixels has, after at
// least kMinAdaptiveSpp samples.
#pragma once

#include <cstdint>

namespace snee {

// Luminance below which the error is measured in absolute terms: without it a black or nearly
// black pixel would need unbounded samples to reach a relative target. 0.01 is 1% of display
// white; an error of 5% of it is below one level of the 8-bit sRGB preview.
inline constexpr double kNoiseFloor = 0.01;
// The variance estimate of a handful of samples misses rare bright paths (a tile whose first
// samples all missed the light looks converged), so no tile stops before this many.
inline constexpr uint32_t kMinAdaptiveSpp = 16;

// Standard error of the pixel's luminance (Rec. 709 weights) over max(luminance, kNoiseFloor),
// from the per-channel mean and variance of the mean. The film keeps no covariances between
// channels, so the luminance's standard error is bounded by the weighted sum of the channels'
// (Minkowski's inequality): the rule can only oversample, never stop early.
double relative_standard_error(const double mean[3], const double variance_of_mean[3]);

}  // namespace snee
