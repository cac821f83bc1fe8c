// Batched Fresnel reflectance and Henyey-Greenstein phase function: bit for bit equal to the
// scalar functions, including total internal reflection, grazing and index-matched cases.
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "kernels/bsdf/fresnel.h"
#include "kernels/medium/henyey_greenstein.h"
#include "kernels/simd/fresnel_batch.h"
#include "kernels/simd/hg_phase_batch.h"

namespace snee {
namespace {

using simd::FloatBatch;
using simd::kLanes;

struct Lanes {
  alignas(64) float v[kLanes];
  FloatBatch batch() const { return FloatBatch::load_aligned(v); }
};

Lanes to_lanes(FloatBatch b) {
  Lanes l;
  b.store_aligned(l.v);
  return l;
}

TEST(ShadingBatch, FresnelMatchesScalarBitwise) {
  std::mt19937 engine(8);
  std::uniform_real_distribution<float> cosine(-0.2f, 1.2f), index(0.3f, 3.0f);
  const float edge_cos[] = {0.0f, -0.0f, 1.0f, 1e-8f, 0.5f};
  const float edge_eta[] = {1.0f, 1.5f, 1.0f / 1.5f, 1.33f, 1.0f / 1.33f};
  for (int trial = 0; trial < 100000; ++trial) {
    Lanes c, eta;
    for (size_t i = 0; i < kLanes; ++i) {
      c.v[i] = trial < 25 ? edge_cos[(trial + i) % 5] : cosine(engine);
      eta.v[i] = trial < 25 ? edge_eta[trial / 5] : index(engine);
    }
    const Lanes got = to_lanes(simd::fresnel_dielectric(c.batch(), eta.batch()));
    for (size_t i = 0; i < kLanes; ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(got.v[i]),
                std::bit_cast<uint32_t>(fresnel_dielectric(c.v[i], eta.v[i])))
          << "cos " << c.v[i] << " eta " << eta.v[i];
  }
}

TEST(ShadingBatch, HenyeyGreensteinMatchesScalarBitwise) {
  std::mt19937 engine(9);
  std::uniform_real_distribution<float> cosine(-1.0f, 1.0f), asymmetry(-0.99f, 0.99f);
  for (int trial = 0; trial < 100000; ++trial) {
    Lanes mu, g;
    for (size_t i = 0; i < kLanes; ++i) {
      mu.v[i] = trial < 10 ? (i % 2 ? 1.0f : -1.0f) : cosine(engine);
      g.v[i] = trial % 7 == 0 ? 0.0f : asymmetry(engine);
    }
    const Lanes got = to_lanes(simd::hg_phase(mu.batch(), g.batch()));
    for (size_t i = 0; i < kLanes; ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(got.v[i]),
                std::bit_cast<uint32_t>(hg_phase(mu.v[i], g.v[i])))
          << "mu " << mu.v[i] << " g " << g.v[i];
  }
}

}  // namespace
}  // namespace snee
