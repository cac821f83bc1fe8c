// The axis-aligned box around shapes, for the estimates that need to know where the objects are
// and how large they are (a light's power, how large a light looks from the objects).
#pragma once

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

}  // namespace snee
