// The axis-aligned box around shapes, for the estimates that need to know where the objects are
// and how large they are (a light's power, how large a light looks from the objects, the ray
// clearance).
#pragma once

#include <algorithm>
#include <limits>

#include "scene/scene.h"

namespace snee {

struct ShapeBounds {
  Vec3 lo{kInfinity};
  Vec3 hi{-kInfinity};

  void add(const Shape& shape) {
    if (shape.kind == ShapeKind::kSphere) {
      lo = vmin(lo, shape.center - Vec3(shape.radius));
      hi = vmax(hi, shape.center + Vec3(shape.radius));
      return;
    }
    for (const Vec3& p : shape.mesh.positions) {
      lo = vmin(lo, p);
      hi = vmax(hi, p);
    }
  }
  bool empty() const { return !(lo.x <= hi.x); }
  Vec3 center() const { return (lo + hi) * 0.5f; }
};

// Ray-origin clearance in units of float epsilon times the scene's extent (ray_clearance).
inline constexpr float kClearanceUlps = 4.0f;

// How far ray origins keep from the surfaces they leave, and scattering points from a boundary:
// kClearanceUlps float epsilons of the scene's extent, the largest coordinate magnitude or edge
// of the box around every shape, which bounds the rounding error of any point on a surface.
inline float ray_clearance(const Scene& scene) {
  ShapeBounds box;
  for (const Shape& shape : scene.shapes) box.add(shape);
  if (box.empty()) box.lo = box.hi = Vec3(0.0f);
  const float extent = max_component(vmax(vmax(box.hi, -box.lo), box.hi - box.lo));
  return kClearanceUlps * std::numeric_limits<float>::epsilon() *
         std::max(extent, std::numeric_limits<float>::min());
}

}  // namespace snee
