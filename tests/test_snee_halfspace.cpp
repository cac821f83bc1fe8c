// SNEE in the analytic half-space (docs/method.md 5.9-5.10, 5.4, 5.7): medium z < 0 below the
// plane z = 0 (outward normal +z), x_i = (0, 0, -0.4), isotropic phase, sigma_s = 1,
// sigma_a = 0.2, eta = 1.5, light axis normalize(0.5, 0.2, 1), cone half-angle 0.3 rad with
// radiance 1, or a directional light of irradiance 1. Visibility is analytic: a segment is clear
// iff it stays in z <= 0, light rays always escape, and the probe ray from x_i hits the plane iff
// it points up. Every strategy estimates I(x_i) of docs/method.md 1.3 alone, and the four-way MIS
// combination must agree with them, with the reference table of 5.10, and (smooth cases) with a
// deterministic quadrature of the case-D integral.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/light_extent.h"
#include "kernels/physics/snee/probe.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"
#include "tests/support/test_size.h"

namespace snee {
namespace {

using test::MeanEstimator;
using test::TestRng;

constexpr double kMaxZ = 4;
constexpr float kDepth = 0.4f;  // of x_i below the plane
constexpr float kSigmaS = 1.0f, kSigmaT = 1.2f, kEta = 1.5f;
constexpr float kConeHalfAngle = 0.3f;
constexpr float kEpsilon = 1e-4f;
const Vec3 kLightAxis = normalize(Vec3(0.5f, 0.2f, 1.0f));
const Vec3 kUp(0, 0, 1);

Scene cone_scene(float half_angle, float radiance) {
  Scene scene;
  Light light;
  light.kind = LightKind::kCone;
  light.direction = kLightAxis;
  light.half_angle = half_angle;
  light.radiance = Rgb(radiance);
  scene.lights.push_back(light);
  return scene;
}

Scene directional_scene() {
  Scene scene;
  Light light;
  light.kind = LightKind::kDirectional;
  light.direction = kLightAxis;
  light.irradiance = Rgb(1.0f);
  scene.lights.push_back(light);
  return scene;
}

// Per-sample estimates of I(x_i): each strategy alone (weight 1, i.e. its contribution divided
// by its MIS weight) and their four-way MIS sum.
struct Estimators {
  MeanEstimator top_to_bottom, bottom_to_top, unidirectional_bsdf, unidirectional_light, mis;
};

class HalfSpace {
 public:
  HalfSpace(DielectricParams interface, const Scene& scene,
            ProbeDirections probe = ProbeDirections::kUniformSphere, float probe_rate = 1.0f)
      : interface_(interface), lights_(scene) {
    options_.probe = probe;
    options_.probe_rate = probe_rate;
    options_.probe_targets = probe_targets_of(scene, lights_, kWholeSkyDegrees);
  }

  Estimators run(int64_t samples, uint64_t seed) const {
    TestRng rng(seed);
    Estimators e;
    for (int64_t n = 0; n < samples; ++n) {
      Sample s;
      subdivide(rng, &s);
      walk(rng, &s);
      e.top_to_bottom.add(s.tb);
      e.bottom_to_top.add(s.bt);
      e.unidirectional_bsdf.add(s.ub);
      e.unidirectional_light.add(s.ul);
      e.mis.add(s.mis);
    }
    return e;
  }

 private:
  struct Sample {
    double tb = 0, bt = 0, ub = 0, ul = 0, mis = 0;
  };

  static bool clear(const SneeCandidate& c) {
    // Segments 0 and 1 run inside the medium; segment 2 goes to a distant light, which nothing
    // blocks in this scene.
    for (int i = 0; i < 2; ++i) {
      const ShadowSegment& seg = c.segments[i];
      const Vec3 end = seg.origin + seg.t_max * seg.direction;
      if (seg.origin.z > 0 || end.z > 0) return false;
    }
    return true;
  }

  template <int N>
  static std::array<float, N> uniforms(TestRng& rng) {
    std::array<float, N> u;
    for (float& x : u) x = rng.uniform();
    return u;
  }

  SneeSuffix suffix(Vec3 x_j, Vec3 x_k, Vec3 omega_o) const {
    SneeSuffix s;
    s.x_i = x_i_;
    s.omega_in = omega_in_;
    s.x_j = x_j;
    s.x_k = x_k;
    s.n_k = s.ns_k = kUp;
    s.omega_o = omega_o;
    s.medium = medium_;
    s.interface = interface_;
    s.v_first = s.x_i_medium = s.x_j_medium = true;
    return s;
  }

  // Probe from x_i, then both subdivision strategies.
  void subdivide(TestRng& rng, Sample* s) const {
    // The lobe's number only where a lobe is drawn, so the other probes draw what they did.
    const Vec2 u = rng.uniform2();
    const float u_lobe = options_.probe == ProbeDirections::kTowardLights ? rng.uniform() : 0.0f;
    const Vec3 w =
        probe_direction_sample(options_, x_i_, omega_in_, medium_.g, Vec3(u.x, u.y, u_lobe));
    const auto u_tb = uniforms<kTopToBottomDimensions>(rng);
    const auto u_bt = uniforms<kBottomToTopDimensions>(rng);
    // The probe runs at x_i with probability probe_rate (drawn only below 1, so the tests at
    // rate 1 draw what they did).
    if (options_.probe_rate < 1.0f && !(rng.uniform() < options_.probe_rate)) return;
    if (!(w.z > 0)) return;
    Vec3 x_k = x_i_ + (kDepth / w.z) * w;
    x_k.z = 0;
    const ExitPoint exit{x_k, kUp, kUp, interface_};
    const SneeOrigin origin{x_i_, omega_in_};
    const SneeCandidate tb =
        sample_top_to_bottom(origin, medium_, exit, lights_, options_, kEpsilon, u_tb);
    if (tb.valid && clear(tb)) {
      s->mis += average(tb.contribution);
      s->tb += average(tb.contribution) / tb.weight;
    }
    const SneeCandidate bt =
        sample_bottom_to_top(origin, medium_, exit, lights_, options_, kEpsilon, u_bt);
    if (bt.valid && clear(bt)) {
      s->mis += average(bt.contribution);
      s->bt += average(bt.contribution) / bt.weight;
    }
  }

  // The tracer's random walk x_i -> x_j -> x_k with its two exit events, weighted as the
  // renderer weights them. The throughput follows the tracer's spectral-MIS free flights.
  void walk(TestRng& rng, Sample* s) const {
    float phase_pdf;
    const Vec3 w1 = hg_sample(omega_in_, medium_.g, rng.uniform2(), &phase_pdf);
    const float c1 = rng.uniform();
    const float t1 = free_flight_sample(medium_.sigma_t, c1, rng.uniform());
    const Vec3 w2 = hg_sample(w1, medium_.g, rng.uniform2(), &phase_pdf);
    const float c2 = rng.uniform();
    const float t2 = free_flight_sample(medium_.sigma_t, c2, rng.uniform());
    const float u_select = rng.uniform();
    const Vec2 u_light = rng.uniform2();
    const float u_lobe = rng.uniform();
    const Vec2 u_bsdf = rng.uniform2();

    if (w1.z > 0 && t1 >= kDepth / w1.z) return;  // reaches the surface first: another class
    const Vec3 x_j = x_i_ + t1 * w1;
    if (!(w2.z > 0)) return;  // never reaches the surface without scattering again
    const float boundary = -x_j.z / w2.z;
    if (t2 < boundary) return;  // scatters again: another class
    Vec3 x_k = x_j + boundary * w2;
    x_k.z = 0;
    const Rgb beta = medium_.sigma_s * transmittance(medium_.sigma_t, t1) /
                     free_flight_pdf(medium_.sigma_t, t1) *
                     transmittance(medium_.sigma_t, boundary) /
                     free_flight_survival(medium_.sigma_t, boundary);
    const Frame frame = Frame::from_normal(kUp);
    const Vec3 local_kj = frame.to_local(-w2);

    // U_L: light sample at x_k (impossible through a smooth interface).
    if (!interface_.delta()) {
      const LightSample light = lights_.sample(x_k, u_select, u_light);
      const float cos_o = dot(kUp, light.wi);
      if (light.valid && cos_o > 0) {
        const float f = dielectric_eval(interface_, local_kj, frame.to_local(light.wi));
        const double value = average(beta * light.radiance) * f * cos_o / light.pdf;
        SneeSuffix sx = suffix(x_j, x_k, light.wi);
        sx.light_pdf = light.pdf;
        sx.light_delta = light.delta;
        s->ul += value;
        s->mis += value * snee_exit_weight(Strategy::kUnidirectionalLight, sx, options_);
      }
    }
    // U_B: the tracer's BSDF sample at x_k; transmission escaping to the (non-delta) light.
    const BsdfSample b = dielectric_sample(interface_, local_kj, u_bsdf, u_lobe);
    if (b.valid && b.transmission) {
      const Vec3 omega_o = frame.to_world(b.wi);
      const Rgb emitted = lights_.escaped_radiance(omega_o);
      if (!is_black(emitted)) {
        const double value = average(beta * emitted) * b.f * std::fabs(b.wi.z) / b.pdf;
        SneeSuffix sx = suffix(x_j, x_k, omega_o);
        sx.light_pdf = lights_.escaped_pdf(omega_o);
        sx.light_delta = false;
        s->ub += value;
        s->mis += value * snee_exit_weight(Strategy::kUnidirectionalBsdf, sx, options_);
      }
    }
  }

  DielectricParams interface_;
  LightTable lights_;
  SneeOptions options_;
  SneeMedium medium_{Rgb(kSigmaS), Rgb(kSigmaT), 0.0f};
  Vec3 x_i_{0, 0, -kDepth};
  Vec3 omega_in_ = normalize(Vec3(0.3f, -0.1f, 1.0f));
};

// I(x_i) for a smooth interface lit by a directional light from direction w_l (irradiance 1),
// by quadrature (docs/method.md Appendix B): with x_j = x_k + t w_r (w_r the refracted light
// direction, cos_r = -w_r.z) the reduced case-D integral over dA(x_k) dt becomes a volume
// integral dV(x_j) / cos_r of exp(-sigma_t r_ij) / r_ij^2 exp(-sigma_t |z_j| / cos_r); in
// spherical coordinates around x_i it depends only on mu = cos(polar angle), and the radial
// integral is closed-form.
double case_d_reference(Vec3 w_l) {
  const double cos_l = w_l.z;
  const double sin_r = std::sqrt(std::max(0.0, 1 - cos_l * cos_l)) / kEta;
  const double cos_r = std::sqrt(1 - sin_r * sin_r);
  const double fresnel = fresnel_dielectric(static_cast<float>(cos_l), kEta);
  const double phase = 1 / (4 * M_PI);
  const double sigma_t = kSigmaT, depth = kDepth;
  const double constant = phase * phase * kSigmaS * (1 - fresnel) * cos_l;
  // mu < 0: the half-line stays in the medium; integral of exp(-k r) over [0, inf) is 1 / k.
  const double downward = cos_r / sigma_t * std::log(1 + 1 / cos_r);
  // mu > 0: the half-line leaves the medium at r = depth / mu.
  const double upward = test::integrate_interval(
      [&](double mu) {
        if (mu <= 0) return 1 / sigma_t;
        const double k = sigma_t * (1 - mu / cos_r), r_max = depth / mu;
        return k == 0 ? r_max : -std::expm1(-k * r_max) / k;
      },
      0, 1);
  return constant * 2 * M_PI / cos_r * std::exp(-sigma_t * depth / cos_r) * (downward + upward);
}

// The cone light of radiance L through a smooth interface: the case-D result integrated over
// the cone's directions.
double case_c_reference(float half_angle, double radiance) {
  const Frame frame = Frame::from_normal(kLightAxis);
  const double integral = test::integrate_interval(
      [&](double theta) {
        return std::sin(theta) *
               test::integrate_interval(
                   [&](double phi) {
                     const Vec3 w = frame.to_world(spherical_direction(
                         float(std::sin(theta)), float(std::cos(theta)), float(phi)));
                     return case_d_reference(w);
                   },
                   0, 2 * M_PI);
      },
      0, half_angle);
  return radiance * integral;
}

struct Reference {
  double mean, standard_error;
};

std::string describe(const char* what, const MeanEstimator& e, Reference r) {
  return std::string(what) + ": " + std::to_string(e.mean()) + " +- " +
         std::to_string(e.standard_error()) + " vs " + std::to_string(r.mean) + " +- " +
         std::to_string(r.standard_error);
}

void expect_agrees(const char* what, const MeanEstimator& e, Reference r) {
  EXPECT_LT(test::z_score(e.mean(), e.standard_error(), r.mean, r.standard_error), kMaxZ)
      << describe(what, e, r);
}

Reference of(const MeanEstimator& e) {
  return {e.mean(), e.standard_error()};
}

// Strategy isolation (docs/method.md 5.4): every strategy that can produce the case estimates the
// same integral as the combination.
void expect_isolation(const Estimators& e, bool tb, bool bt, bool ub, bool ul) {
  if (tb) expect_agrees("TB alone vs MIS", e.top_to_bottom, of(e.mis));
  if (bt) expect_agrees("BT alone vs MIS", e.bottom_to_top, of(e.mis));
  if (ub) expect_agrees("U_B alone vs MIS", e.unidirectional_bsdf, of(e.mis));
  if (ul) expect_agrees("U_L alone vs MIS", e.unidirectional_light, of(e.mis));
}

void print(const char* name, const Estimators& e) {
  const auto line = [](const char* what, const MeanEstimator& m) {
    std::printf("    %-5s %.4e +- %.1e\n", what, m.mean(), m.standard_error());
  };
  std::printf("  %s\n", name);
  line("TB", e.top_to_bottom);
  line("BT", e.bottom_to_top);
  line("U_B", e.unidirectional_bsdf);
  line("U_L", e.unidirectional_light);
  line("MIS", e.mis);
}

// Sample counts: enough that the MIS estimate's standard error is below 0.3% of the mean, so
// that a 2% bias fails against references at least as precise (an eighth in the sanitized
// build, test_size.h).
constexpr int64_t kSamples = test::sanitized_share<int64_t>(6'000'000);

TEST(SneeHalfSpace, CaseARough02Cone) {
  const Scene scene = cone_scene(kConeHalfAngle, 1.0f);
  const Estimators e = HalfSpace({kEta, 0.2f}, scene).run(kSamples, 101);
  print("A alpha=0.2 cone", e);
  expect_agrees("U_B", e.unidirectional_bsdf, {7.255e-3, 1.0e-4});
  expect_agrees("U_L", e.unidirectional_light, {7.229e-3, 1.4e-4});
  expect_agrees("TB", e.top_to_bottom, {7.257e-3, 3.9e-5});
  expect_agrees("BT", e.bottom_to_top, {7.334e-3, 9.7e-5});
  expect_agrees("MIS", e.mis, {7.267e-3, 1.7e-5});
  expect_isolation(e, true, true, true, true);
}

TEST(SneeHalfSpace, CaseARough004Cone) {
  const Scene scene = cone_scene(kConeHalfAngle, 1.0f);
  const Estimators e = HalfSpace({kEta, 0.04f}, scene).run(kSamples, 102);
  print("A alpha=0.04 cone", e);
  expect_agrees("U_B", e.unidirectional_bsdf, {7.323e-3, 9.4e-5});
  expect_agrees("U_L", e.unidirectional_light, {7.010e-3, 7.1e-4});
  expect_agrees("TB", e.top_to_bottom, {7.298e-3, 9.9e-5});
  expect_agrees("BT", e.bottom_to_top, {7.242e-3, 8.9e-5});
  expect_agrees("MIS", e.mis, {7.238e-3, 1.8e-5});
  expect_isolation(e, true, true, true, true);
}

TEST(SneeHalfSpace, CaseBRough02Directional) {
  const Scene scene = directional_scene();
  const Estimators e = HalfSpace({kEta, 0.2f}, scene).run(kSamples, 103);
  print("B alpha=0.2 directional", e);
  expect_agrees("U_L", e.unidirectional_light, {2.567e-2, 7.9e-4});
  expect_agrees("TB", e.top_to_bottom, {2.625e-2, 1.8e-4});
  expect_agrees("MIS", e.mis, {2.634e-2, 1.3e-4});
  EXPECT_EQ(e.bottom_to_top.mean(), 0.0);
  EXPECT_EQ(e.unidirectional_bsdf.mean(), 0.0);
  expect_isolation(e, true, false, false, true);
}

TEST(SneeHalfSpace, CaseCSmoothCone) {
  const Scene scene = cone_scene(kConeHalfAngle, 1.0f);
  const Estimators e = HalfSpace({kEta, 0.0f}, scene).run(kSamples, 104);
  print("C smooth cone", e);
  const Reference quadrature{case_c_reference(kConeHalfAngle, 1.0), 0};
  std::printf("    quadrature %.5e\n", quadrature.mean);
  for (const Reference r : {Reference{7.228e-3, 2.9e-5}, Reference{7.207e-3, 2.3e-5}, quadrature}) {
    expect_agrees("TB", e.top_to_bottom, r);
  }
  for (const Reference r : {Reference{7.219e-3, 7.7e-5}, Reference{7.087e-3, 7.6e-5}, quadrature}) {
    expect_agrees("BT", e.bottom_to_top, r);
  }
  for (const Reference r : {Reference{7.239e-3, 8.1e-5}, Reference{7.310e-3, 8.1e-5}, quadrature}) {
    expect_agrees("U_B", e.unidirectional_bsdf, r);
  }
  for (const Reference r : {Reference{7.218e-3, 1.5e-5}, Reference{7.243e-3, 1.5e-5}, quadrature}) {
    expect_agrees("MIS", e.mis, r);
  }
  EXPECT_EQ(e.unidirectional_light.mean(), 0.0);
  expect_isolation(e, true, true, true, false);
}

TEST(SneeHalfSpace, CaseDSmoothDirectional) {
  const Scene scene = directional_scene();
  const Estimators e = HalfSpace({kEta, 0.0f}, scene).run(kSamples, 105);
  print("D smooth directional", e);
  const Reference quadrature{case_d_reference(kLightAxis), 0};
  std::printf("    quadrature %.5e\n", quadrature.mean);
  for (const Reference r : {Reference{2.630e-2, 1.9e-4}, Reference{2.637e-2, 1.0e-4}, quadrature}) {
    expect_agrees("TB", e.top_to_bottom, r);
  }
  // Only TB can produce delta-delta paths, so it carries weight 1.
  EXPECT_EQ(e.mis.mean(), e.top_to_bottom.mean());
  EXPECT_EQ(e.bottom_to_top.mean(), 0.0);
  EXPECT_EQ(e.unidirectional_bsdf.mean(), 0.0);
  EXPECT_EQ(e.unidirectional_light.mean(), 0.0);
}

// The light-favouring probe (docs/method.md 3.2) changes only which exit points the subdivision
// strategies start from: every strategy alone and the combination still estimate the same
// I(x_i), against the uniform probe's reference (CaseARough004Cone) and the quadrature.
TEST(SneeHalfSpace, LightFavouringProbeCaseARough004Cone) {
  const Scene scene = cone_scene(kConeHalfAngle, 1.0f);
  const Estimators e =
      HalfSpace({kEta, 0.04f}, scene, ProbeDirections::kTowardLights).run(kSamples, 108);
  print("A alpha=0.04 cone, light-favouring probe", e);
  expect_agrees("TB", e.top_to_bottom, {7.298e-3, 9.9e-5});
  expect_agrees("BT", e.bottom_to_top, {7.242e-3, 8.9e-5});
  expect_agrees("MIS", e.mis, {7.238e-3, 1.8e-5});
  expect_isolation(e, true, true, true, true);
}

TEST(SneeHalfSpace, LightFavouringProbeCaseDSmoothDirectional) {
  const Scene scene = directional_scene();
  const Estimators e =
      HalfSpace({kEta, 0.0f}, scene, ProbeDirections::kTowardLights).run(kSamples, 109);
  print("D smooth directional, light-favouring probe", e);
  const Reference quadrature{case_d_reference(kLightAxis), 0};
  std::printf("    quadrature %.5e\n", quadrature.mean);
  expect_agrees("TB", e.top_to_bottom, quadrature);
  EXPECT_EQ(e.mis.mean(), e.top_to_bottom.mean());
}

// The probe at a quarter of the vertices (SneeOptions::probe_rate, docs/method.md 3.2): the
// subdivision strategies' densities carry the rate, so each alone and the combination still
// estimate I(x_i).
TEST(SneeHalfSpace, ProbeRateCaseARough004Cone) {
  const Scene scene = cone_scene(kConeHalfAngle, 1.0f);
  const Estimators e =
      HalfSpace({kEta, 0.04f}, scene, ProbeDirections::kUniformSphere, 0.25f).run(kSamples, 110);
  print("A alpha=0.04 cone, probe rate 1/4", e);
  expect_agrees("TB", e.top_to_bottom, {7.298e-3, 9.9e-5});
  expect_agrees("BT", e.bottom_to_top, {7.242e-3, 8.9e-5});
  expect_agrees("MIS", e.mis, {7.238e-3, 1.8e-5});
  expect_isolation(e, true, true, true, true);
}

TEST(SneeHalfSpace, ProbeRateCaseDSmoothDirectional) {
  const Scene scene = directional_scene();
  const Estimators e =
      HalfSpace({kEta, 0.0f}, scene, ProbeDirections::kUniformSphere, 0.25f).run(kSamples, 111);
  print("D smooth directional, probe rate 1/4", e);
  const Reference quadrature{case_d_reference(kLightAxis), 0};
  expect_agrees("TB", e.top_to_bottom, quadrature);
  EXPECT_EQ(e.mis.mean(), e.top_to_bottom.mean());
}

// Limits (docs/method.md 5.7): a nearly smooth rough interface under the directional light
// approaches case D. U_L is not compared here: at alpha = 0.01 it is heavy-tailed and its
// sample standard error is not trustworthy at this sample count (docs/method.md 5.10).
TEST(SneeHalfSpace, RoughToSmoothLimit) {
  const Scene scene = directional_scene();
  const Estimators e = HalfSpace({kEta, 0.01f}, scene).run(kSamples, 106);
  print("B alpha=0.01 directional", e);
  const Reference quadrature{case_d_reference(kLightAxis), 0};
  for (const Reference r : {Reference{2.599e-2, 1.2e-4}, Reference{2.638e-2, 1.2e-4}, quadrature}) {
    expect_agrees("MIS", e.mis, r);
  }
  for (const Reference r : {Reference{2.596e-2, 1.2e-4}, Reference{2.638e-2, 1.3e-4}, quadrature}) {
    expect_agrees("TB", e.top_to_bottom, r);
  }
}

// A small cone of radiance E / solid angle approaches the directional light of irradiance E.
TEST(SneeHalfSpace, ConeToDirectionalLimit) {
  const float half_angle = 0.01f;
  const double solid_angle = 2 * M_PI * (1 - std::cos(double(half_angle)));
  const Scene scene = cone_scene(half_angle, float(1 / solid_angle));
  const Estimators e = HalfSpace({kEta, 0.0f}, scene).run(kSamples, 107);
  print("C smooth small cone", e);
  expect_agrees("MIS", e.mis, {case_d_reference(kLightAxis), 0});
  expect_agrees("MIS vs cone quadrature", e.mis,
                {case_c_reference(half_angle, 1 / solid_angle), 0});
  expect_isolation(e, true, false, false, false);
}

}  // namespace
}  // namespace snee
