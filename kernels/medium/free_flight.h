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

#include "scene/math.h"

namespace snee {

// exp(-sigma d) with the convention 0 * inf = 0 (a clear channel over an infinite distance).
inline float channel_transmittance(float sigma, float d) {
  return sigma > 0.0f ? std::exp(-sigma * d) : 1.0f;
}

inline constexpr float kThird = 1.0f / 3.0f;

// Distance t in [0, inf) from the channel mixture with probabilities p (summing to 1).
// u_channel picks the channel, u the distance.
inline float free_flight_sample(Rgb sigma_t, Rgb p, float u_channel, float u) {
  const int c = u_channel < p.x ? 0 : (u_channel < p.x + p.y ? 1 : 2);
  const float sigma = sigma_t[c];
  return sigma > 0.0f ? -std::log1p(-u) / sigma : kInfinity;
}
inline float free_flight_sample(Rgb sigma_t, float u_channel, float u) {
  const float sigma = sigma_t[std::min(static_cast<int>(u_channel * 3.0f), 2)];
  return sigma > 0.0f ? -std::log1p(-u) / sigma : kInfinity;
}

// Per-channel densities sigma_c exp(-sigma_c t) of a flight ending at t.
inline Rgb free_flight_channel_pdfs(Rgb sigma_t, float t) {
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[c] = sigma_t[c] > 0.0f ? sigma_t[c] * std::exp(-sigma_t[c] * t) : 0.0f;
  return out;
}

// Density of free_flight_sample at t: sum_c p_c sigma_c exp(-sigma_c t).
inline float free_flight_pdf(Rgb sigma_t, Rgb p, float t) {
  const Rgb q = free_flight_channel_pdfs(sigma_t, t);
  return p.x * q.x + p.y * q.y + p.z * q.z;
}
inline float free_flight_pdf(Rgb sigma_t, float t) {
  const Rgb q = free_flight_channel_pdfs(sigma_t, t);
  return (q.x + q.y + q.z) * kThird;
}

// Probability that a sampled distance exceeds d: sum_c p_c exp(-sigma_c d).
inline float free_flight_survival(Rgb sigma_t, Rgb p, float d) {
  return p.x * channel_transmittance(sigma_t.x, d) + p.y * channel_transmittance(sigma_t.y, d) +
         p.z * channel_transmittance(sigma_t.z, d);
}
inline float free_flight_survival(Rgb sigma_t, float d) {
  return (channel_transmittance(sigma_t.x, d) + channel_transmittance(sigma_t.y, d) +
          channel_transmittance(sigma_t.z, d)) *
         kThird;
}

inline Rgb transmittance(Rgb sigma_t, float d) {
  return {channel_transmittance(sigma_t.x, d), channel_transmittance(sigma_t.y, d),
          channel_transmittance(sigma_t.z, d)};
}

}  // namespace snee
