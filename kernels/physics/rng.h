// Counter-based random numbers: every draw is a pure function of (seed, pixel, sample, event,
// purpose), so the image cannot depend on thread count, batch size or queue order. Philox4x32-10
// (Salmon et al. 2011, Random123) turns one 128-bit counter into four independent 32-bit words.
#pragma once

#include <Random123/philox.h>

#include <cstdint>

namespace snee {

// What a block of four numbers is used for within one path event; each purpose owns its block.
enum class RngPurpose : uint32_t {
  kCamera,       // pixel jitter (2), thin-lens position (2)
  kFreeFlight,   // channel, distance
  kPhase,        // scattering direction
  kBsdf,         // lobe, microfacet normal
  kLightSample,  // light selection and position
  kRussianRoulette,
  kSneeProbe,                // probe direction
  kSneeTopToBottom,          // light (3), inward microfacet normal (first of 2)
  kSneeTopToBottomDistance,  // second normal number, technique, channel, distance
  kSneeBottomToTop,          // middle vertex (4)
  kSneeBottomToTopBtdf,      // outward microfacet normal (2)
  kSneeManifold,             // the manifold strategy's light selection (3), its chain choice
  kSneeGuidedExit,           // the guided exit's rate and axis, its cap direction (2)
  kSneeGuidedExitLight,      // its light sample (3), its BSDF sample's lobe
  kSneeGuidedExitBsdf,       // its BSDF sample's microfacet normal (2)
  kCount
};

struct RandomBlock {
  float u[4];
};

// Maps 32 random bits to [0, 1) with 24 bits of precision (exact in float).
inline float bits_to_unit_float(uint32_t bits) {
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

inline RandomBlock random_block(uint32_t seed, uint32_t pixel, uint32_t sample, uint32_t event,
                                RngPurpose purpose) {
  using Philox = r123::Philox4x32;
  const Philox::ctr_type counter = {{sample, event, static_cast<uint32_t>(purpose), 0u}};
  const Philox::key_type key = {{pixel, seed}};
  const Philox::ctr_type bits = Philox()(counter, key);
  return {{bits_to_unit_float(bits[0]), bits_to_unit_float(bits[1]), bits_to_unit_float(bits[2]),
           bits_to_unit_float(bits[3])}};
}

}  // namespace snee
