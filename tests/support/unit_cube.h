// A closed mesh small enough to write out by hand, for tests of meshes and of volumes.
#pragma once

#include "scene/scene.h"

namespace snee::test {

// The cube [0,1]^3 with outward (counter-clockwise from outside) winding.
inline TriangleMesh unit_cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.positions.push_back(Vec3(static_cast<float>(i & 1), static_cast<float>((i >> 1) & 1),
                               static_cast<float>((i >> 2) & 1)));
  }
  m.indices = {0, 2, 3, 0, 3, 1,   // z = 0, normal -z
               4, 5, 7, 4, 7, 6,   // z = 1, normal +z
               0, 1, 5, 0, 5, 4,   // y = 0, normal -y
               2, 6, 7, 2, 7, 3,   // y = 1, normal +y
               0, 4, 6, 0, 6, 2,   // x = 0, normal -x
               1, 3, 7, 1, 7, 5};  // x = 1, normal +x
  return m;
}

}  // namespace snee::test
