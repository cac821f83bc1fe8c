#include "kernels/physics/snee/light_extent.h"

#include <algorithm>
#include <cmath>

#include "scene/shape_bounds.h"

namespace snee {

namespace {

// The centre of the shapes that enclose a medium: where SNEE's vertices are.
Vec3 media_center(const Scene& scene) {
  ShapeBounds media;
  for (const Shape& shape : scene.shapes) {
    if (shape.interior_medium >= 0) media.add(shape);
  }
  return media.empty() ? Vec3(0.0f) : media.center();
}

// The half-angle of the cone from `viewpoint` that holds the shape's bounding sphere (the box's
// centre and half-diagonal): enough to rank a light against a limit of some degrees.
float apparent_half_angle_degrees(const Shape& shape, Vec3 viewpoint) {
  ShapeBounds box;
  box.add(shape);
  const float radius = length(box.hi - box.lo) * 0.5f;
  const float distance = length(box.center() - viewpoint);
  if (!(distance > radius)) return kWholeSkyDegrees;
  return std::asin(radius / distance) * (180.0f / kPi);
}

}  // namespace

float light_half_angle_degrees(const Scene& scene, const Light& light) {
  switch (light.kind) {
    case LightKind::kDirectional:
    case LightKind::kPoint:
    case LightKind::kSpot:
      return 0.0f;
    case LightKind::kCone:
      return light.half_angle * (180.0f / kPi);
    case LightKind::kConstantEnv:
    case LightKind::kEnvMap:
      return kWholeSkyDegrees;
    case LightKind::kArea:
      return apparent_half_angle_degrees(scene.shapes[static_cast<size_t>(light.shape)],
                                         media_center(scene));
  }
  return kWholeSkyDegrees;
}

float smallest_light_half_angle_degrees(const Scene& scene) {
  float smallest = kWholeSkyDegrees;
  for (const Light& light : scene.lights)
    smallest = std::min(smallest, light_half_angle_degrees(scene, light));
  return smallest;
}

float largest_escaped_light_half_angle_degrees(const Scene& scene) {
  float largest = 0.0f;
  for (const Light& light : scene.lights) {
    const bool escaped = light.kind == LightKind::kCone || light.kind == LightKind::kConstantEnv ||
                         light.kind == LightKind::kEnvMap;
    if (escaped) largest = std::max(largest, light_half_angle_degrees(scene, light));
  }
  return largest;
}

}  // namespace snee
