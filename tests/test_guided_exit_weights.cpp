// The guided exit's MIS weights against the walk's exits (kernels/stages/guided_exit.h,
// docs/method.md 3.15): for every path both can make, the weights of the strategies that can
// make it sum to one, and without the guide the walk keeps the path tracer's weights.
#include <gtest/gtest.h>

#include <random>

#include "kernels/stages/guided_exit.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {
namespace {

TEST(GuidedExitWeights, SumToOneForEveryPathClass) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> log_density(-4.0f, 4.0f);
  const auto density = [&] { return std::pow(10.0f, log_density(rng)); };
  for (int i = 0; i < 10000; ++i) {
    const float a = density(), b = density(), p_light = density(), p_bsdf = density();
    const float ratio = b / a;
    // A non-delta distant light behind a glossy boundary: four strategies.
    EXPECT_NEAR(walk_light_sample_weight(ratio, p_light, p_bsdf, false, true) +
                    walk_bsdf_sample_weight(ratio, p_bsdf, p_light, false, true) +
                    guided_light_sample_weight(a, b, p_light, p_bsdf, false, true) +
                    guided_bsdf_sample_weight(a, b, p_bsdf, p_light, false),
                1.0f, 1e-5f);
    // An emitter: the guided exit does not follow its BSDF sample there.
    EXPECT_NEAR(walk_light_sample_weight(ratio, p_light, p_bsdf, false, false) +
                    walk_bsdf_sample_weight(ratio, p_bsdf, p_light, false, false) +
                    guided_light_sample_weight(a, b, p_light, p_bsdf, false, false),
                1.0f, 1e-5f);
    // A delta light: only light samples.
    EXPECT_NEAR(walk_light_sample_weight(ratio, p_light, p_bsdf, true, true) +
                    guided_light_sample_weight(a, b, p_light, p_bsdf, true, true),
                1.0f, 1e-5f);
    // A smooth boundary: only BSDF samples, the guided exit's toward distant lights only.
    EXPECT_NEAR(walk_bsdf_sample_weight(ratio, 1.0f, p_light, true, true) +
                    guided_bsdf_sample_weight(a, b, 1.0f, p_light, true),
                1.0f, 1e-5f);
    EXPECT_EQ(walk_bsdf_sample_weight(ratio, 1.0f, p_light, true, false), 1.0f);
    // Without the guide: the path tracer's power heuristic.
    EXPECT_NEAR(walk_light_sample_weight(0.0f, p_light, p_bsdf, false, true),
                power_heuristic(p_light, p_bsdf), 1e-6f);
    EXPECT_NEAR(walk_bsdf_sample_weight(0.0f, p_bsdf, p_light, false, false),
                power_heuristic(p_bsdf, p_light), 1e-6f);
  }
}

}  // namespace
}  // namespace snee
