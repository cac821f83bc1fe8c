// Batched Fresnel reflectance, Henyey-Greenstein phase function and frames: bit for bit equal to
// the scalar functions, including total internal reflection, grazing and index-matched cases.
// Batched HG sampling: the pdf bit for bit, directions within the stated absolute bound (xsimd's
// sincos of the azimuth is not libm's).
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "kernels/bsdf/fresnel.h"
#include "kernels/medium/henyey_greenstein.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/fresnel_batch.h"
#include "kernels/simd/hg_phase_batch.h"
#include "kernels/simd/hg_sample_batch.h"
#include "kernels/simd/sampling_batch.h"
#include "kernels/sampling.h"

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

// Unit vectors spread over the sphere, with the poles (the frame's sign switch) included.
Vec3 random_direction(std::mt19937& engine, int trial, size_t lane) {
  if (trial < 4) {
    const float z = (trial + lane) % 2 ? 1.0f : -1.0f;
    return trial < 2 ? Vec3(0.0f, 0.0f, z) : normalize(Vec3(1e-7f, -2e-7f, z));
  }
  std::normal_distribution<float> normal;
  return normalize(Vec3(normal(engine), normal(engine), normal(engine)));
}

TEST(ShadingBatch, FrameMatchesScalarBitwise) {
  std::mt19937 engine(10);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  for (int trial = 0; trial < 100000; ++trial) {
    Lanes nx, ny, nz, vx, vy, vz;
    for (size_t i = 0; i < kLanes; ++i) {
      const Vec3 n = random_direction(engine, trial, i);
      nx.v[i] = n.x, ny.v[i] = n.y, nz.v[i] = n.z;
      vx.v[i] = coordinate(engine), vy.v[i] = coordinate(engine), vz.v[i] = coordinate(engine);
    }
    const simd::FrameBatch frame =
        simd::FrameBatch::from_normal({nx.batch(), ny.batch(), nz.batch()});
    const simd::Vec3Batch w = frame.to_world({vx.batch(), vy.batch(), vz.batch()});
    const Lanes wx = to_lanes(w.x), wy = to_lanes(w.y), wz = to_lanes(w.z);
    for (size_t i = 0; i < kLanes; ++i) {
      const Vec3 want =
          Frame::from_normal({nx.v[i], ny.v[i], nz.v[i]}).to_world({vx.v[i], vy.v[i], vz.v[i]});
      ASSERT_EQ(std::bit_cast<uint32_t>(wx.v[i]), std::bit_cast<uint32_t>(want.x));
      ASSERT_EQ(std::bit_cast<uint32_t>(wy.v[i]), std::bit_cast<uint32_t>(want.y));
      ASSERT_EQ(std::bit_cast<uint32_t>(wz.v[i]), std::bit_cast<uint32_t>(want.z));
    }
  }
}

// The bound of kernels/simd/README.md: the largest component difference seen over these lanes.
constexpr float kDirectionBound = 0x1p-21f;

TEST(ShadingBatch, HenyeyGreensteinSampleMatchesScalar) {
  std::mt19937 engine(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), asymmetry(-0.99f, 0.99f);
  float worst = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    Lanes wx, wy, wz, g, u0, u1;
    for (size_t i = 0; i < kLanes; ++i) {
      const Vec3 w = random_direction(engine, trial, i);
      wx.v[i] = w.x, wy.v[i] = w.y, wz.v[i] = w.z;
      g.v[i] = trial % 7 == 0 ? 0.0f : asymmetry(engine);
      u0.v[i] = trial % 11 == 0 ? (i % 2 ? 0.0f : std::nextafter(1.0f, 0.0f)) : unit(engine);
      u1.v[i] = unit(engine);
    }
    const simd::HgSampleBatch got =
        simd::hg_sample({wx.batch(), wy.batch(), wz.batch()}, g.batch(), u0.batch(), u1.batch());
    const Lanes dx = to_lanes(got.direction.x), dy = to_lanes(got.direction.y),
                dz = to_lanes(got.direction.z), pdf = to_lanes(got.pdf);
    for (size_t i = 0; i < kLanes; ++i) {
      float want_pdf = 0;
      const Vec3 want =
          hg_sample({wx.v[i], wy.v[i], wz.v[i]}, g.v[i], {u0.v[i], u1.v[i]}, &want_pdf);
      ASSERT_EQ(std::bit_cast<uint32_t>(pdf.v[i]), std::bit_cast<uint32_t>(want_pdf));
      worst = std::max({worst, std::fabs(dx.v[i] - want.x), std::fabs(dy.v[i] - want.y),
                        std::fabs(dz.v[i] - want.z)});
    }
  }
  EXPECT_LE(worst, kDirectionBound) << "largest component difference " << worst;
  RecordProperty("largest_component_difference", std::to_string(worst));
  std::printf("largest direction component difference: %g (2^%.2f)\n", worst, std::log2(worst));
}

TEST(ShadingBatch, UniformSphereSampleMatchesScalar) {
  std::mt19937 engine(12);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  float worst = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    Lanes u0, u1;
    for (size_t i = 0; i < kLanes; ++i) {
      u0.v[i] = trial < 2 ? (trial == 0 ? 0.0f : std::nextafter(1.0f, 0.0f)) : unit(engine);
      u1.v[i] = unit(engine);
    }
    const simd::Vec3Batch got = simd::sample_uniform_sphere(u0.batch(), u1.batch());
    const Lanes dx = to_lanes(got.x), dy = to_lanes(got.y), dz = to_lanes(got.z);
    for (size_t i = 0; i < kLanes; ++i) {
      const Vec3 want = sample_uniform_sphere({u0.v[i], u1.v[i]});
      ASSERT_EQ(std::bit_cast<uint32_t>(dz.v[i]), std::bit_cast<uint32_t>(want.z));
      worst = std::max({worst, std::fabs(dx.v[i] - want.x), std::fabs(dy.v[i] - want.y)});
    }
  }
  EXPECT_LE(worst, kDirectionBound) << "largest component difference " << worst;
}

}  // namespace
}  // namespace snee
