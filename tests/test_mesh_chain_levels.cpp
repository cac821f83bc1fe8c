// The levels of the manifold strategy's reflection chains behind a mesh (docs/method.md 3.14):
// what they leave out is counted, never silent (under a directional light, the searches that
// draw more levels than the chain tree holds, and only within the depth limit; under a point
// light, every search a vertex draws; without chains nothing), and asking for more levels
// (`--snee-chain-levels`) only adds light: the same seed draws the same paths, and the longer
// chains are connected where the shorter tree counted them.
#include <gtest/gtest.h>

#include <algorithm>

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
  Film film;
};

Counts render_counts(const Scene& scene, int max_depth, bool chains,
                     int levels = kDefaultMeshChainLevels) {
  RenderOptions options;
  options.integrator = "snee";
  options.spp = 16;
  options.seed = 3;
  options.max_depth = max_depth;
  options.snee.reflection_chains = chains;
  options.snee.mesh_chain_levels = levels;
  RenderResult result = render(scene, options);
  const auto at = [&](SneeCounter c) { return result.stats.snee[static_cast<size_t>(c)]; };
  return {at(SneeCounter::kManifoldChainsUnsupported),
          at(SneeCounter::kManifoldReflectionConnections), std::move(result.film)};
}

double image_sum(const Film& film) {
  double sum = 0;
  for (const Rgb& p : film.mean) sum += p.x + p.y + p.z;
  return sum;
}

TEST(MeshChainLevels, LevelsBeyondTheTreeAreCountedWithinTheDepthLimit) {
  const Scene scene = small_bunny();
  // Every depth: one search in 15 draws five levels or more.
  const Counts every_depth = render_counts(scene, 1024, true);
  EXPECT_GT(every_depth.connected, 0u);
  EXPECT_GT(every_depth.unsupported, 0u);
  EXPECT_LT(every_depth.unsupported, every_depth.connected);
  // A chain of m levels spends m depths and the exit one more, and the first medium vertex is
  // at depth 2 (the camera ray's refraction in is the first): at depth 6 no vertex may search
  // beyond three levels, within the default four, while a two-level tree counts the third.
  static_assert(kDefaultMeshChainLevels == 4);
  const Counts shallow = render_counts(scene, 6, true);
  EXPECT_GT(shallow.connected, 0u);
  EXPECT_EQ(shallow.unsupported, 0u);
  EXPECT_GT(render_counts(scene, 6, true, 2).unsupported, 0u);
  const Counts off = render_counts(scene, 1024, false);
  EXPECT_EQ(off.connected + off.unsupported, 0u);
}

TEST(MeshChainLevels, MoreLevelsOnlyAddLight) {
  const Scene scene = small_bunny();
  const Counts four = render_counts(scene, 1024, true, 4);
  const Counts six = render_counts(scene, 1024, true, 6);
  // Searches the four-level tree counted are connected by the six-level one, the rest kept.
  EXPECT_LT(six.unsupported, four.unsupported);
  EXPECT_GT(six.connected, four.connected);
  ASSERT_EQ(four.film.mean.size(), six.film.mean.size());
  double most = 0, least_difference = 0;
  for (size_t i = 0; i < four.film.mean.size(); ++i) {
    const Rgb& a = four.film.mean[i];
    const Rgb& b = six.film.mean[i];
    most = std::max({most, double(a.x), double(a.y), double(a.z)});
    least_difference =
        std::min({least_difference, double(b.x - a.x), double(b.y - a.y), double(b.z - a.z)});
  }
  // Each pixel sums the same terms and, with six levels, a few more (all positive): nothing
  // but the sums' rounding may come out smaller.
  EXPECT_GE(least_difference, -1e-6 * most);
  EXPECT_GT(image_sum(six.film), image_sum(four.film));
}

TEST(MeshChainLevels, PointLightSearchesAreCounted) {
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
