// A unit icosphere for smooth-shading tests: an icosahedron subdivided `levels` times, its
// vertices on the unit sphere, wound counter-clockwise seen from outside, each normal the
// vertex's direction (smooth) or none (flat). At the corners the shading normal leans from the
// triangle's by up to 20.9 degrees at level 1 (80 triangles), 5.5 at level 3 (1280).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace snee::test {

inline TriangleMesh icosphere(int levels, bool smooth) {
  const float p = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh m;
  for (const Vec3 v : {Vec3(-1, p, 0), Vec3(1, p, 0), Vec3(-1, -p, 0), Vec3(1, -p, 0),
                       Vec3(0, -1, p), Vec3(0, 1, p), Vec3(0, -1, -p), Vec3(0, 1, -p),
                       Vec3(p, 0, -1), Vec3(p, 0, 1), Vec3(-p, 0, -1), Vec3(-p, 0, 1)}) {
    m.positions.push_back(normalize(v));
  }
  m.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] =
          midpoints.try_emplace(key, static_cast<uint32_t>(m.positions.size()));
      if (added) m.positions.push_back(normalize(m.positions[a] + m.positions[b]));
      return it->second;
    };
    std::vector<uint32_t> finer;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      const uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices = std::move(finer);
  }
  if (smooth) m.normals = m.positions;
  return m;
}

}  // namespace snee::test
