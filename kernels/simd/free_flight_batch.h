// The spectral-MIS free-flight functions of medium/free_flight.h for a batch of lanes, each
// lane with its own extinction. The arithmetic is the scalar one in the same order, but the
// transcendentals are xsimd's polynomial exp and log1p instead of libm's, so the results agree
// with the scalar functions only to a few ulp (bounds in README.md, checked by
// tests/test_free_flight_batch.cpp); for results below FLT_MIN xsimd's exp flushes to zero.
#pragma once

#include <limits>

#include "kernels/simd/arch.h"

namespace snee::simd {

inline FloatBatch channel_transmittance(FloatBatch sigma, FloatBatch d) {
  return xsimd::select(sigma > FloatBatch(0.0f), xsimd::exp(-sigma * d), FloatBatch(1.0f));
}

// u_channel picks the channel: trunc(3 u) for u in [0, 1), written as comparisons.
inline FloatBatch free_flight_sample(const Vec3Batch& sigma_t, FloatBatch u_channel, FloatBatch u) {
  const FloatBatch k = u_channel * FloatBatch(3.0f);
  const FloatBatch sigma = xsimd::select(k < FloatBatch(1.0f), sigma_t.x,
                                         xsimd::select(k < FloatBatch(2.0f), sigma_t.y, sigma_t.z));
  return xsimd::select(sigma > FloatBatch(0.0f), -xsimd::log1p(-u) / sigma,
                       FloatBatch(std::numeric_limits<float>::infinity()));
}

// The path-level mixture with channel probabilities p (medium/free_flight.h): the channel is
// the first whose cumulative probability exceeds u_channel, as in the scalar function.
inline FloatBatch free_flight_sample(const Vec3Batch& sigma_t, const Vec3Batch& p,
                                     FloatBatch u_channel, FloatBatch u) {
  const FloatBatch sigma = xsimd::select(
      u_channel < p.x, sigma_t.x, xsimd::select(u_channel < p.x + p.y, sigma_t.y, sigma_t.z));
  return xsimd::select(sigma > FloatBatch(0.0f), -xsimd::log1p(-u) / sigma,
                       FloatBatch(std::numeric_limits<float>::infinity()));
}

inline FloatBatch free_flight_pdf(const Vec3Batch& sigma_t, FloatBatch t) {
  const auto term = [t](FloatBatch sigma) {
    return xsimd::select(sigma > FloatBatch(0.0f), sigma * xsimd::exp(-sigma * t),
                         FloatBatch(0.0f));
  };
  return (term(sigma_t.x) + term(sigma_t.y) + term(sigma_t.z)) * FloatBatch(1.0f / 3.0f);
}

inline FloatBatch free_flight_survival(const Vec3Batch& sigma_t, FloatBatch d) {
  return (channel_transmittance(sigma_t.x, d) + channel_transmittance(sigma_t.y, d) +
          channel_transmittance(sigma_t.z, d)) *
         FloatBatch(1.0f / 3.0f);
}

// Per-channel densities sigma_c exp(-sigma_c t), from the channels' transmittance tr = T(t)
// (the same product the scalar free_flight_channel_pdfs forms).
inline Vec3Batch free_flight_channel_pdfs(const Vec3Batch& sigma_t, const Vec3Batch& tr) {
  const auto term = [](FloatBatch sigma, FloatBatch t_c) {
    return xsimd::select(sigma > FloatBatch(0.0f), sigma * t_c, FloatBatch(0.0f));
  };
  return {term(sigma_t.x, tr.x), term(sigma_t.y, tr.y), term(sigma_t.z, tr.z)};
}

inline Vec3Batch transmittance(const Vec3Batch& sigma_t, FloatBatch d) {
  return {channel_transmittance(sigma_t.x, d), channel_transmittance(sigma_t.y, d),
          channel_transmittance(sigma_t.z, d)};
}

}  // namespace snee::simd
