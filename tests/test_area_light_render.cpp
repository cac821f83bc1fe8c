// A Lambertian floor under a square emitter renders to albedo E / pi, E the closed-form
// irradiance. The floor is large, as in real scenes, so the scene-scale ray offset is large
// against the emitter's distance: shadow rays toward a finite light must end short of the
// light's own surface however far their origin was moved (LightTable's shadow_ray_to_light).
#include <gtest/gtest.h>

#include <cmath>

#include "scheduler/render.h"
#include "tests/support/form_factor.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

Shape square(float half, float y, bool facing_down) {
  Shape s;
  s.kind = ShapeKind::kMesh;
  s.mesh.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
  s.mesh.indices = facing_down ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3}
                               : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
  s.closed = false;
  return s;
}

TEST(AreaLightRender, FloorUnderSquareEmitterMatchesClosedForm) {
  Scene scene;
  scene.camera.position = {0, 0.5f, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.fov_degrees = 2;
  scene.camera.width = scene.camera.height = 8;
  Material floor_material;
  floor_material.albedo = Rgb(0.5f);
  Material black;
  black.albedo = Rgb(0.0f);
  scene.materials = {floor_material, black};
  Shape floor = square(100, 0, false);
  floor.material = 0;
  Shape panel = square(0.5f, 1, true);
  panel.material = 1;
  panel.emission = Rgb(2.0f);
  scene.shapes = {floor, panel};
  Light light;
  light.kind = LightKind::kArea;
  light.shape = 1;
  scene.lights.push_back(light);

  RenderOptions options;
  options.spp = 256;
  options.seed = 21;
  for (const char* integrator : {"pt", "snee"}) {
    options.integrator = integrator;
    options.snee.light_limit_degrees = 180;  // SNEE under any light (docs/method.md 3.11)
    const Film film = render(scene, options).film;
    const test::RegionStats r = test::region_mean(film, std::vector<bool>(film.mean.size(), true));
    // Over 2 degrees the irradiance changes by less than 1e-4 relative.
    const double irradiance = 2.0 * M_PI * 4 * test::corner_form_factor(0.5, 0.5, 1.0);
    const double expected = 0.5 * irradiance / M_PI;
    EXPECT_NEAR(r.mean, expected, 4 * r.standard_error + 1e-4 * expected)
        << integrator << ": " << r.mean << " +- " << r.standard_error;
  }
}

}  // namespace
}  // namespace snee
