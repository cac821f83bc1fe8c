// Several translucent objects with different media in one scene: a jade, a milk and a wax
// sphere side by side, each in a cell of black walls so that no light passes between them, render
// in the three-sphere scene as each renders alone (region means agree within their standard
// errors, with independent seeds), for pt and snee. The media differ enough that a swapped or
// shared medium would show.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

using nlohmann::json;

constexpr int kWidth = 96;
constexpr int kHeight = 32;
constexpr float kRadius = 0.5f;
constexpr float kSpacing = 1.3f;  // between sphere centres along x
const char* const kMedia[] = {"jade", "milk", "wax"};

// The walls are planes x = +-kSpacing / 2 from far behind the spheres to just above their tops
// (z = kWallTop > kRadius), so every segment between two spheres meets one (both ends lie below
// kWallTop), while the camera, far up the z axis, looks over them.
constexpr float kWallTop = 0.55f;
constexpr float kWallSize = 20.0f;

json wall(float x) {
  return {{"type", "quad"},
          {"size", kWallSize},
          {"material", {{"type", "diffuse"}, {"albedo", 0.0}}},
          {"transform", json::array({{{"rotate", {{"axis", {0, 0, 1}}, {"degrees", 90}}}},
                                     {{"translate", {x, 0, kWallTop - 0.5f * kWallSize}}}})}};
}

// The spheres listed in `present` (indices into kMedia), always with both walls.
json spheres_scene(const std::vector<int>& present) {
  json shapes = json::array({wall(-0.5f * kSpacing), wall(0.5f * kSpacing)});
  for (const int i : present) {
    shapes.push_back({{"type", "sphere"},
                      {"name", kMedia[i]},
                      {"center", {(i - 1) * kSpacing, 0, 0}},
                      {"radius", kRadius},
                      {"material", "boundary"},
                      {"medium", kMedia[i]}});
  }
  return {
      {"camera",
       {{"position", {0, 0, 10}},
        {"look_at", {0, 0, 0}},
        {"fov", 14},
        {"resolution", {kWidth, kHeight}}}},
      {"materials",
       json::array(
           {{{"name", "boundary"}, {"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.2}}})},
      {"media",
       json::array(
           {{{"name", "jade"}, {"sigma_s", {8, 9.5, 8.5}}, {"sigma_a", {8, 2, 5}}, {"g", 0.2}},
            {{"name", "milk"}, {"sigma_s", {20, 22, 25}}, {"sigma_a", 0.01}},
            {{"name", "wax"}, {"sigma_s", {6, 5, 4}}, {"sigma_a", {0.05, 0.3, 1}}, {"g", 0.5}}})},
      {"shapes", shapes},
      {"lights",
       json::array({{{"type", "directional"}, {"direction", {0.2, 0.8, 1}}, {"irradiance", 2}},
                    {{"type", "constant"}, {"radiance", 0.3}}})}};
}

Film render_spheres(const Scene& scene, const char* integrator, uint64_t seed) {
  RenderOptions options;
  options.spp = 256;
  options.seed = seed;
  options.integrator = integrator;
  return render(scene, options).film;
}

TEST(SeveralMedia, EachObjectRendersAsItDoesAlone) {
  const Scene together = load_scene_json(spheres_scene({0, 1, 2}), "together", ".").scene;
  for (const char* integrator : {"pt", "snee"}) {
    const Film all = render_spheres(together, integrator, 1);
    std::vector<test::RegionStats> alone_means;
    for (int i = 0; i < 3; ++i) {
      SCOPED_TRACE(std::string(integrator) + " " + kMedia[i]);
      const Scene alone = load_scene_json(spheres_scene({i}), "alone", ".").scene;
      const std::vector<bool> mask =
          test::sphere_mask(together, {(i - 1) * kSpacing, 0, 0}, kRadius);
      const test::RegionStats in_all = test::region_mean(all, mask);
      const test::RegionStats by_itself =
          test::region_mean(render_spheres(alone, integrator, 2 + i), mask);
      ASSERT_GT(in_all.pixels, 60);
      const double z = (in_all.mean - by_itself.mean) /
                       std::hypot(in_all.standard_error, by_itself.standard_error);
      EXPECT_LT(std::fabs(z), 4.0)
          << "together " << in_all.mean << " +- " << in_all.standard_error << ", alone "
          << by_itself.mean << " +- " << by_itself.standard_error;
      std::printf("%s %s: together %.4f +- %.4f, alone %.4f +- %.4f (z %.2f)\n", integrator,
                  kMedia[i], in_all.mean, in_all.standard_error, by_itself.mean,
                  by_itself.standard_error, z);
      alone_means.push_back(by_itself);
    }
    // The test can tell the media apart: a swapped or shared medium would fail it.
    for (int i = 0; i < 3; ++i) {
      const test::RegionStats& a = alone_means[i];
      const test::RegionStats& b = alone_means[(i + 1) % 3];
      EXPECT_GT(std::fabs(a.mean - b.mean), 6 * std::hypot(a.standard_error, b.standard_error))
          << integrator << ": " << kMedia[i] << " and " << kMedia[(i + 1) % 3] << " look alike";
    }
  }
}

}  // namespace
}  // namespace snee
