// The JSON scene format: every field reaches the Scene, every bad input is a SceneError that
// names the file, the JSON path and the expectation, the canonical document reloads to the same
// scene, and every built-in scene loads and is sane.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "scene/mesh_topology.h"
#include "scene/metals.h"
#include "scene/scene_loader.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A closed cube with inward (wrong) winding, and a lone open square, as OBJ text.
constexpr const char* kInsideOutCubeObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
constexpr const char* kOpenSquareObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

const json kRemove = "<remove the key>";

struct BadCase {
  std::string name;
  std::string pointer;      // JSON pointer of the value to replace, or to remove
  json value;               // kRemove: remove the key
  std::string path;         // expected JSON path in the message
  std::string expectation;  // expected text in the message
};

json full_scene();

class SceneLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_directory("test_scene_loader");
    fs::create_directories(dir_ / "meshes");
    std::ofstream(dir_ / "meshes" / "cube.obj") << kInsideOutCubeObj;
    std::ofstream(dir_ / "meshes" / "square.obj") << kOpenSquareObj;
    write_env_exr();
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write_env_exr() {
    const std::string path = (dir_ / "env.exr").string();
    const std::vector<float> pixels = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12,
                                       0, 0, 0, 1, 1, 1, 2, 2, 2, 3,  3,  3};
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(4, 2, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
  }

  std::string scene_path() const { return (dir_ / "scene.json").string(); }

  LoadedScene load_text(const std::string& text) {
    std::ofstream(scene_path()) << text;
    return load_scene_file(scene_path());
  }
  LoadedScene load(const json& doc) { return load_text(doc.dump(2)); }

  // Loads `doc` expecting a SceneError whose message has the file, `path` and `expectation`.
  void expect_error(const json& doc, const std::string& path, const std::string& expectation) {
    try {
      load(doc);
      ADD_FAILURE() << "no SceneError; expected one at " << path;
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(scene_path()), std::string::npos) << message;
      EXPECT_NE(message.find(path + ":"), std::string::npos) << "path " << path << ": " << message;
      EXPECT_NE(message.find(expectation), std::string::npos)
          << "expectation '" << expectation << "': " << message;
    }
  }

  // Each case edits full_scene() and expects its error.
  void expect_errors(const std::vector<BadCase>& cases) {
    for (const BadCase& c : cases) {
      SCOPED_TRACE(c.name);
      json doc = full_scene();
      const json::json_pointer pointer(c.pointer);
      if (c.value == kRemove) {
        doc[pointer.parent_pointer()].erase(pointer.back());
      } else {
        doc[pointer] = c.value;
      }
      expect_error(doc, c.path, c.expectation);
    }
  }

  // Loads `text` expecting a SceneError whose message contains `expected`.
  void expect_text_error(const std::string& text, const std::string& expected) {
    try {
      load_text(text);
      ADD_FAILURE() << "no SceneError; expected " << expected;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }

  fs::path dir_;
};

// A small scene using every feature of the format.
json full_scene() {
  return json::parse(R"({
    "name": "everything",
    "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "up": [0, 1, 0], "fov": 35,
               "resolution": [64, 48]},
    "render": {"spp": 16, "max_depth": 100, "seed": 7, "integrator": "snee",
               "noise_target": 0.02, "light_selection": "power"},
    "materials": [
      {"name": "glass", "type": "dielectric", "ior": 1.33, "roughness": 0.04},
      {"name": "white", "type": "diffuse", "albedo": [0.8, 0.7, 0.6]},
      {"name": "matched", "type": "null"}
    ],
    "media": [
      {"name": "skin", "sigma_s": [4, 5, 6], "sigma_a": 0.1, "g": 0.3},
      {"name": "milk", "albedo": 0.9, "mean_free_path": [0.5, 0.25, 1]}
    ],
    "shapes": [
      {"type": "mesh", "file": "meshes/cube.obj", "material": "glass", "medium": "skin",
       "transform": [{"translate": [1, 0, 0]}, {"rotate": {"axis": [0, 1, 0], "degrees": 30}},
                     {"scale": 2}]},
      {"type": "mesh", "file": "data/meshes/bunny-npm.obj", "normalize": true,
       "material": {"type": "dielectric", "ior": 1.5, "roughness": 0.2},
       "medium": {"albedo": [0.95, 0.97, 0.99], "mean_free_path": 0.3}},
      {"type": "sphere", "name": "ball", "center": [0, 1, 0], "radius": 0.5, "material": "matched",
       "medium": "milk", "transform": [{"scale": 2}, {"translate": [0, 0, -3]}]},
      {"type": "quad", "size": [4, 2], "material": "white", "emission": [1, 2, 3],
       "transform": [{"matrix": [[1, 0, 0, 0], [0, 1, 0, -1], [0, 0, 1, 0], [0, 0, 0, 1]]}]}
    ],
    "lights": [
      {"type": "directional", "direction": [0, 2, 0], "irradiance": [3, 2, 1]},
      {"type": "cone", "direction": [1, 1, 0], "half_angle_degrees": 2.67, "radiance": 400},
      {"type": "constant", "radiance": 0.5},
      {"type": "envmap", "file": "env.exr", "scale": 2,
       "rotation": [{"rotate": {"axis": [0, 1, 0], "degrees": 90}}]},
      {"type": "sky", "scale": [1, 0.9, 0.8]},
      {"type": "point", "position": [0, 3, 0], "intensity": 10},
      {"type": "spot", "position": [0, 4, 0], "look_at": [0, 4, -2], "intensity": 20,
       "cone_angle_degrees": 40, "falloff_start_degrees": 25}
    ]
  })");
}

void expect_same_transform(const Transform& a, const Transform& b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_EQ(a.m[i][j], b.m[i][j]) << i << "," << j;
  }
}

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.camera.position, b.camera.position);
  EXPECT_EQ(a.camera.look_at, b.camera.look_at);
  EXPECT_EQ(a.camera.up, b.camera.up);
  EXPECT_EQ(a.camera.fov_degrees, b.camera.fov_degrees);
  EXPECT_EQ(a.camera.fov_axis, b.camera.fov_axis);
  EXPECT_EQ(a.camera.aperture_radius, b.camera.aperture_radius);
  EXPECT_EQ(a.camera.focus_distance, b.camera.focus_distance);
  EXPECT_EQ(a.camera.width, b.camera.width);
  EXPECT_EQ(a.camera.height, b.camera.height);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].kind, b.materials[i].kind);
    EXPECT_EQ(a.materials[i].albedo, b.materials[i].albedo);
    EXPECT_EQ(a.materials[i].ior, b.materials[i].ior);
    EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
    EXPECT_EQ(a.materials[i].transmittance, b.materials[i].transmittance);
    EXPECT_EQ(a.materials[i].conductor_eta, b.materials[i].conductor_eta);
    EXPECT_EQ(a.materials[i].conductor_k, b.materials[i].conductor_k);
  }
  ASSERT_EQ(a.media.size(), b.media.size());
  for (size_t i = 0; i < a.media.size(); ++i) {
    EXPECT_EQ(a.media[i].name, b.media[i].name);
    EXPECT_EQ(a.media[i].sigma_s, b.media[i].sigma_s);
    EXPECT_EQ(a.media[i].sigma_a, b.media[i].sigma_a);
    EXPECT_EQ(a.media[i].g, b.media[i].g);
  }
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    const Shape &s = a.shapes[i], &t = b.shapes[i];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.kind, t.kind);
    EXPECT_EQ(s.mesh.positions, t.mesh.positions);
    EXPECT_EQ(s.mesh.indices, t.mesh.indices);
    EXPECT_EQ(s.center, t.center);
    EXPECT_EQ(s.radius, t.radius);
    EXPECT_EQ(s.material, t.material);
    EXPECT_EQ(s.interior_medium, t.interior_medium);
    EXPECT_EQ(s.emission, t.emission);
    EXPECT_EQ(s.closed, t.closed);
    EXPECT_EQ(s.source, t.source);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const Light &l = a.lights[i], &m = b.lights[i];
    EXPECT_EQ(l.kind, m.kind);
    EXPECT_EQ(l.direction, m.direction);
    EXPECT_EQ(l.irradiance, m.irradiance);
    EXPECT_EQ(l.half_angle, m.half_angle);
    EXPECT_EQ(l.radiance, m.radiance);
    EXPECT_EQ(l.position, m.position);
    EXPECT_EQ(l.intensity, m.intensity);
    EXPECT_EQ(l.spot_axis, m.spot_axis);
    EXPECT_EQ(l.spot_cos_outer, m.spot_cos_outer);
    EXPECT_EQ(l.spot_cos_inner, m.spot_cos_inner);
    EXPECT_EQ(l.env_image, m.env_image);
    expect_same_transform(l.env_rotation, m.env_rotation);
    EXPECT_EQ(l.shape, m.shape);
  }
  ASSERT_EQ(a.env_images.size(), b.env_images.size());
  for (size_t i = 0; i < a.env_images.size(); ++i) {
    EXPECT_EQ(a.env_images[i].width, b.env_images[i].width);
    EXPECT_EQ(a.env_images[i].height, b.env_images[i].height);
    EXPECT_EQ(a.env_images[i].pixels, b.env_images[i].pixels);
    EXPECT_EQ(a.env_images[i].source, b.env_images[i].source);
  }
  EXPECT_EQ(a.render.spp, b.render.spp);
  EXPECT_EQ(a.render.max_depth, b.render.max_depth);
  EXPECT_EQ(a.render.seed, b.render.seed);
  EXPECT_EQ(a.render.integrator, b.render.integrator);
  EXPECT_EQ(a.render.light_selection, b.render.light_selection);
  EXPECT_EQ(a.render.noise_target, b.render.noise_target);
}

// Loads the canonical document again (from another directory, so relative paths would break)
// and expects the same scene and the same canonical document.
void expect_round_trip(const LoadedScene& first, const std::string& origin) {
  const LoadedScene second = load_scene_json(first.canonical, origin, "/");
  expect_same_scene(first.scene, second.scene);
  EXPECT_EQ(first.canonical, second.canonical) << first.canonical.dump(1) << "\n---\n"
                                               << second.canonical.dump(1);
}

double bounding_radius(const TriangleMesh& mesh, Vec3 center) {
  double r = 0;
  for (const Vec3& p : mesh.positions) r = std::max(r, double{length(p - center)});
  return r;
}

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

TEST_F(SceneLoaderTest, MissingAndMalformedFiles) {
  const std::string missing = (dir_ / "nope.json").string();
  try {
    load_scene_file(missing);
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  try {
    load_text("{\n  \"camera\": {\n    \"fov\": 30,,\n  }\n}\n");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(scene_path() + ":3:15: malformed JSON: "), std::string::npos) << message;
    EXPECT_NE(message.find("expected string literal"), std::string::npos) << message;
    EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  }
}

// Nesting this deep used to overflow the stack while the error message quoted the value.
TEST_F(SceneLoaderTest, DeepNestingIsRefusedWhileParsing) {
  for (const size_t depth : {size_t{100'000}, size_t{1'000'000}}) {
    SCOPED_TRACE(depth);
    expect_text_error("{\n  \"name\": " + std::string(depth, '[') + std::string(depth, ']') + "}",
                      // The object is level 1, so the 100th bracket (column 11 + 99) is too deep.
                      scene_path() + ":2:110: arrays and objects nested deeper than 100 levels");
    expect_text_error(std::string(depth, '[') + "{\"a\": 1}" + std::string(depth, ']'),
                      scene_path() + ":1:101: arrays and objects nested deeper than 100 levels");
  }
  // Up to the bound the document parses, and the loader's message names the path.
  expect_text_error("{\"camera\": " + std::string(99, '[') + std::string(99, ']') + "}",
                    scene_path() + ": camera: expected an object, got [[[[");
}

// A value nested deeper than any parsed document may be (a caller building one in memory) is
// quoted in messages without walking all of it.
TEST_F(SceneLoaderTest, DeeplyNestedValueIsQuotedShortly) {
  json deep = json::array();
  for (int i = 0; i < 1'000'000; ++i) {
    json outer = json::array();
    outer.push_back(std::move(deep));
    deep = std::move(outer);
  }
  json doc = full_scene();
  doc["name"] = std::move(deep);
  try {
    load_scene_json(doc, "memory", dir_.string());
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "memory: name: expected a non-empty string, got " + std::string(37, '[') + "...");
  }
}

TEST_F(SceneLoaderTest, NumberBeyondDoubleRangeNamesLineAndColumn) {
  std::string text = full_scene().dump(2);
  const std::string fov = "\"fov\": 35";
  ASSERT_NE(text.find(fov), std::string::npos);
  text.replace(text.find(fov), fov.size(), "\"fov\": 1e400");
  const size_t at = text.find("1e400");
  const size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  const size_t column = at - text.rfind('\n', at) + 4;  // 1-based, at the last digit
  expect_text_error(text,
                    scene_path() + ":" + std::to_string(line) + ":" + std::to_string(column) +
                        ": the number 1e400 is beyond double range; expected a finite number");
}

// nlohmann's parser keeps the last of two equal keys; a scene refuses them, as it refuses
// unknown keys, so that no written value is silently dropped.
TEST_F(SceneLoaderTest, DuplicateKeyIsAnError) {
  expect_text_error("{\n  \"name\": \"a\",\n  \"name\": \"b\"}",
                    scene_path() + ":3:8: the key \"name\" appears twice in one object");
}

TEST_F(SceneLoaderTest, BadInputNamesFilePathAndExpectation) {
  const std::vector<BadCase> cases = {
      {"unknown top-level key", "/camrea", 1, "camrea", "unknown key (allowed keys: name, camera"},
      {"unknown nested key", "/shapes/1/medium/sigma_x", 1, "shapes[1].medium.sigma_x",
       "unknown key"},
      {"unknown transform op",
       "/shapes/0/transform/1",
       {{"shear", 1}},
       "shapes[0].transform[1].shear",
       "unknown key (allowed keys: translate, rotate, scale, matrix)"},
      {"two ops in one",
       "/shapes/0/transform/1",
       {{"scale", 1}, {"translate", {0, 0, 0}}},
       "shapes[0].transform[1]",
       "exactly one of"},
      {"wrong type", "/camera/fov", "wide", "camera.fov",
       "expected a number in (0, 180), got \"wide\""},
      {"fov too large", "/camera/fov", 180, "camera.fov", "expected a number in (0, 180)"},
      {"fov zero", "/camera/fov", 0, "camera.fov", "expected a number in (0, 180)"},
      {"unknown fov axis", "/camera/fov_axis", "sideways", "camera.fov_axis",
       "expected one of: vertical, horizontal, diagonal"},
      {"negative aperture", "/camera/aperture_radius", -1, "camera.aperture_radius",
       "expected a number >= 0, got -1"},
      {"lens beyond the coordinate bound", "/camera/aperture_radius", 1.5e12,
       "camera.aperture_radius", "keeps the lens around the camera position within"},
      {"aperture far wider than the focus distance", "/camera/aperture_radius", 1e7,
       "camera.aperture_radius", "at most 1e+06 times the focus distance"},
      {"zero focus distance", "/camera/focus_distance", 0, "camera.focus_distance",
       "expected a number > 0, got 0"},
      {"focus distance rounding to 0", "/camera/focus_distance", 1e-50, "camera.focus_distance",
       "expected a number > 0"},
      {"zero width", "/camera/resolution/0", 0, "camera.resolution[0]",
       "expected an integer in [1, 32768], got 0"},
      {"fractional height", "/camera/resolution/1", 2.5, "camera.resolution[1]",
       "expected an integer"},
      {"resolution shape",
       "/camera/resolution",
       {64},
       "camera.resolution",
       "an array of 2 elements"},
      {"missing key", "/camera/position", kRemove, "camera", "missing required key 'position'"},
      {"camera at target",
       "/camera/look_at",
       {0, 1, 5},
       "camera.look_at",
       "a point different from the camera position"},
      {"up along view", "/camera/up", {0, 1, 10}, "camera.up", "not parallel"},
      {"negative sigma_s", "/media/0/sigma_s/1", -2, "media[0].sigma_s[1]",
       "expected a number >= 0, got -2"},
      {"negative inline sigma_a",
       "/shapes/1/medium",
       {{"sigma_s", 1}, {"sigma_a", {0, 0, -1}}},
       "shapes[1].medium.sigma_a[2]",
       "expected a number >= 0"},
      {"zero mean free path", "/media/1/mean_free_path", 0, "media[1].mean_free_path",
       "expected a number > 0"},
      {"albedo above one", "/media/1/albedo", 1.5, "media[1].albedo", "a number in [0, 1]"},
      {"both parametrizations", "/media/1/sigma_s", 1, "media[1]",
       "either sigma_s (and optionally sigma_a) or albedo (or albedo_texture) and mean_free_path"},
      {"g of one", "/media/0/g", 1, "media[0].g", "a number in (-1, 1)"},
      {"ior zero", "/materials/0/ior", 0, "materials[0].ior",
       "expected a number in [0.001, 1000], got 0"},
      {"negative ior", "/materials/0/ior", -1.5, "materials[0].ior",
       "expected a number in [0.001, 1000]"},
      {"roughness above one", "/materials/0/roughness", 1.5, "materials[0].roughness",
       "expected a number in [0, 1], got 1.5"},
      {"diffuse albedo",
       "/materials/1/albedo",
       {0.5, 2, 0.5},
       "materials[1].albedo[1]",
       "a number in [0, 1]"},
      {"unknown material type", "/materials/1/type", "metal", "materials[1].type",
       "one of: diffuse, dielectric, null"},
      {"material without name", "/materials/1/name", kRemove, "materials[1]",
       "missing required key 'name'"},
      {"duplicate material", "/materials/1/name", "glass", "materials[1].name",
       "the material name 'glass' is already used by materials[0]"},
      {"duplicate medium", "/media/1/name", "skin", "media[1].name", "already used by media[0]"},
      {"undefined material", "/shapes/0/material", "steel", "shapes[0].material",
       "no material named 'steel' is defined"},
      {"undefined medium", "/shapes/0/medium", "fog", "shapes[0].medium",
       "no medium named 'fog' is defined"},
      {"material of wrong type", "/shapes/0/material", 3, "shapes[0].material",
       "the name of a defined material or an inline definition"},
      {"medium behind diffuse", "/shapes/0/material", "white", "shapes[0].medium",
       "needs a dielectric or null material"},
      {"unknown shape type", "/shapes/0/type", "cube", "shapes[0].type",
       "one of: mesh, sphere, quad"},
      {"missing mesh", "/shapes/0/file", "meshes/missing.obj", "shapes[0].file", "missing.obj"},
      {"missing data mesh", "/shapes/1/file", "data/meshes/missing.ply", "shapes[1].file",
       "missing.ply"},
      {"mesh key on sphere", "/shapes/2/file", "x.obj", "shapes[2].file", "unknown key"},
      {"non-uniform sphere",
       "/shapes/2/transform/0/scale",
       {1, 2, 1},
       "shapes[2].transform",
       "similarity transform"},
      {"zero scale", "/shapes/0/transform/2/scale", 0, "shapes[0].transform[2].scale",
       "a number > 0"},
      {"negative radius", "/shapes/2/radius", -1, "shapes[2].radius", "expected a number > 0"},
      {"bad matrix row",
       "/shapes/3/transform/0/matrix/3",
       {0, 0, 1, 1},
       "shapes[3].transform[0].matrix[3][2]",
       "the last row must be [0, 0, 0, 1]"},
      {"singular matrix",
       "/shapes/3/transform/0/matrix/0",
       {0, 0, 0, 0},
       "shapes[3].transform",
       "not invertible"},
      {"negative emission", "/shapes/3/emission", -1, "shapes[3].emission",
       "a number in [0, 1e+30]"},
      {"quad size", "/shapes/3/size", {4, 0}, "shapes[3].size[1]", "a number > 0"},
      {"zero direction",
       "/lights/0/direction",
       {0, 0, 0},
       "lights[0].direction",
       "a non-zero direction"},
      {"short direction",
       "/lights/0/direction",
       {0, 1},
       "lights[0].direction",
       "an array of 3 numbers"},
      {"cone angle", "/lights/1/half_angle_degrees", 0, "lights[1].half_angle_degrees",
       "a number in (0, 180]"},
      {"unknown light", "/lights/2/type", "area", "lights[2].type", "one of: directional, cone"},
      {"spot at its target",
       "/lights/6/look_at",
       {0, 4, 0},
       "lights[6].look_at",
       "a point different from the light position"},
      {"spot cone angle", "/lights/6/cone_angle_degrees", 190, "lights[6].cone_angle_degrees",
       "a number in (0, 180]"},
      {"spot falloff past the cone", "/lights/6/falloff_start_degrees", 41,
       "lights[6].falloff_start_degrees", "a number in [0, 40]"},
      {"missing image", "/lights/3/file", "missing.exr", "lights[3].file", "missing.exr"},
      {"scaled env rotation",
       "/lights/3/rotation",
       {{{"scale", 2}}},
       "lights[3].rotation",
       "expected a rotation"},
      {"sky with file", "/lights/4/file", "env.exr", "lights[4].file", "unknown key"},
      {"negative intensity",
       "/lights/5/intensity",
       {1, -1, 1},
       "lights[5].intensity[1]",
       "a number in [0, 1e+30]"},
      {"zero spp", "/render/spp", 0, "render.spp", "expected an integer in [1, "},
      {"negative seed", "/render/seed", -1, "render.seed",
       "expected an integer in [0, 4294967295]"},
      {"seed too large", "/render/seed", 4294967296u, "render.seed",
       "expected an integer in [0, 4294967295], got 4294967296"},
      {"empty integrator", "/render/integrator", "", "render.integrator", "a non-empty string"},
      {"negative noise target", "/render/noise_target", -0.1, "render.noise_target",
       "expected a number >= 0"},
      {"noise target not a number", "/render/noise_target", "low", "render.noise_target",
       "expected a number >= 0"},
      {"shapes not a list", "/shapes", {{"type", "sphere"}}, "shapes", "expected an array"},
  };
  expect_errors(cases);
}

// Embree aborts the process on a ray whose origin or direction reaches about 1.8e18, and
// every one of these was accepted and reached it (SIGABRT); within the bound no ray can.
TEST_F(SceneLoaderTest, CoordinatesBeyondTheBoundAreErrors) {
  const std::string bound =
      "is beyond the coordinate bound; expected every world-space "
      "coordinate within +-1e+12";
  const std::vector<std::pair<double, std::string>> values = {{1e19, "1e+19"}, {1e38, "1e+38"}};
  for (const auto& [far, printed] : values) {
    SCOPED_TRACE(far);
    expect_errors({
        {"camera position", "/camera/position/0", far, "camera.position",
         "the camera position (" + printed + ", 1, 5)"},
        {"camera position bound", "/camera/position/0", far, "camera.position", bound},
        {"look_at", "/camera/look_at/2", -far, "camera.look_at", "the look_at point"},
        {"sphere centre", "/shapes/2/center/1", far, "shapes[2]",
         "reaches beyond the coordinate bound"},
        {"sphere radius", "/shapes/2/radius", far, "shapes[2]",
         "reaches beyond the coordinate bound"},
        {"sphere scale", "/shapes/2/transform/0/scale", far, "shapes[2]",
         "reaches beyond the coordinate bound"},
        {"mesh translate", "/shapes/0/transform/0/translate/1", far, "shapes[0]",
         "vertex 0 of " + (dir_ / "meshes" / "cube.obj").string() + ", after the transform at"},
        {"mesh scale", "/shapes/0/transform/2/scale", far, "shapes[0]", bound},
        {"normalized mesh scale", "/shapes/1/transform", {{{"scale", far}}}, "shapes[1]", bound},
        {"matrix entry", "/shapes/3/transform/0/matrix/2/3", far, "shapes[3]",
         "vertex 0 of the quad, after the transform at (-2, -1, " + printed + ")"},
        {"matrix scale", "/shapes/3/transform/0/matrix/0/0", far, "shapes[3]", bound},
        {"quad size (an area light)", "/shapes/3/size/0", far, "shapes[3]", bound},
        {"point light", "/lights/5/position/2", far, "lights[5].position", "the light position"},
    });
  }
  // The bound itself is allowed, and so is a sphere touching it.
  json doc = full_scene();
  doc["camera"]["position"] = {1e12, -1e12, 1e12};
  doc["shapes"][2]["transform"] = {{{"translate", {0, 0, 1e12 - 1e6}}}};
  doc["shapes"][2]["radius"] = 1e6 / 2;  // scaled by 2
  EXPECT_EQ(load(doc).scene.camera.position, Vec3(1e12f, -1e12f, 1e12f));
}

// The checks apply to the world-space result: an object far out and a transform bringing it
// back is fine, and a transform too large for float is its own error.
TEST_F(SceneLoaderTest, CoordinateBoundAppliesAfterTheTransform) {
  json doc = full_scene();
  doc["shapes"][2]["center"] = {0, 1e15, 0};
  doc["shapes"][2]["radius"] = 1e14;
  doc["shapes"][2]["transform"] = {{{"scale", 1e-6}}};
  const Shape sphere = load(doc).scene.shapes[2];
  EXPECT_FLOAT_EQ(sphere.center.y, 1e9f);
  EXPECT_FLOAT_EQ(sphere.radius, 1e8f);
  expect_errors({{"overflowing transform",
                  "/shapes/3/transform",
                  {{{"scale", 3e38}}, {{"scale", 3e38}}},
                  "shapes[3].transform",
                  "the combined transform has entries beyond single-precision range"}});
}

// Every number is checked as the float the program computes with, and so is every
// coefficient derived from several of them.
TEST_F(SceneLoaderTest, NumbersAreCheckedInSinglePrecision) {
  expect_errors({
      // 0.99999999 lies in (-1, 1) as a double but is 1 as a float.
      {"g rounding to 1", "/media/0/g", 0.99999999, "media[0].g",
       "expected a number in (-1, 1) in single precision, where it is 1, got 0.99999999"},
      {"g rounding to -1", "/media/0/g", -0.99999999, "media[0].g", "where it is -1"},
      {"fov rounding to 180", "/camera/fov", 179.999999, "camera.fov", "where it is 180"},
      {"subnormal fov", "/camera/fov", 1e-45, "camera.fov",
       "whose half-angle tangent is positive in single precision"},
      {"mean free path rounding to 0", "/media/1/mean_free_path", 1e-50, "media[1].mean_free_path",
       "a number > 0 in single precision, where it is 0"},
      {"scale rounding to 0", "/shapes/0/transform/2/scale", 1e-50, "shapes[0].transform[2].scale",
       "where it is 0"},
      // 1 / 1e-39 overflows; times albedo 0 it was NaN, and the medium rendered as vacuum.
      {"sigma_t overflowing",
       "/media/1",
       {{"name", "milk"}, {"albedo", 0}, {"mean_free_path", 1e-39}},
       "media[1].mean_free_path",
       "mean free paths whose inverse (sigma_t) is finite in single precision"},
      {"sigma_s + sigma_a overflowing",
       "/media/0",
       {{"name", "skin"}, {"sigma_s", 3e38}, {"sigma_a", {0, 3e38, 0}}},
       "media[0]",
       "sigma_s + sigma_a (3e+38, inf, 3e+38) is beyond single-precision range"},
      {"ior too small", "/materials/0/ior", 1e-5, "materials[0].ior",
       "expected a number in [0.001, 1000]"},
      // cos(0.001 degrees) is 1 in float: a cone of no solid angle gave no light.
      {"cone without solid angle", "/lights/1/half_angle_degrees", 0.001,
       "lights[1].half_angle_degrees", "whose cosine is below 1 in single precision"},
      // env.exr's brightest pixel is 12: the radiance is beyond kMaxBrightness, or overflows.
      {"env scale too bright", "/lights/3/scale", 1e29, "lights[3].scale",
       "a scale whose product with the image's brightest pixel (10, 11, 12) is at most 1e30"},
      {"env scale beyond the bound", "/lights/3/scale", 1e38, "lights[3].scale",
       "a number in [0, 1e+30]"},
      // Lights beyond kMaxBrightness only ever gave non-finite samples.
      {"emission too bright", "/shapes/3/emission", 2e30, "shapes[3].emission",
       "a number in [0, 1e+30]"},
      {"irradiance too bright",
       "/lights/0/irradiance",
       {1, 3e38, 1},
       "lights[0].irradiance[1]",
       "a number in [0, 1e+30]"},
      {"cone radiance too bright", "/lights/1/radiance", 1e31, "lights[1].radiance",
       "a number in [0, 1e+30]"},
      {"point intensity too bright", "/lights/5/intensity", 1e31, "lights[5].intensity",
       "a number in [0, 1e+30]"},
      {"look_at at a subnormal distance",
       "/camera/look_at",
       {0, 1, 5 + 1e-30},
       "camera.look_at",
       "far enough from it (about 1e-19) to give a viewing direction"},
  });
}

// Directions are scaled before normalizing: [3e38, 3e38, 3e38] used to normalize to 0 (its
// squared length overflows), so the light gave nothing; [1e-30, 0, 0] to NaN.
TEST_F(SceneLoaderTest, ExtremeDirectionsNormalize) {
  json doc = full_scene();
  doc["lights"][0]["direction"] = {3e38, 3e38, 3e38};
  doc["lights"][1]["direction"] = {-1e-30, 0, 0};
  doc["camera"]["up"] = {0, 3e38, 0};
  doc["lights"][3]["rotation"] = {{{"rotate", {{"axis", {0, 3e38, 0}}, {"degrees", 90}}}}};
  const LoadedScene loaded = load(doc);
  const Scene& scene = loaded.scene;
  const float third = 1 / std::sqrt(3.0f);
  EXPECT_NEAR(scene.lights[0].direction.x, third, 1e-6f);
  EXPECT_NEAR(scene.lights[0].direction.y, third, 1e-6f);
  EXPECT_NEAR(scene.lights[0].direction.z, third, 1e-6f);
  EXPECT_EQ(scene.lights[1].direction, Vec3(-1, 0, 0));
  EXPECT_EQ(scene.camera.up, Vec3(0, 1, 0));
  // The rotation about +y by 90 degrees takes +x to -z.
  const Vec3 x = scene.lights[3].env_rotation.vector(Vec3(1, 0, 0));
  EXPECT_NEAR(x.z, -1.0f, 1e-6f);
  EXPECT_NEAR(length(x), 1.0f, 1e-6f);
  expect_round_trip(loaded, scene_path());
}

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
// counts as closed, and "shading" chooses between its normals and its triangles'.
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
