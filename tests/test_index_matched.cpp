// An index-matched (eta = 1) dielectric boundary and a null boundary bound the same medium and
// must give the same image in expectation (docs/method.md 5.6): the first is a delta interface
// that pt can only cross by BSDF sampling, the second is invisible, so lights are reached by
// straight NEE from medium vertices. Agreement checks free flight, spectral MIS, NEE through
// boundaries with transmittance tracking, and the MIS between phase sampling and lights.
#include <gtest/gtest.h>

#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"
#include "tests/support/test_size.h"

namespace snee {
namespace {

Scene lit_sphere(MaterialKind boundary) {
  Material m;
  m.name = "boundary";
  m.kind = boundary;
  m.ior = 1.0f;
  Medium medium;
  medium.name = "milk";
  medium.sigma_s = {2.0f, 3.0f, 4.0f};
  medium.sigma_a = {0.2f, 0.1f, 0.05f};
  medium.g = 0.3f;
  Scene scene = test::sphere_scene(m, medium, 24);
  Light cone;
  cone.kind = LightKind::kCone;
  cone.direction = normalize(Vec3(0.4f, 1.0f, 0.5f));
  cone.half_angle = 0.2f;
  cone.radiance = Rgb(20.0f);
  scene.lights.push_back(cone);
  Light env;
  env.kind = LightKind::kConstantEnv;
  env.radiance = Rgb(0.3f, 0.4f, 0.5f);
  scene.lights.push_back(env);
  return scene;
}

// The sphere's pixels within 4 combined standard errors, each 8x8 block of them within 5.
void expect_sphere_images_agree(const Scene& scene, const Film& a, const Film& b) {
  const std::vector<bool> mask = test::sphere_mask(scene);
  const test::RegionStats ra = test::region_mean(a, mask), rb = test::region_mean(b, mask);
  ASSERT_GT(ra.pixels, 100);
  EXPECT_GT(ra.mean, 0.05);
  EXPECT_LT(test::z_score(ra.mean, ra.standard_error, rb.mean, rb.standard_error), 4.0)
      << ra.mean << " +- " << ra.standard_error << " vs " << rb.mean << " +- " << rb.standard_error;
  for (const auto& block : test::blocks(a, mask, 8, 24)) {
    const test::RegionStats ba = test::region_mean(a, block), bb = test::region_mean(b, block);
    EXPECT_LT(test::z_score(ba.mean, ba.standard_error, bb.mean, bb.standard_error), 5.0)
        << ba.mean << " vs " << bb.mean;
  }
}

TEST(IndexMatched, NullBoundaryEqualsEtaOneDielectric) {
  RenderOptions options;
  options.spp = test::sanitized_share(256);
  options.seed = 11;
  const Scene with_surface = lit_sphere(MaterialKind::kDielectric);
  const Scene null_boundary = lit_sphere(MaterialKind::kNull);
  const Film a = render(with_surface, options).film;
  const Film b = render(null_boundary, options).film;
  expect_sphere_images_agree(with_surface, a, b);
}

// docs/method.md 5.6: behind an index-matched dielectric, SNEE's refraction is the identity and
// its connections are ordinary volumetric NEE, so snee on the eta = 1 boundary must equal pt's
// straight NEE through an invisible boundary. The lights are the cone and the environment
// (case C): with a directional light (case D) single scattering is produced by neither pt nor
// SNEE behind a delta interface (docs/method.md 3.8), so the images would rightly differ by it.
TEST(IndexMatched, SneeThroughEtaOneEqualsStraightNee) {
  RenderOptions options;
  options.spp = test::sanitized_share(256);
  const Scene with_surface = lit_sphere(MaterialKind::kDielectric);
  const Scene null_boundary = lit_sphere(MaterialKind::kNull);
  options.integrator = "snee";
  options.seed = 12;
  const Film a = render(with_surface, options).film;
  options.integrator = "pt";
  options.seed = 13;
  const Film b = render(null_boundary, options).film;
  expect_sphere_images_agree(with_surface, a, b);
}

}  // namespace
}  // namespace snee
