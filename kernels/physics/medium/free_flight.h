// Free-flight distance sampling in a homogeneous medium with chromatic extinction: one channel
// is picked, and every pdf is the one-sample-MIS mixture over the three channels, so the
// estimator stays unbiased for all channels (spectral MIS). A channel with sigma_c = 0 never
// stops the flight: its distances are +inf and it adds nothing to the pdf, while it still
// counts in the survival probability.
//
// The mixture weights are the channel probabilities p_c. Uniform weights make each flight its
// own mixture; the path tracer instead carries p_c along the path (the posterior of a "hero"
// channel chosen once per path, updated by every flight), which makes the whole path's density
// the mixture over channels of the single-channel path densities: no channel's throughput can
// then grow without bound over a long walk, as it can when every flight is weighed alone.
#pragma once

#include <limits>

#include "core/lane_math.h"
#include "core/math.h"

namespace snee {

// Each function is a template over the lane type F (core/lane_math.h), sigma_t and p being
// the lane's 3-vectors, with a scalar form for float beside it. Both outcomes of every test are
// computed and selected. exp and log1p are libm's for float and xsimd's polynomials for a
// batch (kernels/simd/lane_batch.h), so the two forms agree to a few ulp (kernels/simd/README.md),
// not bit for bit.

// exp(-sigma d) with the convention 0 * inf = 0 (a clear channel over an infinite distance).
template <lane::Lane F>
F channel_transmittance(F sigma, F d) {
  using namespace lane;
  return select(sigma > F(0.0f), lane::exp(neg(sigma) * d), F(1.0f));
}
inline float channel_transmittance(float sigma, float d) {
  return channel_transmittance<float>(sigma, d);
}

template <lane::Lane F>
lane::Vec3Of<F> transmittance(const lane::Vec3Of<F>& sigma_t, F d) {
  return {channel_transmittance(sigma_t.x, d), channel_transmittance(sigma_t.y, d),
          channel_transmittance(sigma_t.z, d)};
}
inline Rgb transmittance(Rgb sigma_t, float d) {
  return transmittance<float>(sigma_t, d);
}

inline constexpr float kThird = 1.0f / 3.0f;

// -log(1 - u) / sigma, or +inf for a clear channel.
template <lane::Lane F>
F exponential_distance(F sigma, F u) {
  using namespace lane;
  return select(sigma > F(0.0f), neg(lane::log1p(neg(u))) / sigma,
                F(std::numeric_limits<float>::infinity()));
}

// Distance t in [0, inf) from the channel mixture with probabilities p (summing to 1): the
// channel is the first whose cumulative probability exceeds u_channel; u picks the distance.
template <lane::Lane F>
F free_flight_sample(const lane::Vec3Of<F>& sigma_t, const lane::Vec3Of<F>& p, F u_channel, F u) {
  using namespace lane;
  const F sigma =
      select(u_channel < p.x, sigma_t.x, select(u_channel < p.x + p.y, sigma_t.y, sigma_t.z));
  return exponential_distance(sigma, u);
}
inline float free_flight_sample(Rgb sigma_t, Rgb p, float u_channel, float u) {
  return free_flight_sample<float>(sigma_t, p, u_channel, u);
}
// Uniform channel probabilities: the channel is trunc(3 u_channel) for u_channel in [0, 1),
// written as comparisons.
template <lane::Lane F>
F free_flight_sample(const lane::Vec3Of<F>& sigma_t, F u_channel, F u) {
  using namespace lane;
  const F k = u_channel * F(3.0f);
  const F sigma = select(k < F(1.0f), sigma_t.x, select(k < F(2.0f), sigma_t.y, sigma_t.z));
  return exponential_distance(sigma, u);
}
inline float free_flight_sample(Rgb sigma_t, float u_channel, float u) {
  return free_flight_sample<float>(sigma_t, u_channel, u);
}

// Per-channel densities sigma_c exp(-sigma_c t) of a flight ending at t, from the channels'
// transmittance tr = transmittance(sigma_t, t), which the callers need anyway.
template <class V>
requires lane::Lane<decltype(V::x)> V free_flight_channel_pdfs(const V& sigma_t, const V& tr) {
  using F = decltype(V::x);
  using namespace lane;
  const auto term = [](F sigma, F t_c) { return select(sigma > F(0.0f), sigma * t_c, F(0.0f)); };
  return {term(sigma_t.x, tr.x), term(sigma_t.y, tr.y), term(sigma_t.z, tr.z)};
}
inline Rgb free_flight_channel_pdfs(Rgb sigma_t, float t) {
  return free_flight_channel_pdfs(sigma_t, transmittance(sigma_t, t));
}

// Density of free_flight_sample at t: sum_c p_c sigma_c exp(-sigma_c t).
template <lane::Lane F>
F free_flight_pdf(const lane::Vec3Of<F>& sigma_t, const lane::Vec3Of<F>& p, F t) {
  return dot(p, free_flight_channel_pdfs(sigma_t, transmittance(sigma_t, t)));
}
inline float free_flight_pdf(Rgb sigma_t, Rgb p, float t) {
  return free_flight_pdf<float>(sigma_t, p, t);
}
template <lane::Lane F>
F free_flight_pdf(const lane::Vec3Of<F>& sigma_t, F t) {
  const lane::Vec3Of<F> q = free_flight_channel_pdfs(sigma_t, transmittance(sigma_t, t));
  return (q.x + q.y + q.z) * F(kThird);
}
inline float free_flight_pdf(Rgb sigma_t, float t) {
  return free_flight_pdf<float>(sigma_t, t);
}

// Probability that a sampled distance exceeds d: sum_c p_c exp(-sigma_c d).
template <lane::Lane F>
F free_flight_survival(const lane::Vec3Of<F>& sigma_t, const lane::Vec3Of<F>& p, F d) {
  return dot(p, transmittance(sigma_t, d));
}
inline float free_flight_survival(Rgb sigma_t, Rgb p, float d) {
  return free_flight_survival<float>(sigma_t, p, d);
}
template <lane::Lane F>
F free_flight_survival(const lane::Vec3Of<F>& sigma_t, F d) {
  const lane::Vec3Of<F> tr = transmittance(sigma_t, d);
  return (tr.x + tr.y + tr.z) * F(kThird);
}
inline float free_flight_survival(Rgb sigma_t, float d) {
  return free_flight_survival<float>(sigma_t, d);
}

}  // namespace snee
