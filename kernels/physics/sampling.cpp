#include "kernels/physics/sampling.h"

#include <algorithm>
#include <cmath>

namespace snee {

Vec3 sample_cosine_hemisphere(Vec2 u) {
  // The concentric mapping keeps strata compact, then Malley's projection to the hemisphere
  // makes the density cos(theta)/pi.
  const Vec2 d = sample_concentric_disk(u);
  return {d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y)};
}

Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
  // Linear in cos(theta) because the solid angle of a cap is linear in it.
  const float cos_theta = 1.0f - u.x * (1.0f - cos_max);
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  return spherical_direction(sin_theta, cos_theta, 2.0f * kPi * u.y);
}

float uniform_cone_pdf(float cos_max) {
  return 1.0f / (2.0f * kPi * (1.0f - cos_max));
}

Distribution1D::Distribution1D(std::span<const float> weights)
    : density_(weights.size()), cdf_(weights.size() + 1) {
  const size_t n = weights.size();
  if (n == 0) return;
  // Negative or NaN weights would corrupt the cdf; they mean "never sample here".
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const float w = weights[i];
    density_[i] = (w > 0) ? w : 0.0f;
    sum += density_[i];
  }
  integral_ = static_cast<float>(sum / static_cast<double>(n));
  if (sum == 0) {
    // Nothing to prefer: sample uniformly so callers still get a valid distribution.
    std::fill(density_.begin(), density_.end(), 1.0f);
    sum = static_cast<double>(n);
  }
  // Accumulated in double so tiny trailing cells keep a non-zero width where float allows it.
  double running = 0;
  cdf_[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    running += density_[i];
    cdf_[i + 1] = static_cast<float>(running / sum);
    density_[i] = static_cast<float>(density_[i] * static_cast<double>(n) / sum);
  }
  cdf_[n] = 1.0f;
}

float Distribution1D::sample_continuous(float u, float* pdf, int* cell) const {
  const int i = sample_discrete(u, nullptr);
  const float width = cdf_[i + 1] - cdf_[i];
  const float n = static_cast<float>(size());
  float x = (static_cast<float>(i) + (u - cdf_[i]) / width) / n;
  // Rounding may carry x onto a neighbouring cell, possibly one of zero weight; step back so
  // that pdf_continuous(x) sees the cell that was sampled.
  while (x > 0 && static_cast<int>(x * n) > i) x = std::nextafter(x, 0.0f);
  while (static_cast<int>(x * n) < i) x = std::nextafter(x, 1.0f);
  if (pdf) *pdf = density_[i];
  if (cell) *cell = i;
  return x;
}

int Distribution1D::sample_discrete(float u, float* pmf_out) const {
  // The last cell whose cdf start is <= u; a zero-width cell shares its start with the next
  // cell, so it is never the last one and thus never chosen.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end() - 1, u);
  const int i = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, size() - 1);
  if (pmf_out) *pmf_out = pmf(i);
  return i;
}

float Distribution1D::pdf_continuous(float x) const {
  const int i = std::clamp(static_cast<int>(x * static_cast<float>(size())), 0, size() - 1);
  return density_[i];
}

float Distribution1D::pmf(int cell) const {
  return density_[cell] / static_cast<float>(size());
}

Distribution2D::Distribution2D(std::span<const float> weights, int width, int height)
    : height_(height) {
  conditional_.reserve(height);
  std::vector<float> row_integrals(height);
  for (int y = 0; y < height; ++y) {
    conditional_.emplace_back(weights.subspan(static_cast<size_t>(y) * width, width));
    row_integrals[y] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(row_integrals);
}

Vec2 Distribution2D::sample(Vec2 u, float* pdf) const {
  float pdf_v = 0, pdf_u = 0;
  int row = 0;
  const float v = marginal_.sample_continuous(u.y, &pdf_v, &row);
  const float x = conditional_[row].sample_continuous(u.x, &pdf_u, nullptr);
  if (pdf) *pdf = pdf_u * pdf_v;
  return {x, v};
}

float Distribution2D::pdf(Vec2 uv) const {
  const int row = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  return marginal_.pdf_continuous(uv.y) * conditional_[row].pdf_continuous(uv.x);
}

}  // namespace snee
