// Bad input to the JSON scene format: every error is a SceneError that names the file, the JSON
// path and what was expected (missing and malformed files, every field's bad values, nesting
// and number limits, the coordinate bound), and extreme but valid values still load.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "tests/support/scene_comparison.h"
#include "tests/support/scene_loader_fixture.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::BadCase;
using test::expect_round_trip;
using test::full_scene;
using test::kRemove;
using test::SceneLoaderTest;

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

}  // namespace
}  // namespace snee
