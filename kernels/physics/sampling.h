// Warping of uniform random numbers to common distributions, with matching pdfs, and
// piecewise-constant 1D/2D distributions (used for light selection and environment maps).
// Header-only declarations; implementations live beside them in sampling.cpp or inline.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "core/math.h"

namespace snee {

struct Vec2 {
  float x = 0, y = 0;
};

// The sampling template over the lane type (core/lane_math.h) and its scalar form.
template <lane::Lane F>
lane::Vec3Of<F> sample_uniform_sphere(F u0, F u1) {
  const F z = F(1.0f) - F(2.0f) * u0;
  return spherical_direction(safe_sqrt(F(1.0f) - z * z), z, F(2.0f * kPi) * u1);
}
inline Vec3 sample_uniform_sphere(Vec2 u) {
  return sample_uniform_sphere<float>(u.x, u.y);
}
inline constexpr float uniform_sphere_pdf() {
  return kInv4Pi;
}

// Shirley-Chiu concentric map of [0, 1)^2 onto the unit disk: area-preserving, so uniform
// points give uniform disk points (density 1/pi), and it keeps strata compact. Each square ring
// around the centre goes to a circle; both branches are computed and the selected one is the
// scalar branch's exact result (the other may divide by zero).
template <lane::Lane F>
std::pair<F, F> sample_concentric_disk(F u0, F u1) {
  using namespace lane;
  const F a = F(2.0f) * u0 - F(1.0f), b = F(2.0f) * u1 - F(1.0f);
  const auto wide = abs(a) > abs(b);
  const F r = select(wide, a, b);
  const F phi = select(wide, F(kPi / 4.0f) * (b / a), F(kPi / 2.0f) - F(kPi / 4.0f) * (a / b));
  const auto [sin_phi, cos_phi] = sincos(phi);
  // The centre, where phi is 0 / 0.
  const auto centre = abs(a) + abs(b) == F(0.0f);
  return {select(centre, F(0.0f), r * cos_phi), select(centre, F(0.0f), r * sin_phi)};
}
inline Vec2 sample_concentric_disk(Vec2 u) {
  const auto [x, y] = sample_concentric_disk<float>(u.x, u.y);
  return {x, y};
}

// Cosine-weighted hemisphere around +z.
Vec3 sample_cosine_hemisphere(Vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0 ? cos_theta * kInvPi : 0.0f;
}

// Uniform directions in the cone of half-angle acos(cos_max) around +z.
Vec3 sample_uniform_cone(Vec2 u, float cos_max);
float uniform_cone_pdf(float cos_max);

// Piecewise-constant distribution on [0,1) with n cells; zero-weight cells are never sampled.
// Negative and NaN weights count as zero; if every weight is zero the distribution is uniform
// (integral() still reports 0).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);
  // Returns a continuous position in [0,1); *pdf is the density in that measure, *cell the cell.
  float sample_continuous(float u, float* pdf, int* cell) const;
  int sample_discrete(float u, float* pmf) const;
  float pdf_continuous(float x) const;  // density at x in [0,1)
  float pmf(int cell) const;
  int size() const { return static_cast<int>(density_.size()); }
  float integral() const { return integral_; }  // mean weight (sum / n)

 private:
  std::vector<float> density_;  // normalized: pdf_continuous of each cell, pmf = density / n
  std::vector<float> cdf_;      // n + 1 entries
  float integral_ = 0;
};

// 2D piecewise-constant distribution on [0,1)^2 (rows = v, columns = u).
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, int width, int height);
  Vec2 sample(Vec2 u, float* pdf) const;  // pdf with respect to du dv
  float pdf(Vec2 uv) const;

 private:
  std::vector<Distribution1D> conditional_;  // one per row
  Distribution1D marginal_;
  int height_ = 0;  // rows, for finding a point's row in pdf()
};

}  // namespace snee
