// Whole renders in a grid medium (kernels/physics/medium/grid_medium.h): an absorbing grid
// against the closed-form transmittance of every camera ray, white furnaces through a null and a
// dielectric boundary, a constant grid against the homogeneous medium it equals, snee sampling
// like pt there, and bitwise determinism over threads, schedules and SIMD levels.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kernels/physics/camera.h"
#include "scene/camera_frame.h"
#include "scheduler/render.h"
#include "scheduler/simd_dispatch.h"
#include "tests/support/chi2.h"
#include "tests/support/render_helpers.h"
#include "tests/support/separable_density.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

// A 4 x 4 x 4 separable grid over [-1, 1]^3 (tests/support/separable_density.h).
test::SeparableDensity separable_density() {
  return {{0.0, 1.25, 0.375, 2.0},
          {0.25, 0.0, 0.875, 0.125},
          {0.625, 0.25, 0.0, 1.125},
          {-1, -1, -1},
          {1, 1, 1}};
}

Material material_of(MaterialKind kind, float ior = 1.5f, float roughness = 0.0f) {
  Material m;
  m.name = "boundary";
  m.kind = kind;
  m.ior = ior;
  m.roughness = roughness;
  return m;
}

Medium grid_medium(std::shared_ptr<const DensityGrid> density, Rgb sigma_s, Rgb sigma_a, float g) {
  return {"grid", sigma_s, sigma_a, g, std::move(density)};
}

void add_constant_environment(Scene& scene, float radiance) {
  Light env;
  env.kind = LightKind::kConstantEnv;
  env.radiance = Rgb(radiance);
  scene.lights.push_back(env);
}

// A pure absorber seen through an index-matched sphere under a white environment: each camera
// ray's expected value is its transmittance exp(-sigma_a tau) through the sphere's chord, so the
// image's mean is the mean of that over the camera's rays, which the test estimates from its own
// rays with the slab-sum depth. The render is unbiased only if the flight's survival probability
// is exactly the transmittance the voxel walk gives.
TEST(GridMediumRender, AbsorbingGridShowsTheClosedFormTransmittance) {
  // Sized to tell a flight whose optical depths are 5% off (about 10 standard errors).
  constexpr int kSize = 32;
  const test::SeparableDensity density = separable_density();
  const Rgb sigma_a(0.5f, 1.0f, 2.0f);
  Scene scene = test::sphere_scene(material_of(MaterialKind::kNull),
                                   grid_medium(density.grid(), Rgb(0.0f), sigma_a, 0), kSize);
  add_constant_environment(scene, 1.0f);
  RenderOptions options;
  options.spp = 256;
  options.seed = 3;
  const Film film = render(scene, options).film;
  const test::RegionStats rendered =
      test::region_mean(film, std::vector<bool>(film.mean.size(), true));

  const FilmCamera camera = film_camera(camera_frame(scene.camera), kSize, kSize);
  test::TestRng rng(4);
  constexpr int kRays = 1'000'000;
  double sum = 0, sum2 = 0;
  for (int n = 0; n < kRays; ++n) {
    const float px = static_cast<float>(rng.uniform() * static_cast<float>(kSize));
    const float py = static_cast<float>(rng.uniform() * static_cast<float>(kSize));
    const Vec3 w = camera_direction<float>(camera, std::floor(px), std::floor(py),
                                           px - std::floor(px), py - std::floor(py));
    const Vec3 o = camera.frame.origin;
    // The chord of the unit sphere.
    const double b = dot(o, w), c = dot(o, o) - 1.0, disc = b * b - c;
    double value = 1;
    if (disc > 0) {
      const double tau = density.depth(o, w, -b - std::sqrt(disc), -b + std::sqrt(disc));
      value =
          (std::exp(-sigma_a.x * tau) + std::exp(-sigma_a.y * tau) + std::exp(-sigma_a.z * tau)) /
          3.0;
    }
    sum += value;
    sum2 += value * value;
  }
  const double mean = sum / kRays;
  const double se = std::sqrt(std::max(0.0, sum2 / kRays - mean * mean) / kRays);
  EXPECT_LT(std::fabs(test::z_score(rendered.mean, rendered.standard_error, mean, se)), 4.0)
      << "rendered " << rendered.mean << " +- " << rendered.standard_error << ", expected " << mean
      << " +- " << se;
  EXPECT_LT(mean, 0.8);  // the grid absorbs a visible share
}

struct FurnaceCase {
  const char* name;
  MaterialKind boundary;
  float roughness;
  const char* integrator;
};

class GridFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// An albedo-1 grid under a white environment is invisible through any boundary that absorbs
// nothing (docs/method.md 5.5), however its density varies. (A rough dielectric does absorb:
// single-scattering GGX loses the light that bounces between microfacets.)
TEST_P(GridFurnace, RendersToOne) {
  const test::SeparableDensity density = separable_density();
  Scene scene = test::sphere_scene(material_of(GetParam().boundary, 1.4f, GetParam().roughness),
                                   grid_medium(density.grid(), Rgb(2.0f), Rgb(0.0f), 0.4f), 32);
  add_constant_environment(scene, 1.0f);
  RenderOptions options;
  options.spp = 32;
  options.seed = 9;
  options.integrator = GetParam().integrator;
  options.snee.light_limit_degrees = 180;  // SNEE engaged under any light (docs/method.md 3.11)
  test::expect_renders_to_one(render(scene, options).film);
}

INSTANTIATE_TEST_SUITE_P(
    Boundaries, GridFurnace,
    ::testing::Values(FurnaceCase{"null_pt", MaterialKind::kNull, 0, "pt"},
                      FurnaceCase{"null_sla", MaterialKind::kNull, 0, "sla"},
                      FurnaceCase{"smooth_dielectric_snee", MaterialKind::kDielectric, 0, "snee"},
                      FurnaceCase{"smooth_dielectric_pt", MaterialKind::kDielectric, 0, "pt"}),
    [](const auto& p) { return std::string(p.param.name); });

// The scene of the next tests: a grid of constant or varying density with absorption behind a
// rough dielectric, under a cone light and a dim environment.
Scene lit_grid_scene(std::shared_ptr<const DensityGrid> density, int resolution) {
  Scene scene = test::sphere_scene(
      material_of(MaterialKind::kDielectric, 1.5f, 0.1f),
      grid_medium(std::move(density), Rgb(3.0f, 2.0f, 1.5f), Rgb(0.05f, 0.1f, 0.2f), 0.3f),
      resolution);
  add_constant_environment(scene, 0.2f);
  Light cone;
  cone.kind = LightKind::kCone;
  cone.direction = normalize(Vec3(1, 1, 1));
  cone.half_angle = 0.3f;
  cone.radiance = Rgb(10.0f);
  scene.lights.push_back(cone);
  return scene;
}

// A grid of density 1 everywhere is the homogeneous medium with its coefficients: scattering,
// absorption, the phase function and light through the boundary agree within noise.
TEST(GridMediumRender, ConstantGridRendersAsTheHomogeneousMedium) {
  auto ones = std::make_shared<DensityGrid>();
  ones->nx = 2, ones->ny = 3, ones->nz = 2;
  ones->lo = {-1.5f, -1.5f, -1.5f}, ones->hi = {1.5f, 1.5f, 1.5f};
  ones->values.assign(12, 1.0f);
  ones->max_value = 1;
  const Scene grid = lit_grid_scene(ones, 32);
  Scene homogeneous = grid;
  homogeneous.media[0].density = nullptr;
  RenderOptions options;
  options.spp = 64;
  options.seed = 21;
  const Film a = render(grid, options).film;
  options.seed = 22;
  const Film b = render(homogeneous, options).film;
  EXPECT_GT(test::expect_same_region(a, b, test::sphere_mask(grid), 16, 16, "constant grid"), 0);
}

// SNEE's closed forms assume constant coefficients, so snee runs none of its strategies in a
// grid medium and weighs nothing against them: it is pt there, sample for sample.
TEST(GridMediumRender, SneeSamplesAGridLikePt) {
  const Scene scene = lit_grid_scene(separable_density().grid(), 24);
  RenderOptions options;
  options.spp = 16;
  options.seed = 5;
  const Film pt = render(scene, options).film;
  options.integrator = "snee";
  const RenderResult snee = render(scene, options);
  EXPECT_TRUE(test::bitwise_identical(pt, snee.film));
}

TEST(GridMediumRender, SameBitsForAnyThreadsScheduleAndSimdLevel) {
  const Scene scene = lit_grid_scene(separable_density().grid(), 24);
  RenderOptions options;
  options.spp = 8;
  options.seed = 6;
  options.threads = 1;
  const Film reference = render(scene, options).film;
  for (const char* schedule : {"megakernel", "local", "global"}) {
    for (const int threads : {1, 2}) {
      for (const SimdLevelStatus& level : simd_levels()) {
        if (!level.usable) continue;
        options.schedule = schedule;
        options.threads = threads;
        options.simd = level.level;
        options.queue_capacity = threads == 1 ? 64 : 256;
        EXPECT_TRUE(test::bitwise_identical(reference, render(scene, options).film))
            << schedule << ", " << threads << " threads, level " << static_cast<int>(level.level);
      }
    }
  }
}

}  // namespace
}  // namespace snee
