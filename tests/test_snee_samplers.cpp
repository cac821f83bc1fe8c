// SNEE's samplers and densities (docs/method.md 5.1-5.3): sampling-time pdfs against the
// stand-alone pdf functions, normalisation, chi-square fits, and the MIS weights' partition of
// unity with exact zeros where a strategy cannot produce a path.
#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/snee/distance_samplers.h"
#include "kernels/physics/snee/joint_importance.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/snee_pdfs.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "tests/support/chi2.h"
#include "tests/support/snee_setups.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::ExitSetup;
using test::light_scene;
using test::random_setup;
using test::TestRng;
using test::uniforms;

// Sampling-time and stand-alone pdfs are computed along different routes (sampling variables
// vs. the produced float point); they agree to float rounding amplified by the pdf's
// sensitivity, well inside this bound for the configurations below (docs/method.md 5.1).
constexpr double kRoundTripTolerance = 1e-5;
// Adaptive quadrature of float-valued pdfs.
constexpr double kQuadratureTolerance = 1e-5;
constexpr double kChi2MinPValue = 1e-4;
constexpr double kMaxZ = 4;

double relative_error(double a, double b) {
  return std::fabs(a - b) / std::max(std::fabs(b), 1e-300);
}

Vec3 random_direction(TestRng& rng) {
  return sample_uniform_sphere(rng.uniform2());
}

Vec3 random_point(TestRng& rng, float extent) {
  return Vec3(extent * (2 * rng.uniform() - 1), extent * (2 * rng.uniform() - 1),
              extent * (2 * rng.uniform() - 1));
}

// A ray and a point whose closest approach h is at least 5% of their distance, so the
// equiangular density is well conditioned in float.
struct RayAndPoint {
  Vec3 o, w, c;
};
RayAndPoint random_ray_and_point(TestRng& rng) {
  for (;;) {
    const RayAndPoint r{random_point(rng, 1), random_direction(rng), random_point(rng, 1)};
    const Vec3 v = r.c - r.o;
    const float h = length(v - dot(v, r.w) * r.w);
    if (h > 0.05f * length(v)) return r;
  }
}

TEST(SneeDistance, EquiangularSamplePdfMatchesPdf) {
  TestRng rng(11);
  for (int config = 0; config < 200; ++config) {
    const RayAndPoint r = random_ray_and_point(rng);
    for (int k = 0; k < 500; ++k) {
      const DistanceSample s = equiangular_sample(r.o, r.w, r.c, rng.uniform());
      if (!s.valid) continue;
      ASSERT_LT(relative_error(s.pdf, equiangular_pdf(r.o, r.w, r.c, s.t)), kRoundTripTolerance);
    }
  }
}

TEST(SneeDistance, MixtureSamplePdfMatchesPdf) {
  TestRng rng(12);
  for (int config = 0; config < 200; ++config) {
    const RayAndPoint r = random_ray_and_point(rng);
    const DistanceMixture m{Rgb(0.5f + 3 * rng.uniform(), 0.5f + 3 * rng.uniform(), 1.0f),
                            rng.uniform(), r.o, r.w, r.c};
    for (int k = 0; k < 500; ++k) {
      const float u0 = rng.uniform(), u1 = rng.uniform();
      const DistanceSample s = distance_mixture_sample(m, u0, u1, rng.uniform());
      if (!s.valid) continue;
      ASSERT_LT(relative_error(s.pdf, distance_mixture_pdf(m, s.t)), kRoundTripTolerance);
    }
  }
}

TEST(SneeDistance, DensitiesIntegrateToOne) {
  const Vec3 o(0, 0, 0), w = normalize(Vec3(0.3f, -0.2f, -1.0f)), c(0.4f, 0.1f, -0.9f);
  const Rgb sigma_t(1.2f, 0.6f, 3.0f);
  const double scale = dot(c - o, w);
  const DistanceMixture m{sigma_t, 0.5f, o, w, c};
  const double exponential = test::integrate_interval(
      [&](double t) { return free_flight_pdf(sigma_t, float(t)); }, 0, INFINITY, 1);
  const double equiangular = test::integrate_interval(
      [&](double t) { return equiangular_pdf(o, w, c, float(t)); }, 0, INFINITY, scale);
  const double mixture = test::integrate_interval(
      [&](double t) { return distance_mixture_pdf(m, float(t)); }, 0, INFINITY, scale);
  EXPECT_NEAR(exponential, 1.0, kQuadratureTolerance);
  EXPECT_NEAR(equiangular, 1.0, kQuadratureTolerance);
  EXPECT_NEAR(mixture, 1.0, kQuadratureTolerance);
}

TEST(SneeDistance, EquiangularSamplesFollowPdf) {
  TestRng rng(13);
  // Point ahead of the origin, and behind it (the density then decreases monotonically).
  for (const Vec3 c : {Vec3(0.2f, 0.3f, 1.5f), Vec3(0.1f, 0.4f, -0.7f)}) {
    const Vec3 o(0, 0, 0), w(0, 0, 1);
    const auto r = test::chi2_distance(
        [&]() -> std::optional<double> {
          const DistanceSample s = equiangular_sample(o, w, c, rng.uniform());
          if (!s.valid) return std::nullopt;
          return s.t;
        },
        [&](double t) { return equiangular_pdf(o, w, c, float(t)); }, {.scale = 1.0});
    EXPECT_GT(r.p_value, kChi2MinPValue) << r.report;
  }
}

TEST(SneeDistance, MixtureSamplesFollowPdf) {
  TestRng rng(14);
  const DistanceMixture m{Rgb(0.8f, 2.0f, 5.0f), 0.5f, Vec3(0, 0, 0), Vec3(0, 0, 1),
                          Vec3(0.15f, 0.0f, 1.2f)};
  const auto r = test::chi2_distance(
      [&]() -> std::optional<double> {
        const float u0 = rng.uniform(), u1 = rng.uniform();
        const DistanceSample s = distance_mixture_sample(m, u0, u1, rng.uniform());
        if (!s.valid) return std::nullopt;
        return s.t;
      },
      [&](double t) { return distance_mixture_pdf(m, float(t)); }, {.scale = 1.0});
  EXPECT_GT(r.p_value, kChi2MinPValue) << r.report;
}

constexpr float kJointGs[] = {0.0f, 0.7f, -0.4f};

JointImportance random_joint_importance(TestRng& rng, float g) {
  const Vec3 x_i = random_point(rng, 1);
  return {x_i, random_direction(rng), x_i + (0.2f + rng.uniform()) * random_direction(rng), g,
          0.5f};
}

std::array<float, kJointImportanceDimensions> uniforms4(TestRng& rng) {
  std::array<float, kJointImportanceDimensions> u;
  for (float& x : u) x = rng.uniform();
  return u;
}

// The produced point is rounded to float, which moves it by up to ~1e-7 |x_j| (relative); the
// inverse squares of the densities turn that into a relative pdf change of about
// 2 * rounding / r for each of r_ij, r_jk, amplified further by direction-dependent factors
// (lobes, distance pdfs). The exact comparison is therefore made where that rounding bound is
// below 1e-6, an order of magnitude inside the tolerance, which keeps the great majority
// of samples; points closer to x_i or x_k are not representable more accurately in float.
// A microfacet lobe of roughness alpha amplifies a direction error by up to ~1/alpha more.
bool rounding_negligible(Vec3 x_j, Vec3 x_i, Vec3 x_k, double amplification = 1) {
  const float magnitude = std::max({std::fabs(x_j.x), std::fabs(x_j.y), std::fabs(x_j.z)});
  const double rounding = std::sqrt(3.0) * 0x1p-24 * magnitude;
  return amplification * rounding * (1 / length(x_j - x_i) + 1 / length(x_j - x_k)) < 1e-6;
}

TEST(SneeJointImportance, SamplePdfMatchesPdf) {
  TestRng rng(21);
  for (const float g : kJointGs) {
    int compared = 0;
    for (int config = 0; config < 200; ++config) {
      const JointImportance j = random_joint_importance(rng, g);
      for (int k = 0; k < 500; ++k) {
        const JointImportanceSample s = joint_importance_sample(j, uniforms4(rng));
        if (!s.valid || !rounding_negligible(s.x_j, j.x_i, j.x_k)) continue;
        ASSERT_LT(relative_error(s.pdf, joint_importance_pdf(j, s.x_j)), kRoundTripTolerance)
            << "g " << g;
        ++compared;
      }
    }
    EXPECT_GT(compared, 75000) << "g " << g;
  }
}

TEST(SneeJointImportance, IsotropicDensityIsClosedForm) {
  TestRng rng(22);
  for (int k = 0; k < 10000; ++k) {
    const JointImportance j = random_joint_importance(rng, 0.0f);
    const Vec3 x_j = random_point(rng, 2);
    const double d = length(j.x_k - j.x_i), r_ij = length(x_j - j.x_i), r_jk = length(x_j - j.x_k);
    const double closed = d / (M_PI * M_PI * M_PI * r_ij * r_ij * r_jk * r_jk);
    ASSERT_LT(relative_error(joint_importance_pdf(j, x_j), closed), kRoundTripTolerance);
  }
}

// E[1_B(x) / p(x)] = vol(B) for a box B: the density is normalised over R^3 and positive there.
TEST(SneeJointImportance, VolumeOfBox) {
  TestRng rng(23);
  const Vec3 lo(-0.5f, -0.5f, -0.8f), hi(0.5f, 0.5f, 0.0f);
  const double volume = 0.8;
  for (const float g : kJointGs) {
    const JointImportance j{Vec3(0, 0, -0.4f), normalize(Vec3(0.3f, 0.1f, 1.0f)),
                            Vec3(0.3f, 0.1f, 0.0f), g, 0.5f};
    test::MeanEstimator estimate;
    for (int k = 0; k < 2'000'000; ++k) {
      const JointImportanceSample s = joint_importance_sample(j, uniforms4(rng));
      const bool inside = s.valid && s.x_j.x > lo.x && s.x_j.y > lo.y && s.x_j.z > lo.z &&
                          s.x_j.x < hi.x && s.x_j.y < hi.y && s.x_j.z < hi.z;
      estimate.add(inside ? 1.0 / s.pdf : 0.0);
    }
    EXPECT_LT(test::z_score(estimate.mean(), estimate.standard_error(), volume, 0), kMaxZ)
        << "g " << g << ": " << estimate.mean() << " +- " << estimate.standard_error();
  }
}

// The light-favouring probe's targets for the tests: a distant light and a point light (whose
// lobe's axis depends on x_i), sharing the lobes unevenly, with the default uniform share.
SneeOptions light_favouring_probe() {
  SneeOptions options;
  options.probe = ProbeDirections::kTowardLights;
  ProbeTargets& targets = options.probe_targets;
  targets.count = 2;
  targets.target[0] = {normalize(Vec3(0.6f, -0.2f, 1.0f)), false, 0.7f};
  targets.target[1] = {Vec3(-1.5f, 0.8f, 0.9f), true, 0.3f};
  targets.uniform_share = kDefaultProbeUniformShare;
  return options;
}

// Each kind of probe, at the default rate and, for the uniform sphere, at every vertex.
std::vector<SneeOptions> every_probe() {
  SneeOptions uniform, everywhere, phase;
  everywhere.probe_rate = 1.0f;
  phase.probe = ProbeDirections::kPhaseFunction;
  return {uniform, everywhere, phase, light_favouring_probe()};
}

Vec3 probe_sample(const SneeOptions& options, Vec3 x_i, Vec3 omega_in, float g, TestRng& rng) {
  const Vec2 u = rng.uniform2();
  return probe_direction_sample(options, x_i, omega_in, g, Vec3(u.x, u.y, rng.uniform()));
}

// E[1_P(x_k) / p_probe(x_k)] = area(P) for a patch P of the plane z = 0 seen from below, the
// probe running at x_i with probability probe_rate, which its area density carries.
TEST(SneeProbe, AreaOfPatch) {
  TestRng rng(24);
  const Vec3 x_i(0, 0, -0.4f), n(0, 0, 1), omega_in = normalize(Vec3(0.5f, 0.0f, 1.0f));
  const double area = 1.0;  // [0, 1] x [-0.5, 0.5]
  for (const SneeOptions& options : every_probe()) {
    const float g = 0.6f;
    test::MeanEstimator estimate;
    for (int k = 0; k < 1'000'000; ++k) {
      const Vec3 w = probe_sample(options, x_i, omega_in, g, rng);
      if (!(rng.uniform() < options.probe_rate) || !(w.z > 0)) {
        estimate.add(0);
        continue;
      }
      const Vec3 x_k = x_i + (-x_i.z / w.z) * w;
      const bool inside = x_k.x > 0 && x_k.x < 1 && std::fabs(x_k.y) < 0.5f;
      estimate.add(inside ? 1.0 / probe_area_pdf(options, omega_in, g, x_i, x_k, n) : 0.0);
    }
    EXPECT_LT(test::z_score(estimate.mean(), estimate.standard_error(), area, 0), kMaxZ)
        << probe_directions_name(options.probe) << ": " << estimate.mean() << " +- "
        << estimate.standard_error();
  }
}

// The directions follow their density, which integrates to one (chi2.h), for each probe.
TEST(SneeProbe, DirectionsFollowTheirDensity) {
  const Vec3 x_i(0.2f, -0.1f, 0.3f), omega_in = normalize(Vec3(0.5f, 0.0f, 1.0f));
  const float g = 0.6f;
  for (const SneeOptions& options : every_probe()) {
    TestRng rng(25);
    const auto r = test::chi2_sphere(
        [&]() -> std::optional<Vec3> { return probe_sample(options, x_i, omega_in, g, rng); },
        [&](Vec3 w) { return double(probe_direction_pdf<float>(options, x_i, omega_in, g, w)); },
        {.axis = options.probe == ProbeDirections::kTowardLights
                     ? options.probe_targets.target[0].where
                     : omega_in});
    EXPECT_GT(r.p_value, kChi2MinPValue) << probe_directions_name(options.probe) << r.report;
    EXPECT_NEAR(r.integral, 1.0, 1e-3) << probe_directions_name(options.probe);
  }
}

// The light-favouring probe's point is what it buys: more exits whose side faces the light.
// From the centre of a ball, the light-favouring probe puts u / 2 + (1 - u) of its directions in
// the light's hemisphere (u the uniform share; the lobe never leaves it), against the uniform
// sphere's half.
TEST(SneeProbe, LightFavouringProbeFacesTheLight) {
  SneeOptions options = light_favouring_probe();
  options.probe_targets.count = 1;
  options.probe_targets.target[0].share = 1.0f;
  const Vec3 axis = options.probe_targets.target[0].where;
  const double u = options.probe_targets.uniform_share;
  const double expected = u * 0.5 + (1 - u);
  TestRng rng(26);
  test::MeanEstimator facing;
  for (int k = 0; k < 200'000; ++k) {
    facing.add(dot(probe_sample(options, Vec3(0.0f), Vec3(0, 0, 1), 0.0f, rng), axis) > 0 ? 1 : 0);
  }
  EXPECT_LT(test::z_score(facing.mean(), facing.standard_error(), expected, 0), kMaxZ)
      << facing.mean() << " +- " << facing.standard_error() << " vs " << expected;
}

// Targets come from the small lights only, by selection probability, at most kMaxProbeTargets.
TEST(SneeProbe, TargetsAreTheSmallLights) {
  Scene scene;
  Light sun;
  sun.kind = LightKind::kDirectional;
  sun.direction = normalize(Vec3(1, 1, 1));
  scene.lights.push_back(sun);
  Light sky;
  sky.kind = LightKind::kConstantEnv;
  scene.lights.push_back(sky);
  Light bulb;
  bulb.kind = LightKind::kPoint;
  bulb.position = Vec3(0, 3, 0);
  scene.lights.push_back(bulb);
  Light wide;
  wide.kind = LightKind::kCone;
  wide.direction = Vec3(0, 1, 0);
  wide.half_angle = 0.5f;  // 28.6 degrees: above the default limit
  scene.lights.push_back(wide);
  const LightTable lights(scene);
  const ProbeTargets targets = probe_targets_of(scene, lights, kDefaultLightLimitDegrees);
  ASSERT_EQ(targets.count, 2);
  EXPECT_EQ(targets.target[0].where, sun.direction);
  EXPECT_FALSE(targets.target[0].positional);
  EXPECT_EQ(targets.target[1].where, bulb.position);
  EXPECT_TRUE(targets.target[1].positional);
  EXPECT_FLOAT_EQ(targets.target[0].share + targets.target[1].share, 1.0f);
  EXPECT_EQ(targets.uniform_share, kDefaultProbeUniformShare);

  Scene sky_only;
  sky_only.lights.push_back(sky);
  const ProbeTargets none = probe_targets_of(sky_only, LightTable(sky_only), 180.0f);
  EXPECT_EQ(none.count, 0);
  EXPECT_EQ(none.uniform_share, 1.0f);
}

// --- strategies ------------------------------------------------------------------------------

const SneeMedium kMedium{Rgb(1.0f, 0.8f, 0.5f), Rgb(1.2f, 1.1f, 0.9f), 0.0f};

SneeSuffix suffix_of(const ExitSetup& setup, const SneeMedium& medium, const SneeCandidate& c,
                     const LightTable& lights, bool delta_light) {
  SneeSuffix s;
  s.x_i = setup.origin.x_i;
  s.omega_in = setup.origin.omega_in;
  s.x_j = c.x_j;
  s.x_k = setup.exit.x_k;
  s.n_k = setup.exit.n_k;
  s.ns_k = setup.exit.ns_k;
  s.omega_o = c.omega_o;
  s.medium = medium;
  s.interface = setup.exit.interface;
  s.light_pdf = delta_light ? 1.0f : lights.escaped_pdf(c.omega_o);  // one light: selection 1
  s.light_delta = delta_light;
  s.v_first = s.x_i_medium = s.x_j_medium = true;
  return s;
}

constexpr test::SneeCase kStrategyCases[] = {
    {"A rough+cone", {1.5f, 0.2f}, LightKind::kCone},
    {"B rough+directional", {1.5f, 0.2f}, LightKind::kDirectional},
    {"C smooth+cone", {1.5f, 0.0f}, LightKind::kCone},
    {"D smooth+directional", {1.5f, 0.0f}, LightKind::kDirectional},
};

// Like the joint-importance round trip, the float rounding of x_j limits the comparison near
// x_i and x_k.
bool well_separated(const ExitSetup& setup, Vec3 x_j) {
  const float alpha = setup.exit.interface.alpha;
  return rounding_negligible(x_j, setup.origin.x_i, setup.exit.x_k, alpha > 0 ? 1 / alpha : 1);
}

// On flat boundaries and on smooth-shaded ones (tilt: the shading normal leans from the
// geometric one by up to 0.4 rad, docs/method.md 4.9).
TEST(SneeStrategies, TopToBottomPdfMatchesPdf) {
  TestRng rng(31);
  const SneeOptions options;
  for (const float tilt : {0.0f, 0.4f})
    for (const test::SneeCase& sc : kStrategyCases) {
      const Scene scene = light_scene(sc.light);
      const LightTable lights(scene);
      int compared = 0;
      for (int k = 0; k < 100000; ++k) {
        const ExitSetup setup = random_setup(rng, sc.interface, 0.1f, 0.6f, tilt);
        const SneeCandidate c =
            sample_top_to_bottom(setup.origin, kMedium, setup.exit, lights, options, 1e-4f,
                                 uniforms<kTopToBottomDimensions>(rng));
        if (!c.valid || !well_separated(setup, c.x_j)) continue;
        const SneeSuffix s =
            suffix_of(setup, kMedium, c, lights, sc.light == LightKind::kDirectional);
        ASSERT_LT(relative_error(c.pdf, top_to_bottom_pdf(s, options)), kRoundTripTolerance)
            << sc.name << " tilt " << tilt;
        ++compared;
      }
      EXPECT_GT(compared, 10000) << sc.name << " tilt " << tilt;
    }
}

TEST(SneeStrategies, BottomToTopPdfMatchesPdf) {
  TestRng rng(32);
  for (const float tilt : {0.0f, 0.4f})
    for (const float g : {0.0f, 0.7f}) {
      SneeMedium medium = kMedium;
      medium.g = g;
      const SneeOptions options;
      for (const test::SneeCase& sc : kStrategyCases) {
        if (sc.light == LightKind::kDirectional) continue;  // BT never reaches a delta light
        const Scene scene = light_scene(sc.light);
        const LightTable lights(scene);
        int compared = 0;
        for (int k = 0; k < 500000; ++k) {
          const ExitSetup setup = random_setup(rng, sc.interface, 0.1f, 0.6f, tilt);
          const SneeCandidate c =
              sample_bottom_to_top(setup.origin, medium, setup.exit, lights, options, 1e-4f,
                                   uniforms<kBottomToTopDimensions>(rng));
          if (!c.valid || !well_separated(setup, c.x_j)) continue;
          const SneeSuffix s = suffix_of(setup, medium, c, lights, false);
          ASSERT_LT(relative_error(c.pdf, bottom_to_top_pdf(s, options)), kRoundTripTolerance)
              << sc.name << " g " << g << " tilt " << tilt;
          ++compared;
        }
        EXPECT_GT(compared, 1000) << sc.name << " g " << g << " tilt " << tilt;
      }
    }
}

// Case D on a smooth-shaded boundary (docs/method.md 3.7, 4.9). Top-to-bottom alone under a
// directional light works in the measure dA(x_k) dt, where its integrand carries
// cos_k_j / cos_k_j_shading (the volume at x_j by the geometric normal, the refraction about the
// shading normal); under a cone it works in dV(x_j) dA(x_k) with the refraction Jacobian about
// the shading normal. From the same x_i and x_k, its mean under a 0.5-degree cone of the same
// irradiance must be its mean under the directional light (they differ by O(theta^2), 1e-5 here),
// with the shading normal leaning up to 0.4 rad from the geometric one, and on a flat boundary.
TEST(SneeStrategies, TopToBottomUnderADirectionalLightIsTheLimitOfSmallCones) {
  TestRng rng(36);
  SneeOptions options;
  options.enabled = StrategySet::only(Strategy::kTopToBottom);
  const Scene directional_scene = light_scene(LightKind::kDirectional);
  Scene cone_scene = light_scene(LightKind::kCone);
  const float theta = 0.5f * kPi / 180.0f;
  cone_scene.lights[0].half_angle = theta;
  cone_scene.lights[0].radiance = Rgb(1.0f / (2.0f * kPi * (1.0f - std::cos(theta))));
  const LightTable directional(directional_scene), cone(cone_scene);
  for (int k = 0; k < 6; ++k) {
    const ExitSetup setup = random_setup(rng, {1.5f, 0.0f}, 0.1f, 0.6f, k == 0 ? 0.0f : 0.4f);
    double sum[2] = {0, 0}, sum2[2] = {0, 0};
    constexpr int kSamples = 100000;
    for (int light = 0; light < 2; ++light) {
      for (int n = 0; n < kSamples; ++n) {
        const SneeCandidate c =
            sample_top_to_bottom(setup.origin, kMedium, setup.exit, light == 0 ? directional : cone,
                                 options, 1e-4f, uniforms<kTopToBottomDimensions>(rng));
        const double x = c.valid ? c.contribution.y : 0.0;
        sum[light] += x;
        sum2[light] += x * x;
      }
    }
    double mean[2], error[2];
    for (int light = 0; light < 2; ++light) {
      mean[light] = sum[light] / kSamples;
      error[light] =
          std::sqrt(std::max(0.0, sum2[light] / kSamples - mean[light] * mean[light]) / kSamples);
    }
    ASSERT_GT(mean[0], 10 * error[0]) << "setup " << k << ": the light must reach x_i";
    EXPECT_LT(test::z_score(mean[0], error[0], mean[1], error[1]), 4.0)
        << "setup " << k << " (shading normal " << setup.exit.ns_k.x << ", " << setup.exit.ns_k.y
        << ", " << setup.exit.ns_k.z << "): directional " << mean[0] << " +- " << error[0]
        << ", cone " << mean[1] << " +- " << error[1];
  }
}

// The strategies report the balance-heuristic weight of the pdf functions, and a candidate's
// contribution divided by its weight is F / p.
TEST(SneeStrategies, CandidatesCarryTheSharedWeights) {
  TestRng rng(33);
  const SneeOptions options;
  const Scene scene = light_scene(LightKind::kCone);
  const LightTable lights(scene);
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const ExitSetup setup = random_setup(rng, {1.5f, 0.2f});
    for (const bool top : {true, false}) {
      const SneeCandidate c =
          top ? sample_top_to_bottom(setup.origin, kMedium, setup.exit, lights, options, 1e-4f,
                                     uniforms<kTopToBottomDimensions>(rng))
              : sample_bottom_to_top(setup.origin, kMedium, setup.exit, lights, options, 1e-4f,
                                     uniforms<kBottomToTopDimensions>(rng));
      if (!c.valid || !well_separated(setup, c.x_j)) continue;
      const SneeSuffix s = suffix_of(setup, kMedium, c, lights, false);
      const StrategyPdfs p = strategy_pdfs(s, options);
      const Strategy st = top ? Strategy::kTopToBottom : Strategy::kBottomToTop;
      ASSERT_LT(relative_error(c.weight, mis_weight(st, p, options)), kRoundTripTolerance);
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000);
}

// --- MIS weights -----------------------------------------------------------------------------

// A random suffix below the plane z = 0; for a smooth interface omega_o is the refraction of
// omega_kj, as every strategy produces it.
SneeSuffix random_suffix(TestRng& rng, DielectricParams interface, bool delta_light) {
  for (;;) {
    SneeSuffix s;
    s.x_i = Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, -rng.uniform());
    s.omega_in = random_direction(rng);
    s.x_j = Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, -rng.uniform());
    s.x_k = Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.0f);
    s.n_k = s.ns_k = Vec3(0, 0, 1);
    s.medium = {Rgb(0.8f), Rgb(0.5f + 2 * rng.uniform()), rng.uniform() - 0.5f};
    s.interface = interface;
    const Vec3 w_kj = normalize(s.x_j - s.x_k);
    if (interface.delta()) {
      if (!refract(w_kj, Vec3(0, 0, -1), interface.eta, &s.omega_o)) continue;
    } else {
      s.omega_o = sample_cosine_hemisphere(rng.uniform2());
    }
    s.light_pdf = delta_light ? 1.0f : 0.1f + 5 * rng.uniform();
    s.light_delta = delta_light;
    s.v_first = s.x_i_medium = s.x_j_medium = true;
    return s;
  }
}

constexpr Strategy kAll[] = {Strategy::kTopToBottom, Strategy::kBottomToTop,
                             Strategy::kUnidirectionalBsdf, Strategy::kUnidirectionalLight};

struct CaseExpectation {
  DielectricParams interface;
  bool delta_light;
  std::array<bool, kStrategyCount> possible;  // TB, BT, U_B, U_L
};
constexpr CaseExpectation kCases[] = {
    {{1.5f, 0.2f}, false, {true, true, true, true}},    // A
    {{1.5f, 0.2f}, true, {true, false, false, true}},   // B
    {{1.5f, 0.0f}, false, {true, true, true, false}},   // C
    {{1.5f, 0.0f}, true, {true, false, false, false}},  // D
};

TEST(SneeWeights, SumToOneOverPossibleStrategies) {
  TestRng rng(41);
  for (const MisHeuristic h : {MisHeuristic::kBalance, MisHeuristic::kPower}) {
    SneeOptions options;
    options.heuristic = h;
    for (const CaseExpectation& e : kCases) {
      int positive = 0;
      for (int k = 0; k < 20000; ++k) {
        const SneeSuffix s = random_suffix(rng, e.interface, e.delta_light);
        const StrategyPdfs p = strategy_pdfs(s, options);
        double sum = 0;
        for (const Strategy st : kAll) {
          const int i = static_cast<int>(st);
          if (!e.possible[i]) {
            ASSERT_EQ(p[st], 0.0);
          }
          const double w = mis_weight(st, p, options);
          ASSERT_GE(w, 0.0);
          if (p[st] == 0) {
            ASSERT_EQ(w, 0.0);
          }
          sum += w;
        }
        if (sum > 0) {
          ASSERT_NEAR(sum, 1.0, 1e-5);
          ++positive;
        }
      }
      EXPECT_GT(positive, 10000);
    }
  }
}

// A suffix SNEE cannot produce (occluded probe edge, or a surface vertex among x_i, x_j) has zero
// probe-based pdfs, and the tracer's two strategies keep their plain two-way weights.
TEST(SneeWeights, UnhandledSuffixesFallBackToTwoWay) {
  TestRng rng(42);
  const SneeOptions options;
  for (int variant = 0; variant < 3; ++variant) {
    for (int k = 0; k < 5000; ++k) {
      SneeSuffix s = random_suffix(rng, {1.5f, 0.2f}, false);
      if (variant == 0) s.v_first = false;
      if (variant == 1) s.x_i_medium = false;
      if (variant == 2) s.x_j_medium = false;
      ASSERT_EQ(top_to_bottom_pdf(s, options), 0.0);
      ASSERT_EQ(bottom_to_top_pdf(s, options), 0.0);
      const StrategyPdfs p = strategy_pdfs(s, options);
      ASSERT_FALSE(p.handled);
      const Frame frame = Frame::from_normal(s.n_k);
      const double p_bsdf = dielectric_pdf(s.interface, frame.to_local(normalize(s.x_j - s.x_k)),
                                           frame.to_local(s.omega_o));
      const double p_light = s.light_pdf;
      if (p_bsdf + p_light == 0) continue;
      ASSERT_NEAR(snee_exit_weight(Strategy::kUnidirectionalBsdf, s, options),
                  p_bsdf / (p_bsdf + p_light), 1e-6);
      ASSERT_NEAR(snee_exit_weight(Strategy::kUnidirectionalLight, s, options),
                  p_light / (p_bsdf + p_light), 1e-6);
      ASSERT_EQ(snee_exit_weight(Strategy::kTopToBottom, s, options), 0.0);
    }
  }
  // Delta cases without SNEE: the only possible exit strategy takes everything.
  SneeSuffix smooth = random_suffix(rng, {1.5f, 0.0f}, false);
  smooth.v_first = false;
  EXPECT_EQ(snee_exit_weight(Strategy::kUnidirectionalBsdf, smooth, options), 1.0);
  EXPECT_EQ(snee_exit_weight(Strategy::kUnidirectionalLight, smooth, options), 0.0);
  SneeSuffix delta_light = random_suffix(rng, {1.5f, 0.2f}, true);
  delta_light.x_j_medium = false;
  EXPECT_EQ(snee_exit_weight(Strategy::kUnidirectionalLight, delta_light, options), 1.0);
  EXPECT_EQ(snee_exit_weight(Strategy::kUnidirectionalBsdf, delta_light, options), 0.0);
}

// Strategy isolation: with one strategy enabled it takes the whole handled suffix.
TEST(SneeWeights, IsolatedStrategyTakesEverything) {
  TestRng rng(43);
  for (const Strategy only : kAll) {
    SneeOptions options;
    options.enabled = StrategySet::only(only);
    for (int k = 0; k < 2000; ++k) {
      const SneeSuffix s = random_suffix(rng, {1.5f, 0.2f}, false);
      const StrategyPdfs p = strategy_pdfs(s, options);
      for (const Strategy st : kAll) {
        const double expected = (st == only && p[st] > 0) ? 1.0 : 0.0;
        ASSERT_EQ(mis_weight(st, p, options), expected);
      }
    }
  }
}

// A vertex on the point it connects to makes a 1/r^2 density infinite (seen once in 9.4 M
// paths of a smooth sphere under a directional light, where inf / inf made the sample NaN):
// the weights take their limit, shared among the infinite densities, and still sum to 1.
TEST(SneeMisWeights, InfiniteDensitiesTakeTheLimit) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const MisHeuristic heuristic : {MisHeuristic::kBalance, MisHeuristic::kPower}) {
    SneeOptions options;
    options.heuristic = heuristic;
    StrategyPdfs p;
    p.pdf = {0.5, 2.0, 1.0, inf, 0.0};  // walk-based strategies compete on unhandled suffixes
    EXPECT_EQ(mis_weight(Strategy::kUnidirectionalLight, p, options), 1.0);
    EXPECT_EQ(mis_weight(Strategy::kUnidirectionalBsdf, p, options), 0.0);
    p.pdf = {0.5, 2.0, inf, inf, 0.0};
    EXPECT_EQ(mis_weight(Strategy::kUnidirectionalLight, p, options), 0.5);
    EXPECT_EQ(mis_weight(Strategy::kUnidirectionalBsdf, p, options), 0.5);
  }
}

}  // namespace
}  // namespace snee
