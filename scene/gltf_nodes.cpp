// A glTF asset's node hierarchy: each node's transform, and the camera, lights and meshes it
// places in the world.
#include <algorithm>
#include <cmath>

#include "scene/gltf_model_reader.h"

namespace snee::gltf_reader {

Transform GltfReader::local_transform(const tinygltf::Node& node,
                                      const std::string& element) const {
  Transform t;
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) fail(element + ".matrix", "expected 16 numbers");
    for (int col = 0; col < 4; ++col) {
      for (int row = 0; row < 4; ++row) {
        const double x = node.matrix[4 * col + row];
        if (row < 3) {
          t.m[row][col] = static_cast<float>(x);
        } else if (x != (col == 3 ? 1.0 : 0.0)) {
          fail(element + ".matrix", "expected an affine matrix (last row 0, 0, 0, 1)");
        }
      }
    }
    return t;
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) fail(element + ".scale", "expected 3 numbers");
    t = Transform::scale(Vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                              static_cast<float>(node.scale[2])));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) fail(element + ".rotation", "expected 4 numbers");
    double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double norm = std::sqrt(x * x + y * y + z * z + w * w);
    if (!(norm > 0) || !std::isfinite(norm)) {
      fail(element + ".rotation", "expected a unit quaternion [x, y, z, w]");
    }
    x /= norm, y /= norm, z /= norm, w /= norm;
    Transform r;
    const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r.m[i][j] = static_cast<float>(m[i][j]);
    }
    t = r * t;
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) fail(element + ".translation", "expected 3 numbers");
    t = Transform::translate(Vec3(static_cast<float>(node.translation[0]),
                                  static_cast<float>(node.translation[1]),
                                  static_cast<float>(node.translation[2]))) *
        t;
  }
  return t;
}

void GltfReader::visit_node(int index, const Transform& parent) {
  if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size()) {
    fail("nodes", "a scene or node refers to node " + std::to_string(index) + " but the file has " +
                      std::to_string(model_.nodes.size()));
  }
  const std::string element = indexed("nodes", static_cast<size_t>(index));
  if (visited_[index]) {
    fail(element,
         "is reached twice in the node hierarchy (a glTF node has at most one parent "
         "and no cycles)");
  }
  visited_[index] = true;
  const tinygltf::Node& node = model_.nodes[index];
  const Transform world = parent * local_transform(node, element);
  for (const auto& row : world.m) {
    if (!std::all_of(std::begin(row), std::end(row), [](float x) { return std::isfinite(x); })) {
      fail(element, "the node's world transform has entries beyond single-precision range");
    }
  }
  if (node.mesh >= 0) place_mesh(node, element, world);
  if (node.camera >= 0) place_camera(node, element, world);
  const auto light = node.extensions.find("KHR_lights_punctual");
  if (light != node.extensions.end()) place_light(light->second, element, world);
  for (const int child : node.children) visit_node(child, world);
}

void GltfReader::place_camera(const tinygltf::Node& node, const std::string& element,
                              const Transform& world) {
  if (static_cast<size_t>(node.camera) >= model_.cameras.size()) {
    fail(element + ".camera", "refers to camera " + std::to_string(node.camera) +
                                  " but the file has " + std::to_string(model_.cameras.size()));
  }
  if (asset_.camera) return;
  const std::string camera_element = indexed("cameras", static_cast<size_t>(node.camera));
  const tinygltf::Camera& c = model_.cameras[node.camera];
  if (c.type != "perspective") {
    fail(camera_element, "a '" + c.type + "' camera; snee has only perspective cameras");
  }
  const double fov_degrees = c.perspective.yfov * 180.0 / M_PI;
  if (!(fov_degrees > 0 && fov_degrees < 180)) {
    fail(camera_element + ".perspective.yfov", "expected an angle in (0, pi) radians");
  }
  // A glTF camera looks down its local -z with +y up.
  Camera camera;
  camera.position = world.point(Vec3(0.0f));
  const Vec3 forward = normalize(world.vector(Vec3(0, 0, -1)));
  camera.look_at = camera.position + forward;
  camera.up = normalize(world.vector(Vec3(0, 1, 0)));
  camera.fov_degrees = static_cast<float>(fov_degrees);
  if (!is_finite(forward) || !is_finite(camera.up) ||
      !(length(cross(forward, camera.up)) > 1e-4f)) {
    fail(element, "the node's transform leaves the camera no viewing and up direction");
  }
  asset_.camera = camera;
  asset_.camera_aspect = static_cast<float>(c.perspective.aspectRatio);
}

void GltfReader::place_light(const tinygltf::Value& extension, const std::string& element,
                             const Transform& world) {
  const std::string where = element + ".extensions.KHR_lights_punctual.light";
  if (!extension.Has("light") || !extension.Get("light").IsInt()) {
    fail(where, "expected the index of a light");
  }
  const int index = extension.Get("light").GetNumberAsInt();
  if (index < 0 || static_cast<size_t>(index) >= model_.lights.size()) {
    fail(where, "refers to light " + std::to_string(index) + " but the file has " +
                    std::to_string(model_.lights.size()));
  }
  const std::string light_element =
      indexed("extensions.KHR_lights_punctual.lights", static_cast<size_t>(index));
  const tinygltf::Light& l = model_.lights[index];
  for (size_t i = 0; i < l.color.size(); ++i) {
    check_unit(light_element + ".color[" + std::to_string(i) + "]", l.color[i]);
  }
  if (!(l.intensity >= 0 && l.intensity <= kMaxBrightness)) {
    fail(light_element + ".intensity", "expected a number in [0, 1e30]");
  }
  const Rgb power = factor_rgb(l.color, Rgb(1.0f)) * static_cast<float>(l.intensity);
  Light light;
  if (l.type == "directional") {
    // glTF lights shine down their local -z; snee's direction points toward the light. Lux
    // is irradiance on a surface facing the light.
    light.kind = LightKind::kDirectional;
    light.direction = normalize(world.vector(Vec3(0, 0, 1)));
    light.irradiance = power;
    if (!is_finite(light.direction)) fail(element, "the node's transform has no direction");
  } else if (l.type == "point") {
    // Candela: intensity, as snee's point light takes it. `range` is a hint for culling that
    // glTF lets renderers ignore; snee lights are never cut off.
    light.kind = LightKind::kPoint;
    light.position = world.point(Vec3(0.0f));
    light.intensity = power;
  } else if (l.type == "spot") {
    // Candela on the axis, which is the node's local -z. glTF's cone angles are half-angles
    // from the axis with 0 <= inner < outer <= pi/2; snee's falloff between them is a
    // smoothstep in the cosine (pbrt's), where glTF suggests a squared linear ramp.
    const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
    if (!(outer > 0 && outer <= kPi / 2 + 1e-6)) {
      fail(light_element + ".spot.outerConeAngle", "expected an angle in (0, pi/2]");
    }
    if (!(inner >= 0 && inner < outer)) {
      fail(light_element + ".spot.innerConeAngle", "expected an angle in [0, outerConeAngle)");
    }
    light.kind = LightKind::kSpot;
    light.position = world.point(Vec3(0.0f));
    light.intensity = power;
    light.spot_axis = normalize(world.vector(Vec3(0, 0, -1)));
    light.spot_cos_outer = static_cast<float>(std::cos(outer));
    light.spot_cos_inner = static_cast<float>(std::cos(inner));
    if (!is_finite(light.spot_axis)) fail(element, "the node's transform has no direction");
  } else {
    fail(light_element, "a '" + l.type +
                            "' light; KHR_lights_punctual defines directional, "
                            "point and spot lights");
  }
  asset_.lights.push_back(light);
}

}  // namespace snee::gltf_reader
