// Where a scene's volumes (closed shapes that refract or hold a medium) meet other shapes. A
// path carries one medium at a time: crossing a boundary inward enters that shape's medium,
// crossing it outward returns to vacuum. So a volume that overlaps another or lies inside one
// would be rendered with the wrong medium in the shared part, and an opaque shape inside a
// medium is lit as if it were in vacuum (its shadow rays carry no medium). The loader refuses
// the first and warns of the second (docs/scene-format.md, "Several media").
#pragma once

#include <vector>

#include "scene/scene.h"

namespace snee {

// A closed shape (a sphere or a closed mesh) whose inside differs from the outside: a
// dielectric boundary, or any boundary with an interior medium.
bool is_volume(const Scene& scene, int shape);

struct VolumeContact {
  int volume = -1;      // index into Scene::shapes
  int other = -1;       // another shape that crosses the volume's boundary or lies inside it
  bool inside = false;  // `other` lies wholly inside `volume`, no boundary crossing
};

// Every (volume, other) pair in contact, in shape order; a pair of volumes is reported once,
// with the inner one as `other` when one holds the other. Surfaces closer than a millionth of
// the scene's extent count as apart, so a shape resting on another at a point or along a line
// is no contact. Faces lying flat on each other (two cubes face to face) are not reliably seen:
// give such shapes a gap.
std::vector<VolumeContact> find_volume_contacts(const Scene& scene);

}  // namespace snee
