// Built-in scenes, written as the same JSON documents a user would write (so they go through
// the one loader and `canonical` shows each of them as a file), except for the procedural sky.
//
// The test grid follows the SNEE paper's results figure (docs/method.md sections 1.1 and 6): a
// unit-size translucent object behind a dielectric of IOR 1.5 with GGX roughness 0.2, 0.04 or
// smooth, under a directional light, a cone light of 2.67 degrees half-angle (about 100x the
// sun's solid angle) with the same irradiance, or a low-frequency environment. The paper does
// not state its medium; ours is in the range its authors' open question Q16 suggests.
#include <cmath>
#include <functional>
#include <string>

#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "scene/scene_loader.h"

namespace snee {

namespace {

using nlohmann::json;

constexpr double kGridIrradiance = 3.0;
constexpr double kConeHalfAngleDegrees = 2.67;
constexpr std::string_view kBunnyFile = "data/meshes/bunny-npm.obj";

// Toward the light: above, in front of the object (the camera is on +z) and to the left.
json key_light_direction() {
  return json::array({-0.45, 0.75, 0.5});
}

// Radiance of a cone light whose irradiance on a surface facing it is `irradiance`:
// E = L * 2 pi (1 - cos(theta)).
double cone_radiance(double irradiance, double half_angle_degrees) {
  const double theta = half_angle_degrees * 3.14159265358979323846 / 180.0;
  return irradiance / (2.0 * 3.14159265358979323846 * (1.0 - std::cos(theta)));
}

json object_shape(const std::string& object, json material, json medium) {
  json shape = {{"material", std::move(material)}, {"medium", std::move(medium)}};
  if (object == "sphere") {
    shape["type"] = "sphere";
  } else {
    shape["type"] = "mesh";
    shape["file"] = kBunnyFile;
    shape["normalize"] = true;
  }
  return shape;
}

// The object of radius 1 at the origin fills about 60% of the frame height.
json object_camera(int resolution) {
  return {{"position", {0.0, 1.2, 6.2}},
          {"look_at", {0.0, 0.0, 0.0}},
          {"fov", 30.0},
          {"resolution", {resolution, resolution}}};
}

json grid_scene(const std::string& object, const std::string& light, const std::string& surface) {
  const double roughness = surface == "smooth" ? 0.0 : std::stod(surface.substr(1));
  json lights;
  if (light == "directional") {
    lights = {{{"type", "directional"},
               {"direction", key_light_direction()},
               {"irradiance", kGridIrradiance}}};
  } else if (light == "cone") {
    lights = {{{"type", "cone"},
               {"direction", key_light_direction()},
               {"half_angle_degrees", kConeHalfAngleDegrees},
               {"radiance", cone_radiance(kGridIrradiance, kConeHalfAngleDegrees)}}};
  } else {
    lights = {{{"type", "sky"}}};
  }
  // Optically a few mean free paths across, nearly white, slightly bluer deeper in.
  const json medium = {{"name", "grid-medium"},
                       {"sigma_s", {4.0, 5.0, 6.0}},
                       {"sigma_a", {0.12, 0.1, 0.08}},
                       {"g", 0.0}};
  const json interface = {
      {"name", "interface"}, {"type", "dielectric"}, {"ior", 1.5}, {"roughness", roughness}};
  return {{"name", object + "-" + light + "-" + surface},
          {"camera", object_camera(128)},
          {"render", {{"spp", 64}}},
          {"materials", {interface}},
          {"media", {medium}},
          {"shapes", {object_shape(object, "interface", "grid-medium")}},
          {"lights", lights}};
}

// White furnace: a non-absorbing medium under uniform unit radiance must look uniformly 1.
json furnace_scene(const std::string& name, const std::string& object, bool index_matched) {
  const json interface = index_matched
                             ? json{{"type", "null"}}
                             : json{{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.0}};
  const json medium = {{"sigma_s", 2.0}, {"sigma_a", 0.0}, {"g", 0.0}};
  return {{"name", name},
          {"camera", object_camera(64)},
          {"render", {{"spp", 64}}},
          {"shapes", {object_shape(object, interface, medium)}},
          {"lights", {{{"type", "constant"}, {"radiance", 1.0}}}}};
}

// What snee is for: a jade-like bunny lit from behind and to the left by a small cone light,
// so most of what the camera sees has crossed the rough boundary twice, against a dim sky and a
// dark floor. It renders with `snee` to a noise target (docs/budgets.md). The floor height comes
// from the normalized bunny itself so the bunny stands on it rather than floating or sinking.
json default_scene() {
  TriangleMesh bunny = load_mesh(std::string(SNEE_DATA_DIR) + "/meshes/bunny-npm.obj");
  apply_transform(normalizing_transform(bunny), bunny);
  float floor_y = kInfinity;
  for (const Vec3& p : bunny.positions) floor_y = std::min(floor_y, p.y);

  const double key_half_angle = 6.0;
  return {{"name", "default"},
          {"camera",
           {{"position", {0.4, 0.9, 4.3}},
            {"look_at", {0.0, floor_y + 0.55, 0.0}},
            {"fov", 32.0},
            {"resolution", {320, 240}}}},
          {"render", {{"spp", 256}, {"integrator", "snee"}, {"noise_target", 0.05}}},
          {"materials",
           {{{"name", "jade-surface"}, {"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.25}},
            {{"name", "floor"}, {"type", "diffuse"}, {"albedo", {0.2, 0.19, 0.18}}}}},
          {"media",
           {{{"name", "jade"},
             {"sigma_s", {8.0, 9.5, 8.5}},
             {"sigma_a", {0.4, 0.1, 0.3}},
             {"g", 0.2}}}},
          {"shapes",
           {object_shape("bunny", "jade-surface", "jade"),
            {{"type", "quad"},
             {"size", 200.0},
             {"material", "floor"},
             {"transform", {{{"translate", {0.0, floor_y, 0.0}}}}}}}},
          {"lights",
           {{{"type", "sky"}, {"scale", 0.06}},
            {{"type", "cone"},
             {"direction", {-0.7, 0.45, -0.55}},
             {"half_angle_degrees", key_half_angle},
             {"radiance", cone_radiance(kGridIrradiance, key_half_angle)}}}}};
}

struct BuiltinScene {
  BuiltinSceneInfo info;
  std::function<json()> document;
};

std::vector<BuiltinScene> all_builtin_scenes() {
  std::vector<BuiltinScene> scenes;
  scenes.push_back(
      {{"default",
        "jade-like bunny (rough dielectric 0.25) back-lit by a 6-degree cone key light "
        "on a dark floor under a dim sky; snee to noise target 0.05, at most 256 "
        "spp; 320x240"},
       default_scene});
  const char* const kObjects[] = {"sphere", "bunny"};
  const char* const kLights[] = {"directional", "cone", "env"};
  const char* const kSurfaces[] = {"r0.2", "r0.04", "smooth"};
  for (const char* object : kObjects) {
    for (const char* light : kLights) {
      for (const char* surface : kSurfaces) {
        const std::string name = std::string(object) + "-" + light + "-" + surface;
        const std::string light_text =
            std::string(light) == "directional" ? "a directional light (irradiance 3)"
            : std::string(light) == "cone"      ? "a 2.67-degree cone light (irradiance 3)"
                                                : "a low-frequency procedural sky";
        const std::string surface_text = std::string(surface) == "smooth"
                                             ? "smooth dielectric"
                                             : std::string("GGX roughness ") + (surface + 1);
        scenes.push_back(
            {{name, std::string("SNEE test grid: translucent ") + object + " (IOR 1.5, " +
                        surface_text + ") under " + light_text + "; 128x128"},
             [=] { return grid_scene(object, light, surface); }});
      }
    }
  }
  scenes.push_back({{"furnace-sphere",
                     "white furnace: albedo-1 medium in a smooth IOR-1.5 sphere under constant "
                     "radiance 1; the image must be 1 everywhere"},
                    [] { return furnace_scene("furnace-sphere", "sphere", false); }});
  scenes.push_back({{"furnace-bunny",
                     "white furnace: albedo-1 medium in a smooth IOR-1.5 bunny under constant "
                     "radiance 1; the image must be 1 everywhere"},
                    [] { return furnace_scene("furnace-bunny", "bunny", false); }});
  scenes.push_back({{"furnace-sphere-null",
                     "white furnace with an index-matched (null) sphere boundary; the image "
                     "must be 1 everywhere"},
                    [] { return furnace_scene("furnace-sphere-null", "sphere", true); }});
  return scenes;
}

}  // namespace

std::vector<BuiltinSceneInfo> builtin_scenes() {
  std::vector<BuiltinSceneInfo> infos;
  for (const BuiltinScene& scene : all_builtin_scenes()) infos.push_back(scene.info);
  return infos;
}

LoadedScene load_builtin_scene(const std::string& name) {
  for (const BuiltinScene& scene : all_builtin_scenes()) {
    if (scene.info.name == name) {
      return load_scene_json(scene.document(), "builtin:" + name, SNEE_DATA_DIR);
    }
  }
  std::string known;
  for (const BuiltinScene& scene : all_builtin_scenes()) known += " " + scene.info.name;
  throw SceneError("builtin:" + name + ": no built-in scene of that name (known:" + known + ")");
}

}  // namespace snee
