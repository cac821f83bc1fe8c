// SNEE through smooth-shaded boundaries (docs/method.md 4.9): the exit point's shading normal is
// the interface's frame, its geometric normal converts areas and decides the sides. On a coarse
// icosphere (shading normals up to 21 degrees off its triangles), under a cone light where the
// path tracer converges, `snee` must render what `pt` renders, with a rough and with a smooth
// boundary, and its probe strategies must actually run there (before, such a boundary was left
// to the path tracer). Tolerances come from the films' measured standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/render.h"
#include "tests/support/icosphere.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

// The grid's medium inside a level-1 smooth-shaded icosphere of `roughness`, lit by a cone of
// half-angle 8 degrees (irradiance 3) from the upper left.
Scene coarse_icosphere(float roughness) {
  Material boundary;
  boundary.kind = MaterialKind::kDielectric;
  boundary.ior = 1.5f;
  boundary.roughness = roughness;
  const Medium medium{"grid-medium", {4.0f, 5.0f, 6.0f}, {0.12f, 0.1f, 0.08f}, 0.0f, nullptr};
  Scene scene = test::sphere_scene(boundary, medium, 32);
  Shape& shape = scene.shapes[0];
  shape.kind = ShapeKind::kMesh;
  shape.mesh = test::icosphere(1, true);
  shape.smooth_shading = true;
  shape.closed = true;
  const float theta = 8.0f * kPi / 180.0f;
  Light cone;
  cone.kind = LightKind::kCone;
  cone.direction = normalize(Vec3(-1.0f, 1.0f, 0.6f));
  cone.half_angle = theta;
  cone.radiance = Rgb(3.0f / (2.0f * kPi * (1.0f - std::cos(theta))));
  scene.lights = {cone};
  return scene;
}

RenderResult render_with(const Scene& scene, const char* integrator, int spp, uint32_t seed) {
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  options.integrator = integrator;
  options.snee.light_limit_degrees = 180;  // SNEE under the 8-degree cone too (method.md 3.11)
  return render(scene, options);
}

uint64_t counter(const RenderResult& r, SneeCounter c) {
  return r.stats.snee[static_cast<size_t>(c)];
}

// The object as a whole, and its 8x8 blocks (at least half inside it) where both converged.
void expect_same_object(const Film& pt, const Film& snee, const std::vector<bool>& object,
                        const std::string& what) {
  const test::RegionStats a = test::region_mean(pt, object), b = test::region_mean(snee, object);
  std::printf("%s: pt %.5f +- %.5f, snee %.5f +- %.5f\n", what.c_str(), a.mean, a.standard_error,
              b.mean, b.standard_error);
  ASSERT_GT(b.mean, 20 * b.standard_error) << what << ": a dark object proves nothing";
  EXPECT_GE(test::expect_same_region(pt, snee, object, 8, 32, what), 4) << what;
}

struct BoundaryCase {
  const char* name;
  float roughness;
  int pt_spp, snee_spp;
};

class SneeThroughSmoothShading : public ::testing::TestWithParam<BoundaryCase> {};

TEST_P(SneeThroughSmoothShading, MatchesThePathTracer) {
  const BoundaryCase& c = GetParam();
  const Scene scene = coarse_icosphere(c.roughness);
  const RenderResult pt = render_with(scene, "pt", c.pt_spp, 601);
  const RenderResult snee = render_with(scene, "snee", c.snee_spp, 602);
  // The probe takes the boundary's exit points (none is refused for its shading) and both
  // subdivision strategies connect through them (bottom-to-top rarely: its outward direction
  // must find the small light).
  const uint64_t probes = counter(snee, SneeCounter::kProbes);
  ASSERT_GT(probes, 10000u);
  EXPECT_LT(counter(snee, SneeCounter::kProbeOtherSurface), probes / 100);
  EXPECT_GT(counter(snee, SneeCounter::kTopToBottomConnections), probes / 10);
  EXPECT_GT(counter(snee, SneeCounter::kBottomToTopConnections), 0u);
  EXPECT_EQ(snee.stats.nonfinite_samples, 0u);
  expect_same_object(pt.film, snee.film, test::sphere_mask(scene, {0, 0, 0}, 0.8f), c.name);
}

INSTANTIATE_TEST_SUITE_P(CoarseIcosphere, SneeThroughSmoothShading,
                         ::testing::Values(BoundaryCase{"rough", 0.2f, 1024, 256},
                                           BoundaryCase{"smooth", 0.0f, 4096, 512}),
                         [](const auto& test_case) { return std::string(test_case.param.name); });

}  // namespace
}  // namespace snee
