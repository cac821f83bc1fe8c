// The preview's tone mapping (scene/tone_map.h) against its formulas: the sRGB OETF's two
// segments, Narkowicz's ACES fit at hand-computed points, monotonicity, 0 -> 0, and exposure
// as a power of two on the input.
#include "scene/tone_map.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace snee {
namespace {

TEST(SrgbEncode, FollowsBothSegmentsOfTheStandard) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_EQ(srgb_encode(1.0f), 1.0f);
  // Linear segment: 12.92 x up to 0.0031308.
  EXPECT_FLOAT_EQ(srgb_encode(0.001f), 0.01292f);
  // Power segment: 1.055 x^(1/2.4) - 0.055; 0.5 -> 0.735357, 0.18 (mid grey) -> 0.461356.
  EXPECT_NEAR(srgb_encode(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.461356f, 1e-5f);
  // The two segments meet (within float rounding) at the threshold.
  EXPECT_NEAR(12.92f * 0.0031308f, 1.055f * std::pow(0.0031308f, 1.0f / 2.4f) - 0.055f, 1e-6f);
  // Not gamma 2.2: in the shadows the two differ by far more than a code value.
  EXPECT_GT(std::abs(srgb_encode(0.002f) - std::pow(0.002f, 1.0f / 2.2f)), 0.01f);
}

TEST(SrgbEncode, ClipsOutOfRangeAndNonFinite) {
  EXPECT_EQ(srgb_encode(-1.0f), 0.0f);
  EXPECT_EQ(srgb_encode(7.0f), 1.0f);
  EXPECT_EQ(srgb_encode(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_EQ(srgb_encode(std::numeric_limits<float>::infinity()), 1.0f);
}

TEST(AcesFitted, MatchesTheRationalFormula) {
  EXPECT_EQ(aces_fitted(0.0f), 0.0f);
  // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) evaluated by hand.
  EXPECT_NEAR(aces_fitted(1.0f), 2.54f / 3.16f, 1e-6f);
  EXPECT_NEAR(aces_fitted(0.18f), 0.18f * 0.4818f / (0.18f * 1.0274f + 0.14f), 1e-6f);
  EXPECT_NEAR(aces_fitted(4.0f), 4.0f * 10.07f / (4.0f * 10.31f + 0.14f), 1e-6f);
  EXPECT_EQ(aces_fitted(100.0f), 1.0f);
  EXPECT_EQ(aces_fitted(std::numeric_limits<float>::infinity()), 1.0f);
  EXPECT_EQ(aces_fitted(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_EQ(aces_fitted(-2.0f), 0.0f);
}

TEST(AcesFitted, IsMonotoneAndStaysInTheUnitInterval) {
  float previous = aces_fitted(0.0f);
  for (int i = 1; i <= 20000; ++i) {
    const float x = 0.001f * static_cast<float>(i);  // 0 .. 20, across the crossing of 1
    const float y = aces_fitted(x);
    EXPECT_GE(y, previous) << "x = " << x;
    EXPECT_GE(y, 0.0f);
    EXPECT_LE(y, 1.0f);
    previous = y;
  }
}

TEST(ToneMap, ExposureDoublesTheInputPerStop) {
  for (const ToneCurve curve : {ToneCurve::kClamp, ToneCurve::kFilmic}) {
    const ToneMap base{0.0f, curve};
    for (const float ev : {-3.0f, -1.0f, 1.0f, 2.0f}) {
      const ToneMap exposed{ev, curve};
      for (const float x : {0.01f, 0.1f, 0.3f}) {
        EXPECT_FLOAT_EQ(exposed.encode(x), base.encode(x * std::exp2(ev)))
            << "ev " << ev << " x " << x;
      }
    }
    EXPECT_EQ(ToneMap({5.0f, curve}).encode(0.0f), 0.0f);
  }
}

TEST(ToneMap, CurvesComposeWithTheOetf) {
  const ToneMap clamp{0.0f, ToneCurve::kClamp};
  const ToneMap filmic{0.0f, ToneCurve::kFilmic};
  EXPECT_FLOAT_EQ(clamp.encode(0.5f), srgb_encode(0.5f));
  EXPECT_EQ(clamp.encode(2.0f), 1.0f);  // clamp clips every highlight
  EXPECT_FLOAT_EQ(filmic.encode(0.5f), srgb_encode(aces_fitted(0.5f)));
  EXPECT_LT(filmic.encode(2.0f), filmic.encode(4.0f));  // the shoulder keeps gradation
  float previous = 0.0f;
  for (int i = 1; i <= 1000; ++i) {
    const float y = filmic.encode(0.01f * static_cast<float>(i));
    EXPECT_GE(y, previous);
    previous = y;
  }
}

}  // namespace
}  // namespace snee
