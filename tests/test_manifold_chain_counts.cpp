// What the manifold strategy's reflection chains behind a mesh leave out is counted, never
// silent (docs/method.md 3.14): under a directional light, the searches that draw more levels
// than the chain tree holds, and only within the depth limit; under a point light, every search
// a vertex draws. Without chains nothing is searched, so nothing is counted.
#include <gtest/gtest.h>

#include "kernels/physics/snee/manifold_mesh_chains.h"
#include "kernels/wavefront/snee_counters.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"

namespace snee {
namespace {

Scene small_bunny() {
  Scene scene = load_builtin_scene("bunny-directional-smooth").scene;
  scene.camera.width = scene.camera.height = 24;
  return scene;
}

struct Counts {
  uint64_t unsupported = 0, connected = 0;
};

Counts render_counts(const Scene& scene, int max_depth, bool chains) {
  RenderOptions options;
  options.integrator = "snee";
  options.spp = 16;
  options.seed = 3;
  options.max_depth = max_depth;
  options.snee.reflection_chains = chains;
  const RenderResult result = render(scene, options);
  const auto at = [&](SneeCounter c) { return result.stats.snee[static_cast<size_t>(c)]; };
  return {at(SneeCounter::kManifoldChainsUnsupported),
          at(SneeCounter::kManifoldReflectionConnections)};
}

TEST(ManifoldChainCounts, LevelsBeyondTheTreeAreCountedWithinTheDepthLimit) {
  const Scene scene = small_bunny();
  // Every depth: one search in 15 draws five levels or more.
  const Counts every_depth = render_counts(scene, 1024, true);
  EXPECT_GT(every_depth.connected, 0u);
  EXPECT_GT(every_depth.unsupported, 0u);
  EXPECT_LT(every_depth.unsupported, every_depth.connected);
  // A chain of m levels spends m depths and the exit one more: at depth 4 no vertex may search
  // beyond the tree's four levels.
  static_assert(kMaxMeshChainLevels == 4);
  const Counts shallow = render_counts(scene, 4, true);
  EXPECT_GT(shallow.connected, 0u);
  EXPECT_EQ(shallow.unsupported, 0u);
  const Counts off = render_counts(scene, 1024, false);
  EXPECT_EQ(off.connected + off.unsupported, 0u);
}

TEST(ManifoldChainCounts, PointLightSearchesAreCounted) {
  Scene scene = small_bunny();
  ASSERT_EQ(scene.lights.size(), 1u);
  Light& light = scene.lights[0];
  light.position = 4.0f * light.direction;
  light.intensity = 16.0f * light.irradiance;
  light.kind = LightKind::kPoint;
  const Counts point = render_counts(scene, 1024, true);
  EXPECT_EQ(point.connected, 0u);
  EXPECT_GT(point.unsupported, 0u);
  EXPECT_EQ(render_counts(scene, 1024, false).unsupported, 0u);
}

}  // namespace
}  // namespace snee
