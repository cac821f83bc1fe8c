// White furnace (docs/method.md 5.5): an albedo-1 medium inside a smooth dielectric under a
// uniform environment of radiance 1 is invisible, for any index of refraction. Holds for the
// sphere and the bunny, with a dielectric and an index-matched boundary, and for every
// unbiased integrator. (Surfaces that absorb nothing: tests/test_material_render.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

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

// The closed bunny's thin ear: ray origins offset by a fixed 1e-4 of the scene (not by the
// hit's float error), from hit points with the error of the whole ray's length, crossed it
// wrongly in 10 of these 4.2M paths (2.3 per million); now 2.
TEST(FurnaceCrossing, BunnyPathsCrossItsSurfaceTheRightWay) {
  Scene scene = load_builtin_scene("furnace-bunny").scene;
  RenderOptions options;
  options.spp = 1024;
  options.seed = 7;
  const Film film = render(scene, options).film;
  EXPECT_LE(wrong_samples(film, options.spp), 3);
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
