// White furnace (docs/method.md 5.5): an albedo-1 medium inside a smooth dielectric under a
// uniform environment of radiance 1 is invisible, for any index of refraction. Holds for the
// sphere and the bunny, with a dielectric and an index-matched boundary, and for every
// unbiased integrator. (Surfaces that absorb nothing: tests/test_material_render.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "scene/embree_scene.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_size.h"

namespace snee {
namespace {

struct FurnaceCase {
  const char* scene;
  const char* integrator;
};

class Furnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(Furnace, ObjectRendersToOne) {
  Scene scene = load_builtin_scene(GetParam().scene).scene;
  scene.camera.width = scene.camera.height = 32;
  RenderOptions options;
  options.spp = 32;
  options.seed = 7;
  options.integrator = GetParam().integrator;
  options.snee.light_limit_degrees = 180;  // SNEE under any light (docs/method.md 3.11)
  test::expect_renders_to_one(render(scene, options).film);
}

std::string case_name(const ::testing::TestParamInfo<FurnaceCase>& p) {
  std::string name = std::string(p.param.scene) + "_" + p.param.integrator;
  for (char& c : name) c = (c == '-') ? '_' : c;
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Furnace,
                         ::testing::Values(FurnaceCase{"furnace-sphere", "pt"},
                                           FurnaceCase{"furnace-bunny", "pt"},
                                           FurnaceCase{"furnace-sphere-null", "pt"},
                                           FurnaceCase{"furnace-sphere", "snee"},
                                           FurnaceCase{"furnace-bunny", "snee"},
                                           FurnaceCase{"furnace-sphere-null", "snee"}),
                         case_name);

// Samples of a zero-variance furnace render (every path that leaves the object brings exactly
// 1) that came out otherwise: a path that crossed a surface the wrong way loses its sample (0)
// or gains the eta^2 of an unmatched exit. Counted per pixel from the deviation of its mean.
int64_t wrong_samples(const Film& film, int spp) {
  int64_t wrong = 0;
  for (const Rgb& m : film.mean)
    wrong += std::llround(std::fabs((m.x + m.y + m.z) / 3.0 - 1.0) * spp);
  return wrong;
}

// The largest deviation of any pixel's channel from 1: issue 10 asks for the closed furnace to
// be exact to 1e-6 in every pixel, a bound a single wrong sample in 4096 (2.4e-4) far exceeds
// and the float rounding of a mean of ones (~1e-7) stays under.
double largest_deviation(const Film& film) {
  double largest = 0;
  for (const Rgb& m : film.mean) {
    for (const float c : {m.x, m.y, m.z}) largest = std::max(largest, std::fabs(c - 1.0));
  }
  return largest;
}

// The closed bunny's thin ear: ray origins offset by a fixed 1e-4 of the scene (not by the
// hit's float error), from hit points with the error of the whole ray's length, crossed it
// wrongly in 10 of these 4.2M paths (2.3 per million); then 2 (rays through a shared edge that
// Embree's default, not watertight, triangle test missed on both sides), now none.
TEST(FurnaceCrossing, BunnyPathsCrossItsSurfaceTheRightWay) {
  Scene scene = load_builtin_scene("furnace-bunny").scene;
  RenderOptions options;
  options.spp = test::sanitized_share(1024);
  options.seed = 7;
  const Film film = render(scene, options).film;
  EXPECT_EQ(wrong_samples(film, options.spp), 0);
  EXPECT_LT(largest_deviation(film), 1e-6);
}

// Rays that graze a silhouette edge of the bunny, where they enter and leave within float
// error of one point: Embree reported the far (exit) face as the closest hit, and the path left
// an object it had never entered (eta^2 = 2.25 too much): 3 of these 16.8M paths, with the
// watertight triangle test. Such a hit is now no crossing (shade_surface.cpp).
TEST(FurnaceCrossing, BunnyGrazingRaysDoNotExitWithoutEntering) {
  Scene scene = load_builtin_scene("furnace-bunny").scene;
  RenderOptions options;
  options.spp = test::sanitized_share(4096);
  options.seed = 1;
  const Film film = render(scene, options).film;
  EXPECT_EQ(wrong_samples(film, options.spp), 0);
  EXPECT_LT(largest_deviation(film), 1e-6);
}

// Rays found by that render (seed 7, pixels (42, 39) and (24, 27) at 4096 spp) that pass within
// about an ulp of the edge two of the bunny's triangles share: Embree's default triangle test
// missed both triangles, so the camera ray first hit the bunny's far side from inside (t 6.466
// on triangle 2406) and the ray from inside left the bunny without a hit (t = inf). The
// watertight test (RTC_SCENE_FLAG_ROBUST) finds one of the two.
TEST(FurnaceCrossing, RaysThroughASharedEdgeHitIt) {
  const Scene scene = load_builtin_scene("furnace-bunny").scene;
  const EmbreeScene embree(scene);
  struct Case {
    Vec3 origin, direction;
    uint32_t prim_a, prim_b;  // the triangles on either side of the edge
    float t;                  // where the ray crosses the edge (in double)
  };
  const Case cases[] = {{scene.camera.position,
                         {0.0899156332f, -0.251419514f, -0.963692665f},
                         1066,
                         1106,
                         6.0923030f},
                        {{-0.527013242f, 0.184527099f, -0.0704361647f},
                         {0.0308112949f, -0.281487584f, 0.959070027f},
                         3371,
                         3406,
                         0.52842858f}};
  for (const Case& c : cases) {
    float t = 0;
    uint32_t geom = 0, prim = 0;
    ASSERT_TRUE(embree.intersect1(c.origin, c.direction, 0.0f, kInfinity, &t, &geom, &prim));
    EXPECT_TRUE(prim == c.prim_a || prim == c.prim_b) << "prim " << prim << " at t " << t;
    EXPECT_NEAR(t, c.t, 1e-5f);
  }
}

// sigma_s = 1e6 (mean free path 1e-6, ten ulps of the coordinates): scattering points within
// float error of the boundary lost the medium (the next ray missed the boundary behind its
// origin), and entering paths started a fixed 1e-4 = 100 free paths deep; 0.995 before. A
// sphere of radius 1e-3 keeps the walks short enough to finish (about (R sigma)^2 = 1e6
// events at most), so no path meets the depth limit, while at (1, 0, 0) its coordinates are
// as coarse as a unit object's.
TEST(FurnaceCrossing, DenseMediumFurnaceIsExact) {
  const nlohmann::json doc = {
      {"camera",
       {{"position", {1.0, 1.2e-3, 6.2e-3}},
        {"look_at", {1.0, 0.0, 0.0}},
        {"fov", 30.0},
        {"resolution", {16, 16}}}},
      {"shapes",
       {{{"type", "sphere"},
         {"center", {1.0, 0.0, 0.0}},
         {"radius", 1e-3},
         {"material", {{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.0}}},
         {"medium", {{"sigma_s", 1e6}, {"sigma_a", 0.0}, {"g", 0.0}}}}}},
      {"lights", {{{"type", "constant"}, {"radiance", 1.0}}}}};
  const Scene scene = load_scene_json(doc, "dense furnace", ".").scene;
  RenderOptions options;
  options.spp = 4;
  options.seed = 1;
  options.max_depth = 100'000'000;
  const Film film = render(scene, options).film;
  const std::vector<bool> all(film.mean.size(), true);
  EXPECT_NEAR(test::region_mean(film, all).mean, 1.0, 1e-4);
  EXPECT_EQ(wrong_samples(film, options.spp), 0);
}

}  // namespace
}  // namespace snee
