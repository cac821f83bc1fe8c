// The batched free-flight functions against the scalar ones (kernels/physics/medium/free_flight.h).
// xsimd's exp and log1p are not libm's, so agreement is to a few ulp; the bounds here are the ones
// kernels/simd/README.md states (the largest distances seen over 8M lanes). xsimd's exp also
// flushes results below FLT_MIN to zero where libm returns subnormals (the renderer runs with
// FTZ/DAZ anyway), which moves a value by at most sigma * FLT_MIN: differences that small pass.
#include <gtest/gtest.h>

#include <cfloat>
#include <random>

#include "kernels/physics/medium/free_flight.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/free_flight_batch.h"
#include "tests/support/lanes.h"
#include "tests/support/ulp.h"

namespace snee {
namespace {

using simd::FloatBatch;
using simd::kLanes;

constexpr float kMaxSigma = 50.0f;
constexpr int64_t kSampleUlps = 2;         // -log1p(-u) / sigma
constexpr int64_t kTransmittanceUlps = 2;  // exp(-sigma d)
constexpr int64_t kMixtureUlps = 4;        // pdf and survival: sums of three exp terms
constexpr int64_t kChannelPdfUlps = 2;     // sigma exp(-sigma t)

using Lanes = test::Lanes<float>;
using test::to_lanes;

// Tracks the largest ulp distance seen beyond an absolute floor, so a failure reports it.
struct UlpCheck {
  const char* name;
  int64_t bound;
  float floor;
  int64_t worst = 0;
  void add(float batch, float scalar) {
    if (std::fabs(batch - scalar) <= floor) return;
    const int64_t ulps = test::ulp_distance(batch, scalar);
    worst = std::max(worst, ulps);
  }
  ~UlpCheck() { EXPECT_LE(worst, bound) << name; }
};

class FreeFlightBatch : public ::testing::Test {
 protected:
  // sigma in [0, 50] per channel, a fifth of the channels clear (sigma = 0).
  float sigma() {
    const float u = unit_(engine_);
    return u < 0.2f ? 0.0f : kMaxSigma * unit_(engine_) * unit_(engine_);
  }
  float unit() { return static_cast<float>(engine_() >> 8) * 0x1p-24f; }
  // Distances from 0 up to beyond where every transmittance underflows.
  float distance() { return unit_(engine_) < 0.05f ? kInfinity : 20.0f * sqr(unit_(engine_)); }

  std::mt19937 engine_{7};
  std::uniform_real_distribution<float> unit_{0.0f, 1.0f};
};

TEST_F(FreeFlightBatch, AgreesWithScalarWithinUlpBounds) {
  UlpCheck sample{"sample", kSampleUlps, 0.0f}, pdf{"pdf", kMixtureUlps, kMaxSigma * FLT_MIN},
      survival{"survival", kMixtureUlps, FLT_MIN},
      trans{"transmittance", kTransmittanceUlps, FLT_MIN};
  for (int trial = 0; trial < 500000; ++trial) {
    Lanes sr, sg, sb, uc, u, d;
    for (size_t i = 0; i < kLanes; ++i) {
      sr.v[i] = sigma();
      sg.v[i] = sigma();
      sb.v[i] = sigma();
      uc.v[i] = unit();
      u.v[i] = unit();
      d.v[i] = distance();
    }
    const simd::Vec3Batch sigma_t{sr.batch(), sg.batch(), sb.batch()};
    const Lanes t = to_lanes(simd::free_flight_sample(sigma_t, uc.batch(), u.batch()));
    const Lanes p = to_lanes(simd::free_flight_pdf(sigma_t, d.batch()));
    const Lanes s = to_lanes(simd::free_flight_survival(sigma_t, d.batch()));
    const simd::Vec3Batch tr = simd::transmittance(sigma_t, d.batch());
    const Lanes tx = to_lanes(tr.x), ty = to_lanes(tr.y), tz = to_lanes(tr.z);
    for (size_t i = 0; i < kLanes; ++i) {
      const Rgb st(sr.v[i], sg.v[i], sb.v[i]);
      const float want_t = free_flight_sample(st, uc.v[i], u.v[i]);
      if (std::isinf(want_t)) {
        ASSERT_EQ(t.v[i], want_t);  // a clear channel was picked
      } else {
        sample.add(t.v[i], want_t);
      }
      pdf.add(p.v[i], free_flight_pdf(st, d.v[i]));
      survival.add(s.v[i], free_flight_survival(st, d.v[i]));
      const Rgb want_tr = transmittance(st, d.v[i]);
      trans.add(tx.v[i], want_tr.x);
      trans.add(ty.v[i], want_tr.y);
      trans.add(tz.v[i], want_tr.z);
    }
  }
}

// The path-level mixture medium_event runs: weighted channel choice, per-channel pdfs formed
// from the transmittance, and the weighted pdf and survival as dot products with p.
TEST_F(FreeFlightBatch, PathLevelMixtureAgreesWithScalarWithinUlpBounds) {
  UlpCheck sample{"sample", kSampleUlps, 0.0f},
      channel_pdf{"channel pdf", kChannelPdfUlps, kMaxSigma * FLT_MIN},
      pdf{"pdf", kMixtureUlps, kMaxSigma * FLT_MIN}, survival{"survival", kMixtureUlps, FLT_MIN};
  for (int trial = 0; trial < 500000; ++trial) {
    Lanes sr, sg, sb, pr, pg, pb, uc, u, d;
    for (size_t i = 0; i < kLanes; ++i) {
      sr.v[i] = sigma();
      sg.v[i] = sigma();
      sb.v[i] = sigma();
      const Rgb w(unit() + 0.01f, unit() + 0.01f, trial % 5 == 0 ? 0.0f : unit());
      const float total = w.x + w.y + w.z;
      pr.v[i] = w.x / total;
      pg.v[i] = w.y / total;
      pb.v[i] = w.z / total;
      uc.v[i] = unit();
      u.v[i] = unit();
      d.v[i] = distance();
    }
    const simd::Vec3Batch sigma_t{sr.batch(), sg.batch(), sb.batch()};
    const simd::Vec3Batch p{pr.batch(), pg.batch(), pb.batch()};
    const Lanes t = to_lanes(simd::free_flight_sample(sigma_t, p, uc.batch(), u.batch()));
    const simd::Vec3Batch tr = simd::transmittance(sigma_t, d.batch());
    const simd::Vec3Batch q = simd::free_flight_channel_pdfs(sigma_t, tr);
    const Lanes qx = to_lanes(q.x), qy = to_lanes(q.y), qz = to_lanes(q.z);
    const Lanes mix = to_lanes(simd::dot(p, q)), surv = to_lanes(simd::dot(p, tr));
    for (size_t i = 0; i < kLanes; ++i) {
      const Rgb st(sr.v[i], sg.v[i], sb.v[i]), pi(pr.v[i], pg.v[i], pb.v[i]);
      const float want_t = free_flight_sample(st, pi, uc.v[i], u.v[i]);
      if (std::isinf(want_t)) {
        ASSERT_EQ(t.v[i], want_t);
      } else {
        sample.add(t.v[i], want_t);
      }
      const Rgb want_q = free_flight_channel_pdfs(st, d.v[i]);
      channel_pdf.add(qx.v[i], want_q.x);
      channel_pdf.add(qy.v[i], want_q.y);
      channel_pdf.add(qz.v[i], want_q.z);
      pdf.add(mix.v[i], free_flight_pdf(st, pi, d.v[i]));
      survival.add(surv.v[i], free_flight_survival(st, pi, d.v[i]));
    }
  }
}

TEST_F(FreeFlightBatch, InfiniteDistancesAndClearChannelsAreExact) {
  const simd::Vec3Batch sigma_t{FloatBatch(0.0f), FloatBatch(1.0f), FloatBatch(3.0f)};
  const FloatBatch inf(kInfinity);
  const Lanes tr_x = to_lanes(simd::transmittance(sigma_t, inf).x);
  const Lanes tr_y = to_lanes(simd::transmittance(sigma_t, inf).y);
  const Lanes pdf = to_lanes(simd::free_flight_pdf(sigma_t, inf));
  const Lanes survival = to_lanes(simd::free_flight_survival(sigma_t, inf));
  const Lanes clear =
      to_lanes(simd::free_flight_sample(sigma_t, FloatBatch(0.1f), FloatBatch(0.5f)));
  for (size_t i = 0; i < kLanes; ++i) {
    EXPECT_EQ(tr_x.v[i], 1.0f);
    EXPECT_EQ(tr_y.v[i], 0.0f);
    EXPECT_EQ(pdf.v[i], 0.0f);
    EXPECT_EQ(survival.v[i], free_flight_survival(Rgb(0.0f, 1.0f, 3.0f), kInfinity));
    EXPECT_EQ(clear.v[i], kInfinity);
  }
}

}  // namespace
}  // namespace snee
