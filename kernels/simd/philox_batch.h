// Philox4x32-10 over a batch of lanes, one independent counter and key per lane. Each lane
// produces exactly the bits of Random123's scalar r123::Philox4x32 (rng.h), so a batched kernel
// draws the same numbers as the scalar code for the same (seed, pixel, sample, event, purpose).
#pragma once

#include <array>

#include "kernels/physics/rng.h"
#include "kernels/simd/mul_hilo.h"

namespace snee::simd {

using PhiloxCounter = std::array<UintBatch, 4>;
using PhiloxKey = std::array<UintBatch, 2>;

inline PhiloxCounter philox4x32_10(PhiloxCounter ctr, PhiloxKey key) {
  const UintBatch m0(0xD2511F53u), m1(0xCD9E8D57u);
  const UintBatch w0(0x9E3779B9u), w1(0xBB67AE85u);
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      key[0] += w0;
      key[1] += w1;
    }
    UintBatch hi0, lo0, hi1, lo1;
    mul_hilo(m0, ctr[0], &hi0, &lo0);
    mul_hilo(m1, ctr[2], &hi1, &lo1);
    ctr = {hi1 ^ ctr[1] ^ key[0], lo1, hi0 ^ ctr[3] ^ key[1], lo0};
  }
  return ctr;
}

// bits_to_unit_float per lane; the shifted value is below 2^24, so the conversion is exact
// through a signed integer, as the scalar one is.
inline FloatBatch bits_to_unit_float(UintBatch bits) {
  return xsimd::to_float(xsimd::bitwise_cast<IntBatch>(bits >> 8)) * FloatBatch(0x1p-24f);
}

struct RandomBlockBatch {
  std::array<FloatBatch, 4> u;
};

// random_block for every lane: lane i equals random_block(seed, pixel[i], sample[i], event[i],
// purpose) bit for bit.
inline RandomBlockBatch random_block(uint32_t seed, UintBatch pixel, UintBatch sample,
                                     UintBatch event, RngPurpose purpose) {
  const PhiloxCounter bits =
      philox4x32_10({sample, event, UintBatch(static_cast<uint32_t>(purpose)), UintBatch(0u)},
                    {pixel, UintBatch(seed)});
  return {{bits_to_unit_float(bits[0]), bits_to_unit_float(bits[1]), bits_to_unit_float(bits[2]),
           bits_to_unit_float(bits[3])}};
}

// random_block for a chunk whose real lanes are [0, active): a chunk of one slot (each chunk
// of the one-slot megakernel) is drawn with the scalar function, which gives the same bits as
// its lane of the batch at a quarter of the SSE4.2 batch's cost, and broadcast.
inline RandomBlockBatch random_block(uint32_t seed, UintBatch pixel, UintBatch sample,
                                     UintBatch event, RngPurpose purpose, size_t active) {
  if (active != 1) return random_block(seed, pixel, sample, event, purpose);
  const RandomBlock r =
      snee::random_block(seed, pixel.get(0), sample.get(0), event.get(0), purpose);
  return {{FloatBatch(r.u[0]), FloatBatch(r.u[1]), FloatBatch(r.u[2]), FloatBatch(r.u[3])}};
}

}  // namespace snee::simd
