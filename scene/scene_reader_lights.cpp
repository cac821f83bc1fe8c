// The scene document's lights (point, spot, directional, cone, environment, sky).
#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/procedural_sky.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_reader.h"

namespace snee::scene_reader {

using nlohmann::json;

Transform SceneReader::read_rotation(const JsonValue& value) {
  const Transform rotation = parse_transform(value);
  if (!is_rotation(rotation)) value.fail("expected a rotation (no scale, mirror or translation)");
  return rotation;
}

void SceneReader::read_light(const JsonValue& value) {
  const std::string type = value.member("type").choice(
      {"directional", "cone", "constant", "envmap", "sky", "point", "spot"});
  Light light;
  json canonical = {{"type", type}};
  if (type == "directional") {
    const JsonObject obj = value.object({"type", "direction", "irradiance"});
    light.kind = LightKind::kDirectional;
    const Direction direction = obj.required("direction").direction();
    light.direction = direction.unit;
    if (auto e = obj.optional("irradiance")) light.irradiance = e->rgb(kBrightness);
    canonical["direction"] = to_json(direction.given);
    canonical["irradiance"] = to_json(light.irradiance);
  } else if (type == "cone") {
    const JsonObject obj = value.object({"type", "direction", "half_angle_degrees", "radiance"});
    light.kind = LightKind::kCone;
    const Direction direction = obj.required("direction").direction();
    light.direction = direction.unit;
    const JsonValue half_angle_value = obj.required("half_angle_degrees");
    const float half_angle_degrees = half_angle_value.real({0.0, 180.0, true, false});
    light.half_angle = degrees_to_radians(half_angle_degrees);
    // The cone's solid angle is 2 pi (1 - cos(half angle)), in float: below about 0.014
    // degrees the cosine rounds to 1 and the light could neither be hit nor sampled.
    if (!(std::cos(light.half_angle) < 1.0f)) {
      half_angle_value.expected(
          "an angle in (0, 180] whose cosine is below 1 in single precision (at least about "
          "0.014 degrees)");
    }
    if (auto l = obj.optional("radiance")) light.radiance = l->rgb(kBrightness);
    canonical["direction"] = to_json(direction.given);
    canonical["half_angle_degrees"] = half_angle_degrees;
    canonical["radiance"] = to_json(light.radiance);
  } else if (type == "constant") {
    const JsonObject obj = value.object({"type", "radiance"});
    light.kind = LightKind::kConstantEnv;
    if (auto l = obj.optional("radiance")) light.radiance = l->rgb(kBrightness);
    canonical["radiance"] = to_json(light.radiance);
  } else if (type == "envmap" || type == "sky") {
    const JsonObject obj = type == "envmap" ? value.object({"type", "file", "scale", "rotation"})
                                            : value.object({"type", "scale", "rotation"});
    light.kind = LightKind::kEnvMap;
    if (type == "envmap") {
      const JsonValue file_value = obj.required("file");
      const ResolvedPath file = resolve(file_value.string());
      try {
        out_.scene.env_images.push_back(read_env_image(file.file, budget_));
      } catch (const SceneError& e) {
        file_value.fail(e.what());
      }
      canonical["file"] = file.canonical;
    } else {
      out_.scene.env_images.push_back(make_soft_sky(kSkyWidth, kSkyHeight));
    }
    light.env_image = static_cast<int>(out_.scene.env_images.size() - 1);
    const std::optional<JsonValue> scale = obj.optional("scale");
    if (scale) light.radiance = scale->rgb(kBrightness);
    check_scaled_image(out_.scene.env_images.back(), light.radiance, scale ? *scale : value);
    if (auto rotation = obj.optional("rotation")) light.env_rotation = read_rotation(*rotation);
    canonical["scale"] = to_json(light.radiance);
    canonical["rotation"] = to_json(light.env_rotation);
  } else if (type == "spot") {
    read_spot(value, light, canonical);
  } else {
    const JsonObject obj = value.object({"type", "position", "intensity"});
    light.kind = LightKind::kPoint;
    light.position = read_point(obj.required("position"), "the light position");
    if (auto i = obj.optional("intensity")) light.intensity = i->rgb(kBrightness);
    canonical["position"] = to_json(light.position);
    canonical["intensity"] = to_json(light.intensity);
  }
  canonical_lights_.push_back(canonical);
  out_.scene.lights.push_back(light);
}

void SceneReader::read_spot(const JsonValue& value, Light& light, json& canonical) {
  const JsonObject obj = value.object(
      {"type", "position", "look_at", "intensity", "cone_angle_degrees", "falloff_start_degrees"});
  light.kind = LightKind::kSpot;
  light.position = read_point(obj.required("position"), "the light position");
  const JsonValue look_at_value = obj.required("look_at");
  const Vec3 look_at = read_point(look_at_value, "the look_at point");
  light.spot_axis =
      direction_to_target(light.position, look_at, look_at_value, "the light position", "an axis");
  if (auto i = obj.optional("intensity")) light.intensity = i->rgb(kBrightness);
  float cone_degrees = 30.0f;
  if (auto cone = obj.optional("cone_angle_degrees")) {
    cone_degrees = cone->real({0.0, 180.0, true, false});
  }
  // pbrt's default: the falloff spans the cone's last 5 degrees.
  float falloff_degrees = std::max(0.0f, cone_degrees - 5.0f);
  if (auto falloff = obj.optional("falloff_start_degrees")) {
    falloff_degrees = falloff->real({0.0, cone_degrees});
  }
  light.spot_cos_outer = std::cos(degrees_to_radians(cone_degrees));
  light.spot_cos_inner = std::cos(degrees_to_radians(falloff_degrees));
  canonical["position"] = to_json(light.position);
  canonical["look_at"] = to_json(look_at);
  canonical["intensity"] = to_json(light.intensity);
  canonical["cone_angle_degrees"] = cone_degrees;
  canonical["falloff_start_degrees"] = falloff_degrees;
}

}  // namespace snee::scene_reader
