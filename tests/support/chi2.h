// Chi-square goodness-of-fit tests for samplers, and the quadrature they use.
//
// A sampler is a callable that draws one sample (capturing its own seeded RNG) and returns
// std::nullopt when it fails (e.g. total internal reflection). Its pdf is a separate callable.
// The test bins N draws, computes each bin's expected count by adaptive Simpson quadrature of
// the pdf, and adds one "failure" cell with probability 1 - integral of the pdf, so a pdf that
// integrates to the success probability passes and a mis-normalised one fails. Cells with
// expected count below min_expected are pooled (smallest first) before Pearson's statistic is
// compared to the chi-square distribution with (cells - 1) degrees of freedom.
//
// Typical use:
//   TestRng rng(7);
//   const auto r = chi2_sphere(
//       [&]() -> std::optional<Vec3> { return sample_something(rng.uniform2()); },
//       [&](Vec3 w) { return pdf_something(w); }, {.axis = peak_direction});
//   EXPECT_GT(r.p_value, 1e-4) << r.report;
//
// The quadrature only refines where it sees variation at its initial nodes (a quarter cell
// apart), so a narrow lobe must sit at the axis. To test a sampler with several narrow lobes,
// test one lobe at a time: the sampler returns std::nullopt for samples in the other lobes and
// the pdf returns 0 there; those samples then count as failures, which is exact.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>

#include "kernels/physics/sampling.h"

namespace snee::test {

// Seeded uniform numbers in [0, 1) with 24 bits, like the renderer's (kernels/physics/rng.h);
// std::uniform_real_distribution<float> may round up to 1.
class TestRng {
 public:
  explicit TestRng(uint64_t seed) : engine_(seed) {}
  float uniform() { return static_cast<float>(engine_() >> 40) * 0x1p-24f; }
  Vec2 uniform2() {
    const float x = uniform();
    return {x, uniform()};
  }

 private:
  std::mt19937_64 engine_;
};

struct Chi2Result {
  double statistic = 0;
  int dof = 0;
  double p_value = 0;           // 0 also when a sample was malformed (NaN, not unit, < 0)
  double integral = 0;          // quadrature of the pdf over the whole domain
  double success_fraction = 0;  // fraction of draws that produced a (finite) sample
  std::string report;           // human-readable summary, for failure messages
};

// Directions on the unit sphere. Bins are uniform in (cos theta, phi) about `axis`, covering
// cos theta in [cos_min, 1]; when cos_min > -1 the rest of the sphere is one extra cell, which
// lets narrow lobes (small GGX alpha, small cones) be resolved by choosing cos_min near 1.
struct SphereChi2Options {
  Vec3 axis{0, 0, 1};
  double cos_min = -1;
  int cos_bins = 20;
  int phi_bins = 40;
  int64_t samples = 1'000'000;
  double min_expected = 5;
};
Chi2Result chi2_sphere(const std::function<std::optional<Vec3>()>& sample,
                       const std::function<double(Vec3)>& pdf, const SphereChi2Options& options);

// Distances on [0, inf). Bins are uniform in y = t / (t + scale); pick scale near the typical
// distance. A returned +inf counts as a failure (no finite distance), like std::nullopt.
struct DistanceChi2Options {
  double scale = 1;
  int bins = 100;
  int64_t samples = 1'000'000;
  double min_expected = 5;
};
Chi2Result chi2_distance(const std::function<std::optional<double>()>& sample,
                         const std::function<double(double)>& pdf,
                         const DistanceChi2Options& options);

// Integral of f over the unit sphere (solid angle) by nested adaptive Simpson quadrature on
// the same (cos theta, phi) cells as chi2_sphere; put `axis` at the peak of narrow integrands.
double integrate_sphere(const std::function<double(Vec3)>& f, Vec3 axis = Vec3(0, 0, 1),
                        int cos_bins = 20, int phi_bins = 40);

// Integral of f over [a, b] by adaptive Simpson quadrature; b may be +inf (then the integral is
// taken in y = t / (t + scale)).
double integrate_interval(const std::function<double(double)>& f, double a, double b,
                          double scale = 1);

}  // namespace snee::test
