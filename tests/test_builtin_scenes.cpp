// The built-in scenes: unique names covering the paper grid, every one loads, reloads from its
// canonical form and is sane (lights as in the paper, white furnaces, the default bunny on its
// floor, the procedural sky).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "scene/mesh_topology.h"
#include "scene/scene_loader.h"
#include "tests/support/scene_comparison.h"

namespace snee {
namespace {

using test::bounding_radius;
using test::expect_round_trip;

TEST(BuiltinScenes, NamesAreUniqueAndCoverThePaperGrid) {
  const std::vector<BuiltinSceneInfo> scenes = builtin_scenes();
  std::set<std::string> names;
  for (const BuiltinSceneInfo& info : scenes) {
    EXPECT_TRUE(names.insert(info.name).second) << "duplicate " << info.name;
    EXPECT_FALSE(info.description.empty()) << info.name;
  }
  EXPECT_EQ(scenes.size(), 1u + 18u + 3u);
  for (const char* object : {"sphere", "bunny"}) {
    for (const char* light : {"directional", "cone", "env"}) {
      for (const char* surface : {"r0.2", "r0.04", "smooth"}) {
        const std::string name = std::string(object) + "-" + light + "-" + surface;
        EXPECT_TRUE(names.count(name)) << name;
      }
    }
  }
  for (const char* name : {"default", "furnace-sphere", "furnace-bunny", "furnace-sphere-null"}) {
    EXPECT_TRUE(names.count(name)) << name;
  }
}

TEST(BuiltinScenes, UnknownNameListsTheKnownOnes) {
  try {
    load_scene("builtin:nonesuch");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("nonesuch"), std::string::npos);
    EXPECT_NE(message.find("furnace-sphere"), std::string::npos);
  }
}

// Every built-in scene loads, is sane and round-trips through its canonical document.
TEST(BuiltinScenes, EveryOneLoadsAndIsSane) {
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    SCOPED_TRACE(info.name);
    const LoadedScene loaded = load_scene("builtin:" + info.name);
    const Scene& s = loaded.scene;
    EXPECT_EQ(s.name, info.name);
    EXPECT_TRUE(loaded.warnings.empty());
    EXPECT_GT(s.camera.width, 0);
    EXPECT_GT(s.camera.height, 0);
    EXPECT_GT(length(s.camera.look_at - s.camera.position), 1.0f);
    EXPECT_GT(s.render.spp, 0);
    ASSERT_FALSE(s.lights.empty());
    ASSERT_FALSE(s.shapes.empty());
    for (const Shape& shape : s.shapes) {
      ASSERT_GE(shape.material, 0);
      ASSERT_LT(shape.material, static_cast<int>(s.materials.size()));
      if (shape.interior_medium >= 0) {
        EXPECT_TRUE(shape.closed);
        EXPECT_NE(s.materials[shape.material].kind, MaterialKind::kDiffuse);
        if (shape.kind == ShapeKind::kMesh) {
          EXPECT_GT(signed_volume(shape.mesh), 0.0);
        }
      }
    }
    // The translucent object is the first shape, of bounding radius 1 at the origin.
    const Shape& object = s.shapes[0];
    ASSERT_GE(object.interior_medium, 0);
    if (object.kind == ShapeKind::kSphere) {
      EXPECT_EQ(object.radius, 1.0f);
      EXPECT_EQ(object.center, Vec3(0.0f));
    } else {
      EXPECT_NEAR(bounding_radius(object.mesh, Vec3(0.0f)), 1.0, 1e-5);
    }
    const Medium& medium = s.media[object.interior_medium];
    EXPECT_LE(max_component(medium.sigma_t()), 10.0f);
    expect_round_trip(loaded, "builtin:" + info.name);
  }
}

TEST(BuiltinScenes, GridLightsMatchThePaper) {
  for (const char* object : {"sphere", "bunny"}) {
    for (const char* surface : {"r0.2", "r0.04", "smooth"}) {
      const std::string suffix = std::string("-") + surface;
      const Scene directional =
          load_builtin_scene(object + std::string("-directional") + suffix).scene;
      const Scene cone = load_builtin_scene(object + std::string("-cone") + suffix).scene;
      const Scene env = load_builtin_scene(object + std::string("-env") + suffix).scene;
      ASSERT_EQ(directional.lights.size(), 1u);
      ASSERT_EQ(cone.lights.size(), 1u);
      ASSERT_EQ(env.lights.size(), 1u);
      EXPECT_EQ(directional.lights[0].kind, LightKind::kDirectional);
      EXPECT_EQ(cone.lights[0].kind, LightKind::kCone);
      EXPECT_EQ(env.lights[0].kind, LightKind::kEnvMap);
      EXPECT_NEAR(directional.lights[0].irradiance.x, 3.0f, 1e-6f);
      EXPECT_GT(directional.lights[0].direction.y, 0.5f);  // from above
      EXPECT_GT(directional.lights[0].direction.z, 0.0f);  // on the camera's side
      // The cone covers about 100x the sun's solid angle and gives the same irradiance.
      const float half_angle = cone.lights[0].half_angle;
      EXPECT_NEAR(half_angle, 2.67f * kPi / 180, 1e-6f);
      const double solid_angle = 2 * kPi * (1 - std::cos(double{half_angle}));
      EXPECT_NEAR(solid_angle / 6.8e-5, 100.0, 2.0);
      EXPECT_NEAR(cone.lights[0].radiance.x * solid_angle, 3.0, 1e-3);
      EXPECT_EQ(cone.lights[0].direction, directional.lights[0].direction);

      const Material& m = directional.materials[directional.shapes[0].material];
      EXPECT_EQ(m.kind, MaterialKind::kDielectric);
      EXPECT_EQ(m.ior, 1.5f);
      EXPECT_EQ(m.roughness, surface == std::string("smooth") ? 0.0f : std::stof(surface + 1));
      const Medium& medium = directional.media[directional.shapes[0].interior_medium];
      const Rgb albedo = medium.sigma_s / medium.sigma_t();
      EXPECT_GE(min_component(albedo), 0.95f);
      EXPECT_LE(max_component(albedo), 0.99f);
      EXPECT_EQ(directional.camera.width, 128);
      // The unit-radius object spans about 60% of the vertical field of view.
      const float distance = length(directional.camera.position);
      const float span = 2 * std::atan(1 / distance) * 180 / kPi / directional.camera.fov_degrees;
      EXPECT_NEAR(span, 0.6f, 0.05f);
    }
  }
}

TEST(BuiltinScenes, FurnacesAreWhiteUnderUnitRadiance) {
  for (const char* name : {"furnace-sphere", "furnace-bunny", "furnace-sphere-null"}) {
    SCOPED_TRACE(name);
    const Scene s = load_builtin_scene(name).scene;
    ASSERT_EQ(s.shapes.size(), 1u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, LightKind::kConstantEnv);
    EXPECT_EQ(s.lights[0].radiance, Rgb(1.0f));
    const Medium& medium = s.media[s.shapes[0].interior_medium];
    EXPECT_EQ(medium.sigma_a, Rgb(0.0f));
    EXPECT_EQ(medium.sigma_s, Rgb(2.0f));
    const Material& m = s.materials[s.shapes[0].material];
    if (std::string(name) == "furnace-sphere-null") {
      EXPECT_EQ(m.kind, MaterialKind::kNull);
    } else {
      EXPECT_EQ(m.kind, MaterialKind::kDielectric);
      EXPECT_EQ(m.ior, 1.5f);
      EXPECT_EQ(m.roughness, 0.0f);
    }
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.camera.height, 64);
  }
}

TEST(BuiltinScenes, DefaultBunnyStandsOnTheFloor) {
  const Scene s = load_builtin_scene("default").scene;
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 240);
  float lowest = kInfinity;
  for (const Vec3& p : s.shapes[0].mesh.positions) lowest = std::min(lowest, p.y);
  for (const Vec3& p : s.shapes[1].mesh.positions) EXPECT_EQ(p.y, lowest);
  EXPECT_EQ(s.materials[s.shapes[1].material].kind, MaterialKind::kDiffuse);
  const Medium& jade = s.media[s.shapes[0].interior_medium];
  EXPECT_LE(max_component(jade.sigma_s / jade.sigma_t()), 0.99f);
  // It shows what snee is for, finished by the noise target rather than a fixed count.
  EXPECT_EQ(s.render.integrator, "snee");
  EXPECT_GT(s.render.noise_target, 0.0);
}

TEST(BuiltinScenes, ProceduralSkyIsLowFrequencyAndBrightAbove) {
  const Scene s = load_builtin_scene("sphere-env-smooth").scene;
  ASSERT_EQ(s.env_images.size(), 1u);
  const RgbImage& sky = s.env_images[0];
  ASSERT_EQ(sky.width, 128);
  ASSERT_EQ(sky.height, 64);
  float brightest = 0;
  for (const Rgb& c : sky.pixels) {
    ASSERT_TRUE(is_finite(c));
    ASSERT_GT(min_component(c), 0.0f);
    brightest = std::max(brightest, luminance(c));
  }
  const Rgb zenith = sky.pixels[64];
  const Rgb nadir = sky.pixels[63 * 128 + 64];
  EXPECT_GT(zenith.z, zenith.x);      // blue above
  EXPECT_LT(luminance(nadir), 0.1f);  // dark ground
  EXPECT_GT(brightest, 2.0f);         // the soft bright lobe
  EXPECT_LT(brightest, 5.0f);
}

// A cube whose faces each name their own normal: its corners split into 24 vertices, it still

}  // namespace
}  // namespace snee
