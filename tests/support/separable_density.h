// A density grid whose voxel (i, j, k) holds a[i] + b[j] + c[k], for tests of the grid medium:
// its optical depth along a segment is a sum over the slabs of each axis of that slab's term times
// the segment's length inside it, which needs no voxel walk, so it checks one independently.
// The terms are multiples of 1/64 below 2, so every voxel's sum is exact in float.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/density_grid.h"

namespace snee::test {

struct SeparableDensity {
  std::vector<double> a, b, c;  // the x, y and z terms
  Vec3 lo, hi;

  // The grid itself.
  std::shared_ptr<const DensityGrid> grid() const {
    auto g = std::make_shared<DensityGrid>();
    g->nx = static_cast<int>(a.size()), g->ny = static_cast<int>(b.size());
    g->nz = static_cast<int>(c.size());
    g->lo = lo, g->hi = hi;
    for (double ck : c) {
      for (double bj : b) {
        for (double ai : a) {
          g->values.push_back(static_cast<float>(ai + bj + ck));
          g->max_value = std::max(g->max_value, g->values.back());
        }
      }
    }
    g->source = "test";
    return g;
  }

  // The optical depth of x + t w for t in [t0, t1].
  double depth(Vec3 x, Vec3 w, double t0, double t1) const {
    const double o[3] = {x.x, x.y, x.z}, d[3] = {w.x, w.y, w.z};
    const double box_lo[3] = {lo.x, lo.y, lo.z}, box_hi[3] = {hi.x, hi.y, hi.z};
    const std::vector<double>* terms[3] = {&a, &b, &c};
    double total = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<double>& term = *terms[axis];
      const double size = (box_hi[axis] - box_lo[axis]) / static_cast<double>(term.size());
      for (size_t s = 0; s < term.size(); ++s) {
        const double from = box_lo[axis] + size * static_cast<double>(s), to = from + size;
        // The segment inside this slab and inside the box along the two other axes.
        double s0 = t0, s1 = t1;
        for (int other = 0; other < 3; ++other) {
          const double a0 = other == axis ? from : box_lo[other];
          const double a1 = other == axis ? to : box_hi[other];
          if (d[other] == 0) {
            if (o[other] < a0 || o[other] >= a1) s1 = s0;
            continue;
          }
          const double ta = (a0 - o[other]) / d[other], tb = (a1 - o[other]) / d[other];
          s0 = std::max(s0, std::min(ta, tb));
          s1 = std::min(s1, std::max(ta, tb));
        }
        if (s1 > s0) total += term[s] * (s1 - s0);
      }
    }
    return total;
  }
};

}  // namespace snee::test
