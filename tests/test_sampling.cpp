// Direction warps, piecewise-constant distributions and the alias table: normalization, sample/pdf
// agreement and chi-square goodness of fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "kernels/physics/alias_table.h"
#include "kernels/physics/sampling.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

constexpr double kMinPValue = 1e-4;
// Quadrature of a smooth pdf converges far below this; float pdfs limit agreement to ~1e-6.
constexpr double kQuadratureTolerance = 1e-5;
// Float sums over a few hundred cells.
constexpr float kSumTolerance = 1e-5f;
constexpr int kSamples = 1'000'000;

// Pearson's test of counts against expected counts; cells expected empty must stay empty.
double pearson_p_value(const std::vector<int64_t>& observed, const std::vector<double>& expected) {
  double statistic = 0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] == 0) {
      if (observed[i] != 0) return 0;
      continue;
    }
    const double d = static_cast<double>(observed[i]) - expected[i];
    statistic += d * d / expected[i];
    ++cells;
  }
  return test::chi2_survival(statistic, cells - 1);
}

TEST(Warps, UniformSphere) {
  TestRng rng(1);
  EXPECT_NEAR(test::integrate_sphere([](Vec3) { return uniform_sphere_pdf(); }), 1.0,
              kQuadratureTolerance);
  const auto r = test::chi2_sphere(
      [&]() -> std::optional<Vec3> { return sample_uniform_sphere(rng.uniform2()); },
      [](Vec3) { return uniform_sphere_pdf(); }, {});
  EXPECT_GT(r.p_value, kMinPValue) << r.report;
}

TEST(Warps, CosineHemisphere) {
  TestRng rng(2);
  EXPECT_NEAR(test::integrate_sphere([](Vec3 w) { return cosine_hemisphere_pdf(w.z); }), 1.0,
              kQuadratureTolerance);
  const auto r = test::chi2_sphere(
      [&]() -> std::optional<Vec3> {
        const Vec3 w = sample_cosine_hemisphere(rng.uniform2());
        if (w.z < 0) return Vec3(0.0f);  // malformed: the test reports it
        return w;
      },
      [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, {});
  EXPECT_GT(r.p_value, kMinPValue) << r.report;
}

TEST(Warps, UniformCone) {
  for (const float cos_max : {0.999f, 0.9f, 0.3f, -0.5f, -1.0f}) {
    TestRng rng(3);
    const auto pdf = [&](Vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; };
    // Narrow cones get the whole bin grid; the rest of the sphere is one (empty) extra cell.
    // Normalization is covered too: the chi-square failure cell holds 1 - integral of the pdf.
    const double cos_min = cos_max > 0 ? 2.0 * cos_max - 1.0 : -1.0;
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> { return sample_uniform_cone(rng.uniform2(), cos_max); }, pdf,
        {.cos_min = cos_min});
    EXPECT_GT(r.p_value, kMinPValue) << "cos_max " << cos_max << "\n" << r.report;
  }
}

// Zeros at both ends and inside, one tiny weight, and uneven positive weights.
const std::vector<float> kWeights = {0, 1, 3, 0, 0.5f, 2, 1e-3f, 0, 7, 0.25f, 0};

TEST(Distribution1D, PmfSumsToOneAndIntegralIsMean) {
  const Distribution1D d(kWeights);
  float sum = 0, weight_sum = 0, pdf_integral = 0;
  for (int i = 0; i < d.size(); ++i) {
    sum += d.pmf(i);
    weight_sum += kWeights[i];
    pdf_integral += d.pdf_continuous((static_cast<float>(i) + 0.5f) / d.size()) / d.size();
    EXPECT_EQ(d.pmf(i) == 0, kWeights[i] == 0) << "cell " << i;
  }
  EXPECT_NEAR(sum, 1.0f, kSumTolerance);
  EXPECT_NEAR(pdf_integral, 1.0f, kSumTolerance);
  EXPECT_NEAR(d.integral(), weight_sum / d.size(), kSumTolerance);
}

TEST(Distribution1D, InvalidWeightsCountAsZero) {
  const std::vector<float> w = {-1, 2, std::numeric_limits<float>::quiet_NaN(), 2};
  const Distribution1D d(w);
  EXPECT_EQ(d.pmf(0), 0.0f);
  EXPECT_EQ(d.pmf(2), 0.0f);
  EXPECT_NEAR(d.pmf(1), 0.5f, kSumTolerance);
  EXPECT_NEAR(d.integral(), 1.0f, kSumTolerance);
}

TEST(Distribution1D, AllZeroIsUniform) {
  const std::vector<float> w(4, 0.0f);
  const Distribution1D d(w);
  EXPECT_EQ(d.integral(), 0.0f);
  TestRng rng(4);
  for (int k = 0; k < 1000; ++k) {
    float pdf = 0;
    const float x = d.sample_continuous(rng.uniform(), &pdf, nullptr);
    EXPECT_GE(x, 0.0f);
    EXPECT_LT(x, 1.0f);
    EXPECT_EQ(pdf, 1.0f);
  }
  for (int i = 0; i < 4; ++i) EXPECT_EQ(d.pmf(i), 0.25f);
}

TEST(Distribution1D, DiscreteChi2) {
  const Distribution1D d(kWeights);
  double weight_sum = 0;
  for (const float w : kWeights) weight_sum += w;
  std::vector<int64_t> counts(kWeights.size(), 0);
  std::vector<double> expected(kWeights.size());
  for (size_t i = 0; i < kWeights.size(); ++i) expected[i] = kSamples * kWeights[i] / weight_sum;
  TestRng rng(5);
  for (int k = 0; k < kSamples; ++k) {
    float pmf = 0;
    const int i = d.sample_discrete(rng.uniform(), &pmf);
    ASSERT_EQ(pmf, d.pmf(i));
    ++counts[i];
  }
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
}

TEST(AliasTable, PmfIsTheNormalizedWeights) {
  const AliasTable t(kWeights);
  double weight_sum = 0;
  for (const float w : kWeights) weight_sum += w;
  float sum = 0;
  for (int i = 0; i < t.size(); ++i) {
    sum += t.pmf(i);
    EXPECT_NEAR(t.pmf(i), kWeights[i] / weight_sum, kSumTolerance) << "entry " << i;
    EXPECT_EQ(t.pmf(i) == 0, kWeights[i] == 0) << "entry " << i;
  }
  EXPECT_NEAR(sum, 1.0f, kSumTolerance);
}

TEST(AliasTable, ZeroAndInvalidWeightsAreNeverSampled) {
  // Skewed so that the big entry lends to many bins and rounding has a chance to leave a
  // zero-weight bin over at the end.
  const std::vector<float> w = {0, 1e-7f, -1, 5, std::numeric_limits<float>::quiet_NaN(), 0, 1};
  const AliasTable t(w);
  constexpr int kSteps = 1 << 20;
  for (int k = 0; k <= kSteps; ++k) {
    const float u = std::min(static_cast<float>(k) / kSteps, 0x1.fffffep-1f);
    float pmf = 0, rest = -1;
    const int i = t.sample(u, &pmf, &rest);
    ASSERT_GT(w[i], 0.0f) << "u = " << u;
    ASSERT_EQ(pmf, t.pmf(i));
    ASSERT_GE(rest, 0.0f);
    ASSERT_LT(rest, 1.0f);
  }
}

TEST(AliasTable, SingleEntryAndAllZero) {
  const std::vector<float> one = {3};
  const AliasTable single(one);
  float pmf = 0, rest = 0;
  EXPECT_EQ(single.sample(0.37f, &pmf, &rest), 0);
  EXPECT_EQ(pmf, 1.0f);
  EXPECT_FLOAT_EQ(rest, 0.37f);

  const std::vector<float> zeros(4, 0.0f);
  const AliasTable uniform(zeros);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(uniform.pmf(i), 0.25f);
}

// The entry frequencies follow the weights, and the remapped number is uniform within each
// entry: counts over (entry, tenth of [0,1)) cells against pmf / 10 each.
TEST(AliasTable, Chi2OfEntriesAndRemappedNumber) {
  const AliasTable t(kWeights);
  constexpr int kTenths = 10;
  std::vector<int64_t> counts(kWeights.size() * kTenths, 0);
  std::vector<double> expected(counts.size());
  for (size_t i = 0; i < counts.size(); ++i) {
    expected[i] = kSamples * static_cast<double>(t.pmf(static_cast<int>(i / kTenths))) / kTenths;
  }
  TestRng rng(6);
  for (int k = 0; k < kSamples; ++k) {
    float rest = 0;
    const int i = t.sample(rng.uniform(), nullptr, &rest);
    ++counts[static_cast<size_t>(i) * kTenths + static_cast<size_t>(rest * kTenths)];
  }
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
}

// Bins several per cell, so the position within a cell is tested as well as the cell choice.
TEST(Distribution1D, ContinuousChi2AndPdfRoundTrip) {
  const Distribution1D d(kWeights);
  constexpr int kSubBins = 8;
  const int bins = d.size() * kSubBins;
  double weight_sum = 0;
  for (const float w : kWeights) weight_sum += w;
  std::vector<int64_t> counts(bins, 0);
  std::vector<double> expected(bins);
  for (int b = 0; b < bins; ++b) {
    expected[b] = kSamples * kWeights[b / kSubBins] / weight_sum / kSubBins;
  }
  TestRng rng(6);
  for (int k = 0; k < kSamples; ++k) {
    float pdf = 0;
    int cell = -1;
    const float x = d.sample_continuous(rng.uniform(), &pdf, &cell);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_EQ(cell, static_cast<int>(x * d.size()));
    ASSERT_EQ(pdf, d.pdf_continuous(x));
    ASSERT_GT(pdf, 0.0f);
    ++counts[std::min(bins - 1, static_cast<int>(x * bins))];
  }
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
}

// 7 x 5 cells with a zero row, a zero column and scattered zeros.
struct Grid2D {
  static constexpr int kWidth = 7, kHeight = 5;
  std::vector<float> weights;
  Grid2D() : weights(kWidth * kHeight) {
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const bool zero = y == 2 || x == 4 || (x + y) % 5 == 0;
        weights[y * kWidth + x] = zero ? 0.0f : 0.5f + static_cast<float>((3 * x + 7 * y) % 6);
      }
    }
  }
  Vec2 center(int x, int y) const {
    return {(static_cast<float>(x) + 0.5f) / kWidth, (static_cast<float>(y) + 0.5f) / kHeight};
  }
};

TEST(Distribution2D, PdfIntegratesToOneAndIsProportionalToWeights) {
  const Grid2D g;
  const Distribution2D d(g.weights, Grid2D::kWidth, Grid2D::kHeight);
  double weight_sum = 0;
  for (const float w : g.weights) weight_sum += w;
  const double mean_weight = weight_sum / g.weights.size();
  float integral = 0;
  for (int y = 0; y < Grid2D::kHeight; ++y) {
    for (int x = 0; x < Grid2D::kWidth; ++x) {
      const float pdf = d.pdf(g.center(x, y));
      integral += pdf / (Grid2D::kWidth * Grid2D::kHeight);
      EXPECT_NEAR(pdf, g.weights[y * Grid2D::kWidth + x] / mean_weight, kSumTolerance);
    }
  }
  EXPECT_NEAR(integral, 1.0f, kSumTolerance);
}

TEST(Distribution2D, Chi2AndPdfRoundTrip) {
  const Grid2D g;
  const Distribution2D d(g.weights, Grid2D::kWidth, Grid2D::kHeight);
  constexpr int kSub = 3;  // sub-bins per cell and axis
  constexpr int kBinsX = Grid2D::kWidth * kSub, kBinsY = Grid2D::kHeight * kSub;
  double weight_sum = 0;
  for (const float w : g.weights) weight_sum += w;
  std::vector<int64_t> counts(kBinsX * kBinsY, 0);
  std::vector<double> expected(kBinsX * kBinsY);
  for (int by = 0; by < kBinsY; ++by) {
    for (int bx = 0; bx < kBinsX; ++bx) {
      const float w = g.weights[(by / kSub) * Grid2D::kWidth + bx / kSub];
      expected[by * kBinsX + bx] = kSamples * w / weight_sum / (kSub * kSub);
    }
  }
  TestRng rng(7);
  for (int k = 0; k < kSamples; ++k) {
    float pdf = 0;
    const Vec2 uv = d.sample(rng.uniform2(), &pdf);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LT(uv.x, 1.0f);
    ASSERT_GE(uv.y, 0.0f);
    ASSERT_LT(uv.y, 1.0f);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_NEAR(pdf, d.pdf(uv), FLT_EPSILON * pdf);
    const int bx = std::min(kBinsX - 1, static_cast<int>(uv.x * kBinsX));
    const int by = std::min(kBinsY - 1, static_cast<int>(uv.y * kBinsY));
    ++counts[by * kBinsX + bx];
  }
  EXPECT_GT(pearson_p_value(counts, expected), kMinPValue);
}

}  // namespace
}  // namespace snee
