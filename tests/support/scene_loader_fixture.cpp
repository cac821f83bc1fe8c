#include "tests/support/scene_loader_fixture.h"

#include <OpenImageIO/imageio.h>

#include <fstream>

#include "tests/support/test_directory.h"

namespace snee::test {

namespace fs = std::filesystem;
using nlohmann::json;

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

void SceneLoaderTest::SetUp() {
  dir_ = test::fresh_test_directory("test_scene_loader");
  fs::create_directories(dir_ / "meshes");
  std::ofstream(dir_ / "meshes" / "cube.obj") << kInsideOutCubeObj;
  std::ofstream(dir_ / "meshes" / "square.obj") << kOpenSquareObj;
  write_env_exr();
}

void SceneLoaderTest::TearDown() {
  fs::remove_all(dir_);
}

void SceneLoaderTest::write_env_exr() {
  const std::string path = (dir_ / "env.exr").string();
  const std::vector<float> pixels = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12,
                                     0, 0, 0, 1, 1, 1, 2, 2, 2, 3,  3,  3};
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(path, OIIO::ImageSpec(4, 2, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
}

LoadedScene SceneLoaderTest::load_text(const std::string& text) {
  std::ofstream(scene_path()) << text;
  return load_scene_file(scene_path());
}

void SceneLoaderTest::expect_error(const json& doc, const std::string& path,
                                   const std::string& expectation) {
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

void SceneLoaderTest::expect_errors(const std::vector<BadCase>& cases) {
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

void SceneLoaderTest::expect_text_error(const std::string& text, const std::string& expected) {
  try {
    load_text(text);
    ADD_FAILURE() << "no SceneError; expected " << expected;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

}  // namespace snee::test
