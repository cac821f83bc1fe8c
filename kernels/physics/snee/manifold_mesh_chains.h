// The manifold strategy's reflection chains behind a closed, flat-shaded triangle mesh under a
// directional light (docs/method.md 3.14): light refracted in through one facet and reflected
// specularly inside by one or more others, or crossing out of the mesh and into another part of
// it, before it reaches an interior point x. On flat facets every beam stays parallel: the
// light entering through a facet is one beam, and its reflection off a facet, or its refraction
// out and in again, is again one beam, leaving the part of a facet the incoming beam covers (a
// convex fragment). The fragments are enumerated once per light, level by level (one
// reflection or crossing more each), by clipping each beam against the facets ahead of it; a query
// then finds the fragments whose beam passes through x with a ball-and-cone tree per level, and
// traces each back, facet by facet, to its entry point. Which facets block a beam is left to
// the caller's rays, so the enumeration is exact without hidden-surface removal.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/vec3d.h"
#include "kernels/physics/snee/ball_cone_tree.h"
#include "scene/scene.h"

namespace snee {

// Most levels (reflections and crossings) a mesh chain may have: each level holds about twice
// the fragments of the one below (each beam splits over the facets ahead of it), so the levels
// are few (SneeOptions::mesh_chain_levels chooses how many, kDefaultMeshChainLevels by default).
inline constexpr int kMaxMeshChainLevels = 8;
// Fragments each of the first four levels may hold per triangle of the mesh (measured on the
// bunny: 4.0, 11.8, 27.2 and 51.0 for one to four levels), twice as many each level above; a
// level that would hold more, or more than what is left of the memory allowance, is not built
// (nor any above it), and its chains are counted as unsupported.
inline constexpr uint64_t kMeshChainFragmentsPerTriangle = 64;
// Most chains one query finds (more are counted as dropped). Near a caustic, where the beams of
// many facet pairs focus, a point inside an icosphere sees hundreds.
inline constexpr int kMaxMeshChainsFound = 4096;
// Most chains one query returns in full: a run of the chains found (the caller connects each
// with its share of them).
inline constexpr int kMaxMeshChainsReturned = 16;

// Points on the boundary a chain may pass between its entry and x: one per reflection, two per
// crossing (leaving the mesh and entering it again).
inline constexpr int kMaxMeshChainEvents = 2 * kMaxMeshChainLevels;

// The light entering at y, then reflected inside or crossing out and back in at point[0],
// point[1], ... (in the light's order), that reaches x on its last segment.
struct MeshChain {
  int levels = 0;  // reflections and crossings
  int events = 0;  // points between y and x
  Vec3 y;          // where the light refracts in
  Vec3 n;          // the entry facet's outward normal
  std::array<Vec3, kMaxMeshChainEvents> point{};
  std::array<Vec3, kMaxMeshChainEvents> normal{};  // outward normals there
  // Whether the light leaves the mesh at point[k] (and travels outside to point[k + 1], where
  // it enters again); otherwise it reflects there.
  std::array<bool, kMaxMeshChainEvents> leaves{};
  Vec3 omega_last;      // unit propagation direction on the last segment (toward x)
  double length = 0;    // path length inside, y to x (the stretches outside excluded)
  double fresnel = 1;   // the reflections' reflectances times the crossings' transmittances
  double jacobian = 0;  // dV(x) / (dA(y) dt): |n . omega_r| at the entry, scaled by each crossing
};

struct MeshChains {
  std::array<MeshChain, kMaxMeshChainsReturned> chain{};  // the run returned
  int returned = 0;
  int found = 0;    // all the chains found, each in the run with probability returned / found
  int dropped = 0;  // solutions beyond kMaxMeshChainsFound
};

class FacetChainTree {
 public:
  // The chains of `mesh` (world space, outward winding, relative index eta = inside / outside)
  // under the directional light along `light` (unit, toward it), up to `max_levels` levels (at
  // most kMaxMeshChainLevels), all of them within `bytes` (what the levels hold and what
  // building the next one takes): a level that would not fit is left out, and those above it.
  FacetChainTree(const TriangleMesh& mesh, float eta, Vec3 light, int max_levels,
                 uint64_t bytes = ~uint64_t{0});
  // What one fragment costs a level, kept and while it is built.
  static uint64_t bytes_per_fragment();

  Vec3 light() const { return light_; }
  // Level counts it has every chain of: 1 to this.
  int levels_solved() const { return static_cast<int>(trees_.size()); }
  // Fragments at each level (statistics for the docs and tests).
  uint64_t fragments(int level) const;
  // What the levels built hold.
  uint64_t bytes() const { return bytes_; }

  // The chains with exactly `levels` levels (reflections and crossings) whose last beam passes
  // through x (which should lie inside): all are counted, and a run of at most `run` of them
  // (at most kMaxMeshChainsReturned) is returned, cyclically from the one a uniform u in
  // [0, 1) picks, so that each is returned with probability returned / found. Whether each
  // segment is unblocked, and the light reaches y, is for the caller's rays to decide. None
  // where `levels` is not solved.
  MeshChains chains_toward(Vec3 x, int levels, int run, double u) const;

 private:
  struct Facet {
    Vec3d p0, e1, e2;  // corner and edges
    Vec3d n;           // outward unit normal
  };
  // A beam leaving a facet into the inside: the light refracted in (level 0), reflected, or
  // refracted in again after crossing out of the mesh at crossed_from (above).
  struct Beam {
    uint32_t facet = 0;
    uint32_t parent = 0;  // the beam it continues, one level down
    Vec3d direction;      // unit propagation direction after the facet
    double fresnel = 1;   // the product of the Fresnel factors so far
    double jacobian = 0;  // dV / (dA(y) dt) so far
    uint32_t crossed_from = kNoFacet;
    Vec3d outside;  // unit propagation direction outside, for a crossing
  };
  static constexpr uint32_t kNoFacet = ~uint32_t{0};
  // The chain whose last beam is levels_[level][beam], traced back from x; false if the beam,
  // or one below it, misses its facet.
  bool trace_back(const Vec3d& x, int level, uint32_t beam, MeshChain* chain) const;

  Vec3 light_;
  std::vector<Facet> facets_;
  std::vector<std::vector<Beam>> levels_;  // levels_[k]: beams after k levels
  std::vector<BallConeTree> trees_;        // trees_[k - 1] over levels_[k]
  uint64_t bytes_ = 0;
};

}  // namespace snee
