// Free-flight distance sampling in a homogeneous medium with chromatic extinction: one channel
// is picked uniformly, and every pdf is the one-sample-MIS average over the three channels, so
// the estimator stays unbiased and bounded for all channels (spectral MIS). A channel with
// sigma_c = 0 never stops the flight: its distances are +inf and it adds nothing to the pdf,
// while it still counts in the survival probability.
#pragma once

#include "scene/math.h"

namespace snee {

// exp(-sigma d) with the convention 0 * inf = 0 (a clear channel over an infinite distance).
inline float channel_transmittance(float sigma, float d) {
  return sigma > 0.0f ? std::exp(-sigma * d) : 1.0f;
}

// Distance t in [0, inf) from the channel mixture. u_channel picks the channel, u the distance.
inline float free_flight_sample(Rgb sigma_t, float u_channel, float u) {
  const float sigma = sigma_t[std::min(static_cast<int>(u_channel * 3.0f), 2)];
  return sigma > 0.0f ? -std::log1p(-u) / sigma : kInfinity;
}

// Density of free_flight_sample at t: mean_c sigma_c exp(-sigma_c t).
inline float free_flight_pdf(Rgb sigma_t, float t) {
  float sum = 0.0f;
  for (int c = 0; c < 3; ++c)
    sum += sigma_t[c] > 0.0f ? sigma_t[c] * std::exp(-sigma_t[c] * t) : 0.0f;
  return sum * (1.0f / 3.0f);
}

// Probability that a sampled distance exceeds d: mean_c exp(-sigma_c d).
inline float free_flight_survival(Rgb sigma_t, float d) {
  return (channel_transmittance(sigma_t.x, d) + channel_transmittance(sigma_t.y, d) +
          channel_transmittance(sigma_t.z, d)) *
         (1.0f / 3.0f);
}

inline Rgb transmittance(Rgb sigma_t, float d) {
  return {channel_transmittance(sigma_t.x, d), channel_transmittance(sigma_t.y, d),
          channel_transmittance(sigma_t.z, d)};
}

}  // namespace snee
