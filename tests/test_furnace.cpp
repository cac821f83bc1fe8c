// White furnace (docs/snee.md 5.5): an albedo-1 medium inside a smooth dielectric under a
// uniform environment of radiance 1 is invisible, for any index of refraction. Holds for the
// sphere and the bunny, with a dielectric and an index-matched boundary, and for every
// unbiased integrator.
#include <gtest/gtest.h>

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
  const Film film = render(scene, options).film;
  // Every pixel is judged, background included (it sees the environment directly).
  const std::vector<bool> all(film.mean.size(), true);
  const test::RegionStats whole = test::region_mean(film, all);
  // Float accumulation over a path allows a few ulps of drift even where the estimator has
  // zero variance (pt with Fresnel-proportional choices).
  const double rounding = 1e-5;
  EXPECT_NEAR(whole.mean, 1.0, 4 * whole.standard_error + rounding)
      << "se " << whole.standard_error;
  // No region far off: 8x8 blocks, each within 5 standard errors (about 16 blocks, so a
  // Bonferroni-safe bound at a 1e-6 per-block false alarm rate).
  for (const auto& block : test::blocks(film, all, 8, 16)) {
    const test::RegionStats r = test::region_mean(film, block);
    EXPECT_NEAR(r.mean, 1.0, 5 * r.standard_error + rounding)
        << "block of " << r.pixels << " pixels";
  }
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

}  // namespace
}  // namespace snee
