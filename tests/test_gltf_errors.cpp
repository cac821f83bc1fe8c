// glTF 2.0 import of bad input: a damaged asset (accessors, primitives, lights, nodes, cameras,
// materials, required extensions) names the file, the element and what was expected; broken
// files and unknown override names are scene errors, never a crash or a different scene.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/gltf_reader.h"
#include "scene/scene_loader.h"
#include "tests/support/gltf_cube.h"
#include "tests/support/scene_error_of.h"

namespace snee {
namespace {

using nlohmann::json;
using test::cube_document;
using test::glb;
using test::GltfTest;

struct BadAsset {
  std::string name;
  std::function<void(json&)> damage;
  std::string element;
  std::string expectation;
};

TEST_F(GltfTest, BadAssetsNameTheFileAndTheElement) {
  const std::vector<BadAsset> cases = {
      {"index past the vertices",
       [](json& d) {
         d["accessors"][3]["bufferView"] = 0;
         d["accessors"][3]["componentType"] = 5125;
       },
       "meshes[0].primitives[0]", "but the primitive has 24 vertices"},
      {"accessor past its view", [](json& d) { d["accessors"][0]["count"] = 25; }, "accessors[0]",
       "reach past the end of bufferViews[0]"},
      {"positions of the wrong type", [](json& d) { d["accessors"][0]["type"] = "VEC2"; },
       "accessors[0]", "POSITION needs VEC3 of FLOAT"},
      {"normals that do not match the positions", [](json& d) { d["accessors"][1]["count"] = 23; },
       "meshes[0].primitives[0]", "NORMAL has 23 elements, POSITION 24"},
      {"triangle strips", [](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 5; },
       "meshes[0].primitives[0]", "snee reads triangle lists"},
      {"a spot cone wider than a hemisphere",
       [](json& d) {
         d["extensions"]["KHR_lights_punctual"]["lights"][1] = {
             {"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}};
       },
       "extensions.KHR_lights_punctual.lights[1].spot.outerConeAngle", "(0, pi/2]"},
      {"a spot falloff starting past its cone",
       [](json& d) {
         d["extensions"]["KHR_lights_punctual"]["lights"][1] = {
             {"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}};
       },
       "extensions.KHR_lights_punctual.lights[1].spot.innerConeAngle", "[0, outerConeAngle)"},
      {"an unknown light type",
       [](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"][1]["type"] = "area"; },
       "extensions.KHR_lights_punctual.lights[1]", "directional, point and spot"},
      {"a node cycle", [](json& d) { d["nodes"][1]["children"] = {0}; }, "nodes[0]",
       "reached twice"},
      {"an orthographic camera",
       [](json& d) {
         d["cameras"][0] = {
             {"type", "orthographic"},
             {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 2}, {"znear", 1}}}};
       },
       "cameras[0]", "only perspective cameras"},
      {"an ior below 1",
       [](json& d) { d["materials"][0]["extensions"]["KHR_materials_ior"]["ior"] = 0.5; },
       "materials[0].extensions.KHR_materials_ior.ior", "expected a number in [1"},
      {"an unknown required extension",
       [](json& d) { d["extensionsRequired"] = {"KHR_draco_mesh_compression"}; },
       "extensionsRequired", "KHR_draco_mesh_compression"},
  };
  for (const BadAsset& c : cases) {
    json doc = embedded();
    c.damage(doc);
    const std::string path = write_gltf(doc, "bad.gltf");
    const std::string message = test::scene_error_of([&] { load_gltf(path, Transform()); });
    EXPECT_NE(message.find(path + ": " + c.element + ": "), std::string::npos)
        << c.name << ": " << message;
    EXPECT_NE(message.find(c.expectation), std::string::npos) << c.name << ": " << message;
  }
}

TEST_F(GltfTest, BrokenFilesAreSceneErrors) {
  const std::string truncated =
      write("short.glb", glb(cube_document(cube_, ""), cube_.bytes).substr(0, 40));
  EXPECT_NE(test::scene_error_of([&] {
              load_gltf(truncated, Transform());
            }).find(truncated + ": cannot read glTF binary (.glb) file"),
            std::string::npos);
  const std::string missing_bin = write_gltf(cube_document(cube_, "absent.bin"));
  EXPECT_NE(test::scene_error_of([&] { load_gltf(missing_bin, Transform()); }).find("absent.bin"),
            std::string::npos);
}

TEST_F(GltfTest, UnknownOverrideNameIsAnError) {
  write_gltf(embedded());
  const json doc = {{"include", {{{"file", "cube.gltf"}, {"materials", {{"jaed", "x"}}}}}}};
  const std::string path = write("scene.json", doc.dump());
  const std::string message = test::scene_error_of([&] { load_scene(path); });
  EXPECT_NE(message.find("include[0].materials.jaed: the glTF file"), std::string::npos) << message;
  EXPECT_NE(message.find("has no material named 'jaed' (it has 'jade')"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace snee
