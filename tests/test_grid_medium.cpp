// The grid medium (kernels/physics/medium/grid_medium.h): the voxel walk's optical depth against
// an independent closed form, free flight as the exact inverse of it, the flight's distances
// against its pdf (chi-square), the pdf and transmittance consistent with each other, and a grid
// of constant density equal to the homogeneous medium.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kernels/physics/medium/grid_medium.h"
#include "tests/support/chi2.h"
#include "tests/support/separable_density.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using test::TestRng;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A separable grid (tests/support/separable_density.h) with random terms.
struct SeparableGrid {
  test::SeparableDensity density;
  DensityGrid grid;

  SeparableGrid(TestRng& rng, int nx, int ny, int nz, Vec3 lo, Vec3 hi) {
    const auto term = [&](double scale) { return std::floor(64 * scale * rng.uniform()) / 64; };
    for (int i = 0; i < nx; ++i) density.a.push_back(rng.uniform() < 0.3 ? 0.0 : term(1.5));
    for (int j = 0; j < ny; ++j) density.b.push_back(term(1.0));
    for (int k = 0; k < nz; ++k) density.c.push_back(term(0.5));
    density.lo = lo, density.hi = hi;
    grid = *density.grid();
  }

  double reference_depth(Vec3 x, Vec3 w, double t_max) const {
    return density.depth(x, w, 0, t_max);
  }
};

Vec3 random_direction(TestRng& rng) {
  const double z = 2 * rng.uniform() - 1, phi = 2 * M_PI * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
          static_cast<float>(z)};
}

Vec3 random_point(TestRng& rng, Vec3 lo, Vec3 hi) {
  const auto at = [&](float a, float b) { return a + (b - a) * static_cast<float>(rng.uniform()); };
  return {at(lo.x, hi.x), at(lo.y, hi.y), at(lo.z, hi.z)};
}

// Both sides are double sums of a few dozen terms from the same float inputs; what separates
// them is the placement of slab faces, a few ulp of the coordinates times the densities.
constexpr double kDepthTolerance = 1e-9;

TEST(GridMedium, OpticalDepthMatchesTheSlabSums) {
  TestRng rng(11);
  const SeparableGrid g(rng, 5, 4, 3, {-1, -0.5f, 0}, {1, 1.5f, 2});
  int inside = 0;
  for (int n = 0; n < 4000; ++n) {
    // Origins inside and around the box; axis-aligned directions now and then.
    const Vec3 x = random_point(rng, {-2, -1.5f, -1}, {2, 2.5f, 3});
    Vec3 w = random_direction(rng);
    if (n % 10 == 0) w = Vec3(0, 0, 0), w[n % 3] = n % 20 == 0 ? 1.0f : -1.0f;
    const double t_max = n % 7 == 0 ? kInf : 6 * rng.uniform();
    const double expected = g.reference_depth(x, w, t_max);
    inside += expected > 0;
    EXPECT_NEAR(optical_depth(g.grid, x, w, t_max), expected, kDepthTolerance * (1 + expected))
        << "ray " << n;
  }
  EXPECT_GT(inside, 1000);  // the rays do cross the grid
}

TEST(GridMedium, FlightDistanceInvertsTheOpticalDepth) {
  TestRng rng(12);
  const SeparableGrid g(rng, 6, 3, 5, {0, 0, 0}, {1, 2, 3});
  for (int n = 0; n < 2000; ++n) {
    const Vec3 x = random_point(rng, {0, 0, 0}, {1, 2, 3});
    const Vec3 w = random_direction(rng);
    const double total = optical_depth(g.grid, x, w, kInf);
    const double depth = 1.2 * total * rng.uniform();
    const double t = distance_to_depth(g.grid, x, w, depth);
    if (depth > total) {
      EXPECT_EQ(t, kInf) << "ray " << n;
    } else {
      ASSERT_TRUE(std::isfinite(t)) << "ray " << n;
      EXPECT_NEAR(optical_depth(g.grid, x, w, t), depth, kDepthTolerance * (1 + depth));
    }
  }
}

GridMedium chromatic_medium(const DensityGrid& grid) {
  return {&grid, {0.7f, 1.2f, 0.3f}, {1.0f, 2.0f, 0.5f}, 0.2f};
}

// The flight's density sum_c p_c sigma_c d(x_t) T_c(t), as the stages evaluate it.
double flight_pdf(const GridMedium& m, Vec3 x, Vec3 w, Rgb p, double t) {
  const float tf = static_cast<float>(t);
  return dot(p, m.channel_pdfs(x, w, tf, m.transmittance(x, w, tf)));
}

TEST(GridMedium, FlightsFollowTheirPdf) {
  TestRng rng(13);
  const SeparableGrid g(rng, 4, 4, 4, {-1, -1, -1}, {1, 1, 1});
  const GridMedium m = chromatic_medium(g.grid);
  const Rgb p(0.2f, 0.3f, 0.5f);
  for (const Vec3 w : {normalize(Vec3(0.3f, -0.5f, 0.8f)), Vec3(1, 0, 0)}) {
    const Vec3 x(-0.7f, 0.4f, -0.9f);
    const auto r = test::chi2_distance(
        [&]() -> std::optional<double> {
          const float u_channel = static_cast<float>(rng.uniform());
          return m.sample_distance(x, w, p, u_channel, static_cast<float>(rng.uniform()));
        },
        [&](double t) { return flight_pdf(m, x, w, p, t); }, {.scale = 0.5, .samples = 400'000});
    EXPECT_GT(r.p_value, 1e-4) << r.report;
    // What does not stop leaves the grid: the pdf's integral is one minus the survival.
    EXPECT_NEAR(r.integral, 1.0 - dot(p, m.transmittance(x, w, INFINITY)), 1e-4);
  }
}

TEST(GridMedium, PdfIntegratesToOneMinusTransmittance) {
  TestRng rng(14);
  const SeparableGrid g(rng, 3, 5, 4, {-1, -1, -1}, {1, 1, 1});
  const GridMedium m = chromatic_medium(g.grid);
  const Rgb p(0.5f, 0.25f, 0.25f);
  const Vec3 x(0.2f, -0.9f, 0.1f), w = normalize(Vec3(-0.2f, 1.0f, 0.3f));
  for (const double d : {0.3, 0.9, 1.7, 4.0}) {
    const double cdf =
        test::integrate_interval([&](double t) { return flight_pdf(m, x, w, p, t); }, 0, d);
    EXPECT_NEAR(cdf, 1.0 - dot(p, m.transmittance(x, w, static_cast<float>(d))), 1e-4) << d;
  }
}

TEST(GridMedium, ExtinctionStaysUnderTheMajorant) {
  TestRng rng(15);
  const SeparableGrid g(rng, 7, 2, 3, {-1, -1, -1}, {1, 1, 1});
  const GridMedium m = chromatic_medium(g.grid);
  for (int n = 0; n < 10000; ++n) {
    const Rgb e = m.extinction(random_point(rng, {-1.5f, -1.5f, -1.5f}, {1.5f, 1.5f, 1.5f}));
    for (int c = 0; c < 3; ++c) EXPECT_LE(e[c], m.majorant()[c]);
  }
}

TEST(GridMedium, ConstantDensityIsTheHomogeneousMedium) {
  DensityGrid grid;
  grid.nx = 3, grid.ny = 2, grid.nz = 4;
  grid.lo = {-10, -10, -10}, grid.hi = {10, 10, 10};
  grid.values.assign(24, 1.0f);
  grid.max_value = 1;
  const GridMedium m = chromatic_medium(grid);
  const HomogeneousMedium h{m.sigma_s, m.sigma_t, m.g};
  TestRng rng(16);
  const Rgb p(0.3f, 0.3f, 0.4f);
  for (int n = 0; n < 2000; ++n) {
    const Vec3 x = random_point(rng, {-1, -1, -1}, {1, 1, 1});
    const Vec3 w = random_direction(rng);
    const float t = static_cast<float>(3 * rng.uniform());
    const Rgb a = m.transmittance(x, w, t), b = h.transmittance(x, w, t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * b[c] + 1e-7f);
    const float u_channel = static_cast<float>(rng.uniform()),
                u = static_cast<float>(rng.uniform());
    const float ta = m.sample_distance(x, w, p, u_channel, u);
    const float tb = h.sample_distance(x, w, p, u_channel, u);
    if (tb < 5) {
      EXPECT_NEAR(ta, tb, 1e-5f * tb) << "flight " << n;
    }
    const Rgb pa = m.channel_pdfs(x, w, t, a), pb = h.channel_pdfs(x, w, t, b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(pa[c], pb[c], 1e-5f * pb[c] + 1e-7f);
  }
}

}  // namespace
}  // namespace snee
