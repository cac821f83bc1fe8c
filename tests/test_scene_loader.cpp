// The JSON scene format: every field reaches the Scene, the canonical document reloads to the
// same scene, defaults, examples, meshes' orientation and shading. Bad input is
// test_scene_errors.cpp's, the built-in scenes test_builtin_scenes.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/mesh_topology.h"
#include "scene/metals.h"
#include "scene/scene_loader.h"
#include "tests/support/scene_comparison.h"
#include "tests/support/scene_loader_fixture.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::bounding_radius;
using test::expect_round_trip;
using test::full_scene;
using test::kRemove;
using test::SceneLoaderTest;

TEST_F(SceneLoaderTest, EveryFieldReachesTheScene) {
  const LoadedScene loaded = load(full_scene());
  const Scene& s = loaded.scene;
  EXPECT_EQ(s.name, "everything");
  EXPECT_EQ(s.camera.width, 64);
  EXPECT_EQ(s.camera.height, 48);
  EXPECT_EQ(s.camera.fov_degrees, 35.0f);
  EXPECT_EQ(s.render.spp, 16);
  EXPECT_EQ(s.render.max_depth, 100);
  EXPECT_EQ(s.render.seed, 7u);
  EXPECT_EQ(s.render.integrator, "snee");
  EXPECT_EQ(s.render.noise_target, 0.02);
  EXPECT_EQ(s.render.light_selection, LightSelection::kPower);

  ASSERT_EQ(s.materials.size(), 4u);  // three named, one inline
  EXPECT_EQ(s.materials[0].kind, MaterialKind::kDielectric);
  EXPECT_EQ(s.materials[0].ior, 1.33f);
  EXPECT_EQ(s.materials[0].roughness, 0.04f);
  EXPECT_EQ(s.materials[1].albedo, Rgb(0.8f, 0.7f, 0.6f));
  EXPECT_EQ(s.materials[2].kind, MaterialKind::kNull);
  EXPECT_EQ(s.materials[3].name, "shapes[1].material");
  EXPECT_EQ(s.materials[3].roughness, 0.2f);

  ASSERT_EQ(s.media.size(), 3u);
  EXPECT_EQ(s.media[0].sigma_a, Rgb(0.1f));
  EXPECT_EQ(s.media[0].g, 0.3f);
  // albedo 0.9 with mean free paths 0.5, 0.25, 1: sigma_t = 2, 4, 1.
  EXPECT_NEAR(s.media[1].sigma_s.x, 1.8f, 1e-6f);
  EXPECT_NEAR(s.media[1].sigma_s.y, 3.6f, 1e-6f);
  EXPECT_NEAR(s.media[1].sigma_a.z, 0.1f, 1e-6f);
  EXPECT_NEAR(s.media[1].sigma_t().y, 4.0f, 1e-6f);
  EXPECT_EQ(s.media[2].name, "shapes[1].medium");

  ASSERT_EQ(s.shapes.size(), 4u);
  const Shape& cube = s.shapes[0];
  EXPECT_EQ(cube.name, "cube");
  EXPECT_TRUE(cube.closed);
  EXPECT_EQ(cube.material, 0);
  EXPECT_EQ(cube.interior_medium, 0);
  EXPECT_EQ(cube.source, (dir_ / "meshes" / "cube.obj").string());
  // Scaled by 2 (volume 8), turned outward although the file is inside out.
  EXPECT_NEAR(signed_volume(cube.mesh), 8.0, 1e-4);
  // Operations apply in the order listed. Vertex (1, 0, 0): translate -> (2, 0, 0), rotate 30
  // degrees about y -> (2 cos 30, 0, -2 sin 30), scale by 2.
  EXPECT_NEAR(cube.mesh.positions[1].x, 4 * std::cos(kPi / 6), 1e-5f);
  EXPECT_NEAR(cube.mesh.positions[1].z, -4 * std::sin(kPi / 6), 1e-5f);

  const Shape& bunny = s.shapes[1];
  EXPECT_EQ(bunny.mesh.triangle_count(), 3674u);
  EXPECT_TRUE(bunny.closed);
  EXPECT_GT(signed_volume(bunny.mesh), 0.0);
  EXPECT_EQ(bunny.material, 3);
  EXPECT_EQ(bunny.interior_medium, 2);

  const Shape& ball = s.shapes[2];
  EXPECT_EQ(ball.kind, ShapeKind::kSphere);
  EXPECT_EQ(ball.name, "ball");
  EXPECT_TRUE(ball.closed);
  EXPECT_EQ(ball.center, Vec3(0, 2, -3));
  EXPECT_EQ(ball.radius, 1.0f);

  const Shape& quad = s.shapes[3];
  EXPECT_FALSE(quad.closed);
  ASSERT_EQ(quad.mesh.triangle_count(), 2u);
  EXPECT_EQ(quad.mesh.positions[0], Vec3(-2, -1, -1));
  const Vec3 normal = cross(quad.mesh.positions[quad.mesh.indices[1]] - quad.mesh.positions[0],
                            quad.mesh.positions[quad.mesh.indices[2]] - quad.mesh.positions[0]);
  EXPECT_GT(normal.y, 0.0f);
  EXPECT_EQ(quad.emission, Rgb(1, 2, 3));

  ASSERT_EQ(s.lights.size(), 8u);  // seven listed and the emissive quad
  EXPECT_EQ(s.lights[0].kind, LightKind::kDirectional);
  EXPECT_EQ(s.lights[0].direction, Vec3(0, 1, 0));
  EXPECT_EQ(s.lights[0].irradiance, Rgb(3, 2, 1));
  EXPECT_EQ(s.lights[1].kind, LightKind::kCone);
  EXPECT_NEAR(s.lights[1].half_angle, 2.67f * kPi / 180, 1e-7f);
  EXPECT_NEAR(s.lights[1].direction.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(s.lights[2].kind, LightKind::kConstantEnv);
  EXPECT_EQ(s.lights[2].radiance, Rgb(0.5f));
  EXPECT_EQ(s.lights[3].kind, LightKind::kEnvMap);
  EXPECT_EQ(s.lights[3].radiance, Rgb(2.0f));
  EXPECT_EQ(s.lights[3].env_image, 0);
  const Vec3 turned = s.lights[3].env_rotation.vector(Vec3(1, 0, 0));
  EXPECT_NEAR(turned.z, -1.0f, 1e-6f);
  EXPECT_EQ(s.lights[4].kind, LightKind::kEnvMap);
  EXPECT_EQ(s.lights[4].env_image, 1);
  EXPECT_EQ(s.lights[5].kind, LightKind::kPoint);
  EXPECT_EQ(s.lights[5].intensity, Rgb(10.0f));
  EXPECT_EQ(s.lights[6].kind, LightKind::kSpot);
  EXPECT_EQ(s.lights[6].position, Vec3(0, 4, 0));
  EXPECT_EQ(s.lights[6].spot_axis, Vec3(0, 0, -1));
  EXPECT_EQ(s.lights[6].intensity, Rgb(20.0f));
  EXPECT_FLOAT_EQ(s.lights[6].spot_cos_outer, std::cos(40 * kPi / 180));
  EXPECT_FLOAT_EQ(s.lights[6].spot_cos_inner, std::cos(25 * kPi / 180));
  EXPECT_EQ(s.lights[7].kind, LightKind::kArea);
  EXPECT_EQ(s.lights[7].shape, 3);

  ASSERT_EQ(s.env_images.size(), 2u);
  EXPECT_EQ(s.env_images[0].width, 4);
  EXPECT_EQ(s.env_images[0].pixels[1], Rgb(4, 5, 6));
  EXPECT_EQ(s.env_images[1].width, 128);
  EXPECT_EQ(s.env_images[1].height, 64);
  EXPECT_TRUE(loaded.warnings.empty());
}

// The thin-lens keys and fov_axis reach the camera and its canonical document, which holds them
// only where a scene gives them, so older scenes keep their document and hash.
TEST_F(SceneLoaderTest, ThinLensAndFovAxisRoundTrip) {
  const json plain = load(full_scene()).canonical["camera"];
  for (const char* key : {"fov_axis", "aperture_radius", "focus_distance"})
    EXPECT_FALSE(plain.contains(key)) << key;
  json doc = full_scene();
  doc["camera"]["fov_axis"] = "horizontal";
  doc["camera"]["aperture_radius"] = 0.25;
  doc["camera"]["focus_distance"] = 3;
  const LoadedScene lens = load(doc);
  EXPECT_EQ(lens.scene.camera.fov_axis, FovAxis::kHorizontal);
  EXPECT_EQ(lens.scene.camera.aperture_radius, 0.25f);
  EXPECT_EQ(lens.scene.camera.focus_distance, 3.0f);
  EXPECT_EQ(lens.canonical["camera"]["fov_axis"], "horizontal");
  expect_round_trip(lens, scene_path());
  // A subnormal fov that a vertical axis accepts leaves no height across a 32768:1 image.
  doc["camera"]["fov"] = 1e-40;
  expect_error(doc, "camera.fov", "divided by the widest aspect ratio 32768");
}

// A scene with the conductor (by metal name and by index) and the diffuse transmitter.
json metals_scene() {
  return json::parse(R"({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "resolution": [8, 8]},
    "materials": [
      {"name": "gold", "type": "conductor", "metal": "gold", "roughness": 0.1},
      {"name": "mirror", "type": "conductor", "eta": 0, "k": [1, 2, 3]},
      {"name": "paper", "type": "diffuse_transmission", "reflectance": [0.3, 0.4, 0.5],
       "transmittance": [0.7, 0.6, 0.5]},
      {"name": "sheet", "type": "diffuse_transmission"}
    ],
    "shapes": [
      {"type": "sphere", "material": "gold"},
      {"type": "sphere", "center": [3, 0, 0], "material": "mirror"},
      {"type": "quad", "material": "paper"},
      {"type": "quad", "material": "sheet", "transform": [{"translate": [0, 0, -2]}]}
    ],
    "lights": [{"type": "constant", "radiance": 1}]
  })");
}

TEST_F(SceneLoaderTest, ConductorAndDiffuseTransmissionReachTheScene) {
  const LoadedScene loaded = load(metals_scene());
  const std::vector<Material>& m = loaded.scene.materials;
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].kind, MaterialKind::kConductor);
  EXPECT_EQ(m[0].conductor_eta, find_metal("gold")->eta);
  EXPECT_EQ(m[0].conductor_k, find_metal("gold")->k);
  EXPECT_EQ(m[0].roughness, 0.1f);
  EXPECT_EQ(m[1].conductor_eta, Rgb(0.0f));
  EXPECT_EQ(m[1].conductor_k, Rgb(1, 2, 3));
  EXPECT_EQ(m[1].roughness, 0.0f);
  EXPECT_EQ(m[2].kind, MaterialKind::kDiffuseTransmission);
  EXPECT_EQ(m[2].albedo, Rgb(0.3f, 0.4f, 0.5f));
  EXPECT_EQ(m[2].transmittance, Rgb(0.7f, 0.6f, 0.5f));
  EXPECT_EQ(m[3].albedo, Rgb(0.5f));
  EXPECT_EQ(m[3].transmittance, Rgb(0.5f));
  // The canonical document holds the resolved index, not the metal's name.
  const json& gold = loaded.canonical["materials"][0];
  EXPECT_FALSE(gold.contains("metal"));
  EXPECT_EQ(gold["type"], "conductor");
  expect_round_trip(loaded, scene_path());
  for (const std::string_view name : metal_names()) {
    json doc = metals_scene();
    doc["materials"][0]["metal"] = name;
    EXPECT_EQ(load(doc).scene.materials[0].conductor_eta, find_metal(name)->eta) << name;
  }
}

// The light-selection measurement scene of docs/lights.md loads, with power selection.
TEST_F(SceneLoaderTest, KeyLightExampleLoads) {
  const fs::path example =
      fs::path(SNEE_PROJECT_DATA_DIR).parent_path() / "docs/examples/key-light.json";
  const LoadedScene loaded = load_scene_file(example.string());
  EXPECT_EQ(loaded.scene.render.light_selection, LightSelection::kPower);
  EXPECT_EQ(loaded.scene.lights.size(), 3u);
  EXPECT_TRUE(loaded.warnings.empty());
}

// The materials example of docs/scene-format.md loads and round-trips.
TEST_F(SceneLoaderTest, MaterialsExampleLoads) {
  const fs::path example =
      fs::path(SNEE_PROJECT_DATA_DIR).parent_path() / "docs/examples/materials.json";
  const LoadedScene loaded = load_scene_file(example.string());
  ASSERT_EQ(loaded.scene.materials.size(), 5u);
  EXPECT_EQ(loaded.scene.materials[0].kind, MaterialKind::kConductor);
  EXPECT_EQ(loaded.scene.materials[3].kind, MaterialKind::kDiffuseTransmission);
  EXPECT_TRUE(loaded.warnings.empty());
  expect_round_trip(loaded, example.string());
}

// The point- and spot-light example of docs/lights.md loads: two spheres behind a smooth
// boundary, a spot, a point light and a sky.
TEST_F(SceneLoaderTest, SpotLitExampleLoads) {
  const fs::path example =
      fs::path(SNEE_PROJECT_DATA_DIR).parent_path() / "docs/examples/spot-lit.json";
  const LoadedScene loaded = load_scene_file(example.string());
  ASSERT_EQ(loaded.scene.lights.size(), 3u);
  EXPECT_EQ(loaded.scene.lights[0].kind, LightKind::kSpot);
  EXPECT_EQ(loaded.scene.lights[1].kind, LightKind::kPoint);
  EXPECT_EQ(loaded.scene.materials[0].roughness, 0.0f);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST_F(SceneLoaderTest, BadLightSelectionNamesItsPath) {
  json doc = full_scene();
  doc["render"]["light_selection"] = "importance";
  expect_error(doc, "render.light_selection",
               "expected one of: uniform, power, got \"importance\"");
  doc["render"]["light_selection"] = 1;
  expect_error(doc, "render.light_selection", "expected one of: uniform, power, got 1");
}

TEST_F(SceneLoaderTest, BadConductorAndDiffuseTransmissionFieldsNameTheirPath) {
  const auto with = [](const std::string& pointer, const json& value) {
    json doc = metals_scene();
    const json::json_pointer p(pointer);
    if (value == kRemove) {
      doc[p.parent_pointer()].erase(p.back());
    } else {
      doc[p] = value;
    }
    return doc;
  };
  expect_error(with("/materials/0/metal", "steel"), "materials[0].metal",
               "expected one of: gold, silver, copper, aluminium, got \"steel\"");
  expect_error(with("/materials/0/eta", 1), "materials[0]", "either metal or eta and k, not both");
  expect_error(with("/materials/1/k", kRemove), "materials[1]",
               "needs either metal (a named index) or both eta and k");
  expect_error(with("/materials/1/k", {1, -2, 3}), "materials[1].k[1]",
               "expected a number in [0, 1000], got -2");
  expect_error(with("/materials/1/eta", -0.5), "materials[1].eta",
               "expected a number in [0, 1000]");
  expect_error(with("/materials/0/roughness", 2), "materials[0].roughness",
               "expected a number in [0, 1], got 2");
  expect_error(with("/materials/2/transmittance", {0.7, 0.7, 0.5}), "materials[2].transmittance",
               "reflectance + transmittance is 1.1 in channel 1");
  expect_error(with("/materials/3/reflectance", 0.75), "materials[3]",
               "reflectance + transmittance is 1.25 in channel 0 (transmittance defaults to 0.5)");
  expect_error(with("/materials/2/reflectance", {0.3, 1.5, 0}), "materials[2].reflectance[1]",
               "a number in [0, 1]");
  expect_error(with("/materials/2/albedo", 0.5), "materials[2].albedo",
               "unknown key (allowed keys: name, type, reflectance, transmittance)");
  // Opaque surfaces bound no medium.
  json doc = metals_scene();
  doc["shapes"][0]["medium"] = {{"sigma_s", 1}};
  expect_error(doc, "shapes[0].medium", "an interior medium needs a dielectric or null material");
  doc = metals_scene();
  doc["shapes"][2]["medium"] = {{"sigma_s", 1}};
  expect_error(doc, "shapes[2].medium", "an interior medium needs a dielectric or null material");
}

TEST_F(SceneLoaderTest, CanonicalDocumentRoundTrips) {
  const LoadedScene loaded = load(full_scene());
  expect_round_trip(loaded, scene_path());
  // Defaults are filled in and inline definitions moved to the named lists.
  const json& c = loaded.canonical;
  EXPECT_EQ(c["camera"]["type"], "pinhole");
  EXPECT_EQ(c["shapes"][1]["material"], "shapes[1].material");
  EXPECT_EQ(c["shapes"][1]["file"], "data/meshes/bunny-npm.obj");
  EXPECT_EQ(c["shapes"][0]["file"], (dir_ / "meshes" / "cube.obj").string());
  EXPECT_EQ(c["shapes"][0]["normalize"], false);
  EXPECT_EQ(c["media"][1]["type"], "homogeneous");
  EXPECT_EQ(c["lights"].size(), 7u);
  EXPECT_EQ(c["lights"][6]["look_at"], json({0.0, 4.0, -2.0}));
  EXPECT_EQ(c["lights"][6]["falloff_start_degrees"], 25.0);
}

// A spot given only its position and target gets pbrt's defaults: a 30-degree cone whose last
// 5 degrees fall off; a narrow cone falls off over all of it.
TEST_F(SceneLoaderTest, SpotLightDefaults) {
  const LoadedScene loaded = load_text(R"({
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
    "shapes": [{"type": "sphere", "material": {"type": "diffuse"}}],
    "lights": [{"type": "spot", "position": [0, 2, 0], "look_at": [0, 0, 0]},
               {"type": "spot", "position": [0, 2, 0], "look_at": [0, 0, 0],
                "cone_angle_degrees": 3}]
  })");
  const Light& spot = loaded.scene.lights[0];
  EXPECT_EQ(spot.intensity, Rgb(1.0f));
  EXPECT_EQ(spot.spot_axis, Vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(spot.spot_cos_outer, std::cos(30 * kPi / 180));
  EXPECT_FLOAT_EQ(spot.spot_cos_inner, std::cos(25 * kPi / 180));
  EXPECT_EQ(loaded.scene.lights[1].spot_cos_inner, 1.0f);
  EXPECT_EQ(loaded.canonical["lights"][0]["cone_angle_degrees"], 30.0);
  EXPECT_EQ(loaded.canonical["lights"][1]["falloff_start_degrees"], 0.0);
  expect_round_trip(loaded, scene_path());
}

TEST_F(SceneLoaderTest, MinimalSceneGetsDefaults) {
  const LoadedScene loaded = load_text(R"({
    // comments are allowed
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
    "shapes": [{"type": "sphere", "material": {"type": "diffuse"}}]
  })");
  const Scene& s = loaded.scene;
  EXPECT_EQ(s.name, "scene");
  EXPECT_EQ(s.camera.width, 256);
  EXPECT_EQ(s.camera.fov_degrees, 40.0f);
  EXPECT_EQ(s.render.spp, 64);
  EXPECT_EQ(s.render.integrator, "pt");
  EXPECT_EQ(s.render.noise_target, 0.0);
  EXPECT_EQ(s.shapes[0].center, Vec3(0.0f));
  EXPECT_EQ(s.shapes[0].radius, 1.0f);
  EXPECT_EQ(s.materials[0].albedo, Rgb(0.5f));
  EXPECT_TRUE(s.lights.empty());
  expect_round_trip(loaded, scene_path());
}

TEST_F(SceneLoaderTest, NormalizedMeshHasUnitBoundingSphere) {
  json doc = full_scene();
  doc["shapes"] = json::array({json{{"type", "mesh"},
                                    {"file", "meshes/cube.obj"},
                                    {"normalize", true},
                                    {"material", "glass"},
                                    {"transform", {{{"translate", {0, 5, 0}}}}}}});
  const LoadedScene loaded = load(doc);
  const Shape& cube = loaded.scene.shapes[0];
  // The unit cube's half-diagonal sqrt(3)/2 becomes 1, centred at (0, 5, 0) after the move.
  EXPECT_NEAR(bounding_radius(cube.mesh, Vec3(0, 5, 0)), 1.0, 1e-6);
  EXPECT_NEAR(cube.mesh.positions[7].x, 1 / std::sqrt(3.0f), 1e-6f);
  EXPECT_NEAR(signed_volume(cube.mesh), std::pow(2 / std::sqrt(3.0), 3), 1e-5);
}

TEST_F(SceneLoaderTest, MirroredQuadKeepsItsFrontSide) {
  json doc = full_scene();
  doc["shapes"] = json::array(
      {json{{"type", "quad"},
            {"material", "white"},
            {"transform", {{{"matrix", {{-1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}}}}}}});
  const LoadedScene loaded = load(doc);
  const TriangleMesh& m = loaded.scene.shapes[0].mesh;
  const Vec3 normal = cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                            m.positions[m.indices[2]] - m.positions[m.indices[0]]);
  EXPECT_GT(normal.y, 0.0f);
}

TEST_F(SceneLoaderTest, OpenMeshWithMediumWarns) {
  json doc = full_scene();
  doc["shapes"] =
      json::array({json{{"type", "mesh"},
                        {"file", "meshes/square.obj"},
                        {"material", "glass"},
                        {"medium", "skin"}},
                   json{{"type", "mesh"}, {"file", "meshes/square.obj"}, {"material", "white"}}});
  const LoadedScene loaded = load(doc);
  EXPECT_FALSE(loaded.scene.shapes[0].closed);
  ASSERT_EQ(loaded.warnings.size(), 1u);  // the second square has no medium: no warning
  const std::string& warning = loaded.warnings[0];
  EXPECT_NE(warning.find("square.obj"), std::string::npos) << warning;
  EXPECT_NE(warning.find("4 boundary edges"), std::string::npos) << warning;
  EXPECT_NE(warning.find("shapes[0]"), std::string::npos) << warning;
}

TEST_F(SceneLoaderTest, ShadingIsSmoothWhereTheMeshHasNormals) {
  std::ofstream(dir_ / "meshes" / "normals_cube.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
         "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
         "f 1//1 3//1 4//1 2//1\nf 5//2 6//2 8//2 7//2\nf 1//3 2//3 6//3 5//3\n"
         "f 3//4 7//4 8//4 4//4\nf 1//5 5//5 7//5 3//5\nf 2//6 4//6 8//6 6//6\n";
  json doc = full_scene();
  doc["shapes"][0]["file"] = "meshes/normals_cube.obj";
  const LoadedScene smooth = load(doc);
  const Shape& cube = smooth.scene.shapes[0];
  EXPECT_TRUE(cube.smooth_shading);
  EXPECT_TRUE(cube.closed);
  EXPECT_EQ(cube.mesh.positions.size(), 24u);
  EXPECT_EQ(smooth.canonical["shapes"][0]["shading"], "smooth");
  // The bunny has no normals: flat, and nothing in the canonical form.
  EXPECT_FALSE(smooth.scene.shapes[1].smooth_shading);
  EXPECT_FALSE(smooth.canonical["shapes"][1].contains("shading"));

  doc["shapes"][0]["shading"] = "flat";
  const LoadedScene flat = load(doc);
  EXPECT_FALSE(flat.scene.shapes[0].smooth_shading);
  EXPECT_EQ(flat.canonical["shapes"][0]["shading"], "flat");
  EXPECT_FALSE(
      load_scene_json(flat.canonical, "canonical", dir_.string()).scene.shapes[0].smooth_shading);
}

TEST_F(SceneLoaderTest, ShadingErrorsNameThePathAndTheChoices) {
  json doc = full_scene();
  doc["shapes"][0]["shading"] = "phong";
  expect_error(doc, "shapes[0].shading", "smooth, flat");
  doc["shapes"][0]["shading"] = true;
  expect_error(doc, "shapes[0].shading", "smooth, flat");
  // cube.obj has no normals to be smooth with.
  doc["shapes"][0]["shading"] = "smooth";
  expect_error(doc, "shapes[0].shading", "needs vertex normals");
  // Spheres and quads have no such key.
  doc["shapes"][0].erase("shading");
  doc["shapes"][2]["shading"] = "flat";
  expect_error(doc, "shapes[2].shading", "unknown key");
}

}  // namespace
}  // namespace snee
