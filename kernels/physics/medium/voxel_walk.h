// Walking a ray through a density grid voxel by voxel (a 3-D DDA: each step crosses the nearest
// voxel face), which is what makes a piecewise-constant grid's optical depth exact: it is the sum
// of density times length over the voxels the segment crosses (docs/method.md 4.8). The walk is
// done in double so the boundaries between voxels sit where the grid puts them to well below a
// float's rounding of the ray's points; it visits at most nx + ny + nz voxels and stops at the
// first NaN (which fails every comparison).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/density_grid.h"

namespace snee {

// Calls visit(t0, t1, density) for each voxel the ray x + t w crosses with t in [0, t_max), in
// order, while visit returns true.
template <class Visit>
void walk_voxels(const DensityGrid& grid, Vec3 x, Vec3 w, double t_max, Visit&& visit) {
  const double origin[3] = {x.x, x.y, x.z}, dir[3] = {w.x, w.y, w.z};
  const double lo[3] = {grid.lo.x, grid.lo.y, grid.lo.z};
  const double hi[3] = {grid.hi.x, grid.hi.y, grid.hi.z};
  const int n[3] = {grid.nx, grid.ny, grid.nz};
  double t_enter = 0, t_exit = t_max;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0) {
      if (!(origin[a] >= lo[a] && origin[a] <= hi[a])) return;
      continue;
    }
    const double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
    t_enter = std::max(t_enter, std::min(ta, tb));
    t_exit = std::min(t_exit, std::max(ta, tb));
  }
  if (!(t_enter < t_exit)) return;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  int cell[3], step[3];
  double t_next[3], t_delta[3];
  for (int a = 0; a < 3; ++a) {
    const double size = (hi[a] - lo[a]) / n[a];
    const double entry = origin[a] + dir[a] * t_enter;
    cell[a] = std::clamp(static_cast<int>(std::floor((entry - lo[a]) / size)), 0, n[a] - 1);
    if (dir[a] > 0) {
      step[a] = 1;
      t_next[a] = (lo[a] + (cell[a] + 1) * size - origin[a]) / dir[a];
      t_delta[a] = size / dir[a];
    } else if (dir[a] < 0) {
      step[a] = -1;
      t_next[a] = (lo[a] + cell[a] * size - origin[a]) / dir[a];
      t_delta[a] = -size / dir[a];
    } else {
      step[a] = 0;
      t_next[a] = kNever;
      t_delta[a] = kNever;
    }
  }
  double t = t_enter;
  for (;;) {
    const int a =
        t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const double t1 = std::min(t_next[a], t_exit);
    // Rounding can leave the entry voxel's far face a hair before t_enter: nothing to visit.
    if (t1 > t && !visit(t, t1, grid.at(cell[0], cell[1], cell[2]))) return;
    if (!(t_next[a] < t_exit)) return;
    t = std::max(t, t1);
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] >= n[a]) return;
    t_next[a] += t_delta[a];
  }
}

// The integral of the density over the segment from x to x + t w.
inline double optical_depth(const DensityGrid& grid, Vec3 x, Vec3 w, double t) {
  double depth = 0;
  walk_voxels(grid, x, w, t, [&](double t0, double t1, float density) {
    depth += static_cast<double>(density) * (t1 - t0);
    return true;
  });
  return depth;
}

// The distance along the ray x + t w at which the integral of the density reaches `depth`, or
// +inf if it never does (the ray leaves the grid first, or depth is +inf).
inline double distance_to_depth(const DensityGrid& grid, Vec3 x, Vec3 w, double depth) {
  double accumulated = 0;
  double found = std::numeric_limits<double>::infinity();
  if (!(depth < found)) return found;
  walk_voxels(grid, x, w, found, [&](double t0, double t1, float density) {
    const double here = static_cast<double>(density) * (t1 - t0);
    if (density > 0 && accumulated + here >= depth) {
      found = std::min(t1, t0 + (depth - accumulated) / static_cast<double>(density));
      return false;
    }
    accumulated += here;
    return true;
  });
  return found;
}

}  // namespace snee
