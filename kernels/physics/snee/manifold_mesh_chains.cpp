#include "kernels/physics/snee/manifold_mesh_chains.h"

#include <algorithm>
#include <cmath>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "scene/memory_budget.h"

namespace snee {

namespace {

// A convex polygon: a beam's cross-section where it leaves a facet. Each clip adds at most one
// corner to the triangle it starts as; landing on a facet clips four times, and a crossing
// level lands twice.
constexpr int kMaxCorners = 3 + 8 * kMaxMeshChainLevels;
struct Polygon {
  std::array<Vec3d, kMaxCorners> corner;
  int count = 0;
};

// The part of a convex polygon where dot(m, p) >= c (Sutherland-Hodgman, one plane).
Polygon clip(const Polygon& polygon, const Vec3d& m, double c) {
  Polygon out;
  const int n = polygon.count;
  for (int i = 0; i < n; ++i) {
    const Vec3d& a = polygon.corner[static_cast<size_t>(i)];
    const Vec3d& b = polygon.corner[static_cast<size_t>((i + 1) % n)];
    const double da = dot(m, a) - c, db = dot(m, b) - c;
    if (da >= 0) out.corner[static_cast<size_t>(out.count++)] = a;
    // A corner on the plane is kept once, not again as a crossing of its own edge.
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      out.corner[static_cast<size_t>(out.count++)] = a + (da / (da - db)) * (b - a);
    }
  }
  return out;
}

double polygon_area(const Polygon& polygon) {
  Vec3d sum{};
  for (int i = 1; i + 1 < polygon.count; ++i) {
    sum = sum + cross(polygon.corner[static_cast<size_t>(i)] - polygon.corner[0],
                      polygon.corner[static_cast<size_t>(i + 1)] - polygon.corner[0]);
  }
  return 0.5 * length(sum);
}

// One level's cross-sections, their corners stored one after another.
struct Regions {
  std::vector<Vec3d> corners;
  std::vector<uint32_t> first{0};
  void add(const Polygon& polygon) {
    corners.insert(corners.end(), polygon.corner.begin(), polygon.corner.begin() + polygon.count);
    first.push_back(static_cast<uint32_t>(corners.size()));
  }
  Polygon operator[](size_t i) const {
    Polygon p;
    for (uint32_t c = first[i]; c < first[i + 1]; ++c)
      p.corner[static_cast<size_t>(p.count++)] = corners[c];
    return p;
  }
};

// A bounding-box tree over the facets, to find the facets a beam may reach: a beam's
// cross-section, projected along its direction, must overlap a node's projected box, and the
// box must reach ahead of the beam's start.
class FacetBoxTree {
 public:
  explicit FacetBoxTree(const std::vector<std::array<Vec3d, 3>>& corners) {
    for (const auto& triangle : corners) {
      Box box{triangle[0], triangle[0]};
      for (const Vec3d& p : triangle) {
        box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
        box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
      }
      box_.push_back(box);
    }
    order_.resize(corners.size());
    for (size_t i = 0; i < corners.size(); ++i) order_[i] = static_cast<uint32_t>(i);
    if (!corners.empty()) build(corners, 0, static_cast<uint32_t>(corners.size()));
  }

  // Calls candidate(facet) for each facet whose box may meet the beam from `polygon` along the
  // unit direction d.
  template <class Candidate>
  void for_each_candidate(const Polygon& polygon, const Vec3d& d,
                          const Candidate& candidate) const {
    if (nodes_.empty()) return;
    const Vec3d a =
        normalize(std::abs(d.x) < 0.9 ? cross(d, Vec3d(1, 0, 0)) : cross(d, Vec3d(0, 1, 0)));
    const Vec3d b = cross(d, a);
    double a_lo = kInfinity, a_hi = -kInfinity, b_lo = kInfinity, b_hi = -kInfinity;
    double start = kInfinity;
    for (int i = 0; i < polygon.count; ++i) {
      const Vec3d& p = polygon.corner[static_cast<size_t>(i)];
      a_lo = std::min(a_lo, dot(a, p));
      a_hi = std::max(a_hi, dot(a, p));
      b_lo = std::min(b_lo, dot(b, p));
      b_hi = std::max(b_hi, dot(b, p));
      start = std::min(start, dot(d, p));
    }
    // A box projected on an axis: its centre's projection plus or minus the half-extents
    // weighted by the axis' absolute components.
    const auto meets = [&](const Vec3d& lo, const Vec3d& hi) {
      const Vec3d centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
      const auto reach = [&half](const Vec3d& axis) {
        return std::abs(axis.x) * half.x + std::abs(axis.y) * half.y + std::abs(axis.z) * half.z;
      };
      const double ca = dot(a, centre), cb = dot(b, centre), ra = reach(a), rb = reach(b);
      const double slack = 1e-9 * (1.0 + std::abs(ca) + std::abs(cb) + ra + rb);
      return ca - ra <= a_hi + slack && ca + ra >= a_lo - slack && cb - rb <= b_hi + slack &&
             cb + rb >= b_lo - slack && dot(d, centre) + reach(d) >= start - slack;
    };
    walk_tree(
        nodes_, [&](const Node& node) { return meets(node.lo, node.hi); },
        [&](const Node& node) {
          for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const uint32_t f = order_[i];
            if (meets(box_[f].lo, box_[f].hi)) candidate(f);
          }
        });
  }

 private:
  struct Box {
    Vec3d lo, hi;
  };
  struct Node {
    Vec3d lo, hi;
    uint32_t first = 0, count = 0;  // facets of a leaf; count 0: children at index + 1, second
    uint32_t second = 0;
  };

  uint32_t build(const std::vector<std::array<Vec3d, 3>>& corners, uint32_t first, uint32_t count) {
    const uint32_t index = static_cast<uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.lo = {kInfinity, kInfinity, kInfinity};
    node.hi = {-kInfinity, -kInfinity, -kInfinity};
    for (uint32_t i = first; i < first + count; ++i) {
      const Box& b = box_[order_[i]];
      node.lo = {std::min(node.lo.x, b.lo.x), std::min(node.lo.y, b.lo.y),
                 std::min(node.lo.z, b.lo.z)};
      node.hi = {std::max(node.hi.x, b.hi.x), std::max(node.hi.y, b.hi.y),
                 std::max(node.hi.z, b.hi.z)};
    }
    if (count <= 4) {
      node.first = first;
      node.count = count;
      nodes_[index] = node;
      return index;
    }
    const uint32_t half = split_at_median(
        order_, first, count, node.hi - node.lo,
        [&corners](uint32_t f) { return corners[f][0] + corners[f][1] + corners[f][2]; });
    nodes_[index] = node;
    build(corners, first, half);
    nodes_[index].second = build(corners, first + half, count - half);
    return index;
  }

  std::vector<Box> box_;  // each facet's
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

// Fragments smaller than this share of their facet are rounding, not light.
constexpr double kSmallestFragment = 1e-12;

}  // namespace

FacetChainTree::FacetChainTree(const TriangleMesh& mesh, float eta, Vec3 light, int max_levels,
                               uint64_t bytes)
    : light_(light) {
  const Vec3d l = normalize(Vec3d(light));
  std::vector<std::array<Vec3d, 3>> corners;
  facets_.reserve(mesh.triangle_count());
  corners.reserve(mesh.triangle_count());
  for_each_facet(mesh, [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3d& n) {
    const Vec3d q0(p0), q1(p1), q2(p2);
    facets_.push_back({q0, q1 - q0, q2 - q0, n});
    corners.push_back({q0, q1, q2});
  });
  const FacetBoxTree boxes(corners);

  // Level 0: the beams refracted in through the facets facing the light, each leaving its whole
  // facet.
  Regions region;
  levels_.emplace_back();
  for (uint32_t f = 0; f < facets_.size(); ++f) {
    const Vec3d omega_r = refracted_inward(facets_[f].n, l, eta);
    if (!(length(omega_r) > 0)) continue;
    levels_[0].push_back(
        {f, 0, omega_r, 1.0, std::abs(dot(facets_[f].n, omega_r)), kNoFacet, Vec3d{}});
    Polygon triangle;
    for (const Vec3d& p : corners[f]) triangle.corner[static_cast<size_t>(triangle.count++)] = p;
    region.add(triangle);
  }
  const float inverse_eta = 1.0f / eta;
  // What the levels built hold (bytes_), and the cross-sections of the last, which the next
  // level is clipped from; the facets and their box tree are the exit tree's size, which the
  // caller's allowance leaves out.
  const auto level_bytes = [](const std::vector<Beam>& beams) {
    return beams.capacity() * sizeof(Beam) + beams.size() * BallConeTree::bytes_per_item();
  };
  bytes_ = level_bytes(levels_[0]);
  for (int k = 1; k <= std::min(max_levels, kMaxMeshChainLevels); ++k) {
    const uint64_t held = bytes_ + region.corners.capacity() * sizeof(Vec3d) +
                          region.first.capacity() * sizeof(uint32_t);
    const uint64_t per_triangle = kMeshChainFragmentsPerTriangle << std::max(0, k - 4);
    // The last bound: Regions::first indexes corners in 32 bits.
    const uint64_t cap = std::min({per_triangle * facets_.size(),
                                   (bytes > held ? bytes - held : 0) / bytes_per_fragment(),
                                   uint64_t{UINT32_MAX} / kMaxCorners});
    const std::vector<Beam>& below = levels_.back();
    std::vector<Beam> beams;
    Regions next_region;
    bool too_many = false;
    for (uint32_t i = 0; i < below.size() && !too_many; ++i) {
      const Beam& beam = below[i];
      const Vec3d& d = beam.direction;
      const Polygon source = region[i];
      // A beam's cross-section cut to where it lands on facet f along `along`: the part on the
      // side of f's plane it comes from (`side` = +1 outside, -1 inside), carried onto the
      // plane and cut to the triangle (its edges' inward normals lie in the plane); empty if
      // nothing is left.
      const auto land = [](const Polygon& from, const Facet& f, const Vec3d& along, double side) {
        Polygon part = clip(from, side * f.n, side * dot(f.n, f.p0));
        if (part.count < 3) return Polygon{};
        const double cos_along = dot(along, f.n);
        for (int c = 0; c < part.count; ++c) {
          Vec3d& p = part.corner[static_cast<size_t>(c)];
          p = p + (dot(f.p0 - p, f.n) / cos_along) * along;
        }
        const Vec3d c0 = f.p0, c1 = f.p0 + f.e1, c2 = f.p0 + f.e2;
        for (const auto& [a, b] : {std::pair{c0, c1}, std::pair{c1, c2}, std::pair{c2, c0}}) {
          const Vec3d inward = cross(f.n, b - a);
          part = clip(part, inward, dot(inward, a));
          if (part.count < 3) return Polygon{};
        }
        if (!(polygon_area(part) > kSmallestFragment * 0.5 * length(cross(f.e1, f.e2)))) {
          return Polygon{};
        }
        return part;
      };
      const auto keep = [&](const Beam& next, const Polygon& part) {
        if (beams.size() == cap) {
          too_many = true;
          return;
        }
        beams.push_back(next);
        next_region.add(part);
      };
      boxes.for_each_candidate(source, d, [&](uint32_t g) {
        const Facet& f = facets_[g];
        const double cos_out = dot(d, f.n);
        if (too_many || !(cos_out > 0)) return;
        const Polygon part = land(source, f, d, -1.0);
        if (part.count == 0) return;
        const double reflectance = fresnel_dielectric(static_cast<float>(cos_out), inverse_eta);
        keep({g, i, normalize(d - 2.0 * cos_out * f.n), beam.fresnel * reflectance, beam.jacobian,
              kNoFacet, Vec3d{}},
             part);
        // The part that leaves: refracted out, it may enter the mesh again through a facet
        // facing it from outside (the mesh need not be convex).
        const Vec3d out = refracted_inward(-f.n, -d, 1.0 / eta);
        if (!(length(out) > 0)) return;
        // Crossing a flat facet keeps the beam parallel and scales its cross-section by the
        // ratio of the cosines (dV / (dA(y) dt) with it).
        const double widening_out = dot(out, f.n) / cos_out;
        boxes.for_each_candidate(part, out, [&](uint32_t h) {
          const Facet& e = facets_[h];
          const double cos_in = -dot(out, e.n);
          if (too_many || !(cos_in > 0)) return;
          const Vec3d in = refracted_inward(e.n, -out, eta);
          if (!(length(in) > 0)) return;
          const Polygon entered = land(part, e, out, 1.0);
          if (entered.count == 0) return;
          const double transmitted =
              (1.0 - reflectance) * (1.0 - fresnel_dielectric(static_cast<float>(cos_in), eta));
          keep({h, i, in, beam.fresnel * transmitted,
                beam.jacobian * widening_out * (-dot(in, e.n) / cos_in), g, out},
               entered);
        });
      });
    }
    if (too_many) break;
    std::vector<BallConeTree::Bounds> bounds;
    bounds.reserve(beams.size());
    for (size_t i = 0; i < beams.size(); ++i) {
      BallConeTree::Bounds b;
      Vec3d sum{};
      const Polygon part = next_region[i];
      for (int c = 0; c < part.count; ++c) {
        b.add(part.corner[static_cast<size_t>(c)]);
        sum = sum + part.corner[static_cast<size_t>(c)];
      }
      b.centroid = Vec3(sum / static_cast<double>(part.count));
      b.axis = beams[i].direction;
      bounds.push_back(b);
    }
    trees_.emplace_back(std::move(bounds));
    bytes_ += level_bytes(beams);
    levels_.push_back(std::move(beams));
    region = std::move(next_region);
  }
}

uint64_t FacetChainTree::bytes_per_fragment() {
  // Kept: its beam and its share of the level's tree. While building: its cross-section, and
  // the tree's bounds of it (copied once into the tree). The beams and cross-sections grow by
  // doubling, so each may hold twice what it uses.
  return 2 * sizeof(Beam) + BallConeTree::bytes_per_item() +
         2 * (sizeof(uint32_t) + kMaxCorners * sizeof(Vec3d)) + 2 * sizeof(BallConeTree::Bounds);
}

uint64_t FacetChainTree::fragments(int level) const {
  if (level < 1 || level > levels_solved()) return 0;
  return levels_[static_cast<size_t>(level)].size();
}

bool FacetChainTree::trace_back(const Vec3d& x, int level, uint32_t beam_index,
                                MeshChain* chain) const {
  // From x against the last beam to the facet it left, then (for a crossing) against the
  // stretch outside to the facet the light left the mesh by, then against the beam below, down
  // to the entry. The points are found from x backwards and stored in the light's order.
  const Beam& last = levels_[static_cast<size_t>(level)][beam_index];
  chain->levels = level;
  chain->omega_last = Vec3(last.direction);
  chain->fresnel = last.fresnel;
  chain->jacobian = last.jacobian;
  chain->length = 0;
  std::array<Vec3d, kMaxMeshChainEvents> points;
  std::array<uint32_t, kMaxMeshChainEvents> facets;
  std::array<bool, kMaxMeshChainEvents> leaves;
  int found = 0;
  Vec3d at = x;
  uint32_t index = beam_index;
  const auto back = [&](uint32_t facet, const Vec3d& direction, bool inside) {
    const Facet& f = facets_[facet];
    double u = 0, v = 0, t = 0;
    if (!meets_backwards(f.p0, f.e1, f.e2, at, direction, &u, &v, &t)) return false;
    at = at - t * direction;
    if (inside) chain->length += t;
    return true;
  };
  for (int at_level = level; at_level >= 0; --at_level) {
    const Beam& beam = levels_[static_cast<size_t>(at_level)][index];
    if (!back(beam.facet, beam.direction, true)) return false;
    if (at_level == 0) {
      chain->y = Vec3(at);
      chain->n = Vec3(facets_[beam.facet].n);
      break;
    }
    points[static_cast<size_t>(found)] = at;
    facets[static_cast<size_t>(found)] = beam.facet;
    leaves[static_cast<size_t>(found++)] = false;
    if (beam.crossed_from != kNoFacet) {
      if (!back(beam.crossed_from, beam.outside, false)) return false;
      points[static_cast<size_t>(found)] = at;
      facets[static_cast<size_t>(found)] = beam.crossed_from;
      leaves[static_cast<size_t>(found++)] = true;
    }
    index = beam.parent;
  }
  chain->events = found;
  for (int k = 0; k < found; ++k) {
    const size_t from = static_cast<size_t>(found - 1 - k);
    chain->point[static_cast<size_t>(k)] = Vec3(points[from]);
    chain->normal[static_cast<size_t>(k)] = Vec3(facets_[facets[from]].n);
    chain->leaves[static_cast<size_t>(k)] = leaves[from];
  }
  return true;
}

MeshChains FacetChainTree::chains_toward(Vec3 x_in, int levels, int run, double u) const {
  MeshChains out;
  if (levels < 1 || levels > levels_solved()) return out;
  const Vec3d x(x_in);
  std::array<uint32_t, kMaxMeshChainsFound> found;
  MeshChain scratch;
  trees_[static_cast<size_t>(levels - 1)].for_each_candidate(x, [&](uint32_t i) {
    if (!trace_back(x, levels, i, &scratch)) return;
    if (out.found == kMaxMeshChainsFound) {
      ++out.dropped;
      return;
    }
    found[static_cast<size_t>(out.found++)] = i;
  });
  const int n = out.found;
  const int keep = std::min({n, run, kMaxMeshChainsReturned});
  const int start = n > keep ? std::min(static_cast<int>(u * n), n - 1) : 0;
  for (int k = 0; k < keep; ++k) {
    trace_back(x, levels, found[static_cast<size_t>((start + k) % n)],
               &out.chain[static_cast<size_t>(out.returned++)]);
  }
  return out;
}

}  // namespace snee
