// Batched Fresnel reflectance, Henyey-Greenstein phase function and frames: bit for bit equal to
// the scalar functions, including total internal reflection, grazing and index-matched cases.
// Batched dielectric samples (one template with the scalar samplers): bit for bit.
// Batched HG sampling: the pdf bit for bit, directions within the stated absolute bound (xsimd's
// sincos of the azimuth is not libm's).
#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <random>

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/sampling.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/hg_sample_batch.h"
#include "kernels/simd/sampling_batch.h"
#include "tests/support/lanes.h"

namespace snee {
namespace {

using simd::FloatBatch;
using simd::kLanes;

using Lanes = test::Lanes<float>;
using test::to_lanes;

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
    const Lanes got = to_lanes(fresnel_dielectric(c.batch(), eta.batch()));
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
    const Lanes got = to_lanes(hg_phase(mu.batch(), g.batch()));
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

// A lane's sine and cosine do not depend on its neighbours, not even on a NaN or huge one (which
// switches xsimd's own sincos to another argument reduction for the whole batch).
TEST(ShadingBatch, LanewiseSincosIgnoresOtherLanes) {
  std::mt19937 engine(17);
  std::uniform_real_distribution<float> angle(-20.0f * kPi, 20.0f * kPi);
  const float odd[] = {std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::infinity(), 1e30f, -1e6f};
  int compared = 0;
  for (int k = 0; k < 20000; ++k) {
    test::Lanes<float> x;
    for (float& v : x.v) v = angle(engine);
    const auto [sin_ref, cos_ref] = simd::lanewise_sincos(x.batch());
    const test::Lanes<float> s = test::to_lanes(sin_ref), c = test::to_lanes(cos_ref);
    test::Lanes<float> y = x;
    y.v[0] = odd[k % 4];
    const auto [sin_y, cos_y] = simd::lanewise_sincos(y.batch());
    const test::Lanes<float> sy = test::to_lanes(sin_y), cy = test::to_lanes(cos_y);
    for (size_t l = 1; l < simd::kLanes; ++l) {
      ASSERT_EQ(std::bit_cast<uint32_t>(s.v[l]), std::bit_cast<uint32_t>(sy.v[l])) << x.v[l];
      ASSERT_EQ(std::bit_cast<uint32_t>(c.v[l]), std::bit_cast<uint32_t>(cy.v[l])) << x.v[l];
      ++compared;
    }
  }
  EXPECT_GT(compared, 50000);
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

uint32_t bits(float f) {
  return std::bit_cast<uint32_t>(f);
}

// Directions (some grazing, one in the surface plane), interfaces and random numbers for one
// batch of dielectric samples: smooth, index-matched and rough interfaces from both sides, in
// mixed chunks and in chunks of one interface (which skip the other path).
struct InterfaceLanes {
  Lanes wx, wy, wz, eta, alpha, u0, u1, u_lobe;
};
InterfaceLanes random_interface_lanes(std::mt19937& engine, int trial) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float alphas[] = {0.0f, 1e-3f, 0.04f, 0.2f, 0.7f};
  const float etas[] = {1.5f, 1.0f, 1.33f, 2.4f};
  InterfaceLanes in;
  for (size_t i = 0; i < kLanes; ++i) {
    Vec3 w = random_direction(engine, trial, i);
    if (trial % 13 == 0) w = normalize(Vec3(w.x, w.y, 1e-4f * w.z));  // grazing
    if (trial == 5) w = Vec3(1.0f, 0.0f, 0.0f);                       // w.z == 0
    in.wx.v[i] = w.x, in.wy.v[i] = w.y, in.wz.v[i] = w.z;
    const bool uniform = trial % 3 == 0;
    in.eta.v[i] = uniform ? etas[(trial / 3) % 4] : etas[(trial + i) % 4];
    in.alpha.v[i] = uniform ? alphas[(trial / 12) % 5] : alphas[(trial / 4 + i) % 5];
    in.u0.v[i] = unit(engine), in.u1.v[i] = unit(engine), in.u_lobe.v[i] = unit(engine);
  }
  return in;
}

TEST(ShadingBatch, DielectricSampleMatchesScalarBitwise) {
  std::mt19937 engine(13);
  int valid = 0, lanes = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const InterfaceLanes in = random_interface_lanes(engine, trial);
    const Lanes &wx = in.wx, &wy = in.wy, &wz = in.wz, &eta = in.eta, &alpha = in.alpha,
                &u0 = in.u0, &u1 = in.u1, &ul = in.u_lobe;
    const simd::BsdfSampleBatch got =
        simd::dielectric_sample({eta.batch(), alpha.batch()}, {wx.batch(), wy.batch(), wz.batch()},
                                u0.batch(), u1.batch(), ul.batch());
    const Lanes gx = to_lanes(got.wi.x), gy = to_lanes(got.wi.y), gz = to_lanes(got.wi.z),
                f = to_lanes(got.f), pdf = to_lanes(got.pdf);
    alignas(64) bool ok[kLanes], transmission[kLanes], delta[kLanes];
    got.valid.store_aligned(ok);
    got.transmission.store_aligned(transmission);
    got.delta.store_aligned(delta);
    for (size_t i = 0; i < kLanes; ++i) {
      const BsdfSample want = dielectric_sample({eta.v[i], alpha.v[i]}, {wx.v[i], wy.v[i], wz.v[i]},
                                                {u0.v[i], u1.v[i]}, ul.v[i]);
      ++lanes;
      ASSERT_EQ(ok[i], want.valid) << "eta " << eta.v[i] << " alpha " << alpha.v[i];
      if (!want.valid) continue;
      ++valid;
      ASSERT_EQ(bits(gx.v[i]), bits(want.wi.x));
      ASSERT_EQ(bits(gy.v[i]), bits(want.wi.y));
      ASSERT_EQ(bits(gz.v[i]), bits(want.wi.z));
      ASSERT_EQ(bits(f.v[i]), bits(want.f));
      ASSERT_EQ(bits(pdf.v[i]), bits(want.pdf));
      ASSERT_EQ(transmission[i], want.transmission);
      ASSERT_EQ(delta[i], want.delta);
    }
  }
  // Most samples succeed: the comparison is not vacuous.
  EXPECT_GT(valid, lanes / 2);
}

// SNEE's transmission-only sampler: one template, so the batch form returns the scalar form's
// direction bit for bit wherever the scalar sample succeeds, and fails where it fails.
TEST(ShadingBatch, DielectricSampleTransmissionMatchesScalarBitwise) {
  std::mt19937 engine(14);
  int ok_lanes = 0, lanes = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const InterfaceLanes in = random_interface_lanes(engine, trial);
    const Lanes &wx = in.wx, &wy = in.wy, &wz = in.wz, &eta = in.eta, &alpha = in.alpha,
                &u0 = in.u0, &u1 = in.u1;
    const Refracted<FloatBatch> got = simd::dielectric_sample_transmission(
        simd::DielectricLanes{eta.batch(), alpha.batch()}, {wx.batch(), wy.batch(), wz.batch()},
        u0.batch(), u1.batch());
    const Lanes gx = to_lanes(got.direction.x), gy = to_lanes(got.direction.y),
                gz = to_lanes(got.direction.z);
    alignas(64) bool ok[kLanes];
    got.ok.store_aligned(ok);
    for (size_t i = 0; i < kLanes; ++i) {
      Vec3 want;
      const bool want_ok = dielectric_sample_transmission(
          {eta.v[i], alpha.v[i]}, {wx.v[i], wy.v[i], wz.v[i]}, {u0.v[i], u1.v[i]}, &want);
      ++lanes;
      ASSERT_EQ(ok[i], want_ok) << "eta " << eta.v[i] << " alpha " << alpha.v[i];
      if (!want_ok) continue;
      ++ok_lanes;
      ASSERT_EQ(bits(gx.v[i]), bits(want.x));
      ASSERT_EQ(bits(gy.v[i]), bits(want.y));
      ASSERT_EQ(bits(gz.v[i]), bits(want.z));
    }
  }
  EXPECT_GT(ok_lanes, lanes / 2);
}

}  // namespace
}  // namespace snee
