// A density field on a regular voxel grid over an axis-aligned box: the shape of a heterogeneous
// medium (Medium::density). The density is constant within each voxel (nearest-voxel lookup, no
// interpolation), so the optical depth of any segment is a finite sum that a voxel walk computes
// exactly (kernels/physics/medium/grid_medium.h); outside the box it is 0.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace snee {

struct DensityGrid {
  int nx = 0, ny = 0, nz = 0;
  Vec3 lo, hi;  // the box the grid fills, in world space
  // nx * ny * nz non-negative finite values, x varying fastest, then y, then z.
  std::vector<float> values;
  float max_value = 0;
  // Where it came from (a .vol file or the scene's JSON path), for messages and the canonical
  // scene.
  std::string source;

  // nx * ny * nz: 0 if an axis has none, UINT64_MAX where the product overflows (a file's
  // header may claim any size, and the count is checked before anything is allocated).
  uint64_t voxel_count() const {
    if (nx < 1 || ny < 1 || nz < 1) return 0;
    const uint64_t slice = static_cast<uint64_t>(nx) * static_cast<uint64_t>(ny);  // < 2^62
    const uint64_t z = static_cast<uint64_t>(nz);
    return slice > UINT64_MAX / z ? UINT64_MAX : slice * z;
  }
  float at(int x, int y, int z) const {
    return values[(static_cast<size_t>(z) * static_cast<size_t>(ny) + static_cast<size_t>(y)) *
                      static_cast<size_t>(nx) +
                  static_cast<size_t>(x)];
  }
  // The density at world point p: its voxel's value, 0 outside the box.
  float density(Vec3 p) const {
    const auto cell = [](float v, float from, float to, int n, int* i) {
      if (!(v >= from && v <= to)) return false;
      *i = std::min(n - 1, static_cast<int>((v - from) / (to - from) * static_cast<float>(n)));
      return true;
    };
    int x = 0, y = 0, z = 0;
    if (!cell(p.x, lo.x, hi.x, nx, &x) || !cell(p.y, lo.y, hi.y, ny, &y) ||
        !cell(p.z, lo.z, hi.z, nz, &z)) {
      return 0.0f;
    }
    return at(x, y, z);
  }
};

}  // namespace snee
