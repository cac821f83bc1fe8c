// Everything the stage kernels read but never write: the scene's Embree handle and light
// table, per-shape and per-medium parameters flattened for fast lookup, the camera basis and
// the integrator settings. Built once per render and shared by all work units.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/physics/bsdf/conductor.h"
#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/bsdf/diffuse_transmission.h"
#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/medium/grid_medium.h"
#include "kernels/physics/medium/homogeneous_medium.h"
#include "kernels/physics/snee/manifold_mesh.h"
#include "kernels/physics/snee/manifold_mesh_chains.h"
#include "kernels/physics/snee/manifold_mesh_point.h"
#include "kernels/physics/snee/snee_options.h"
#include "kernels/wavefront/snee_counters.h"
#include "scene/camera_frame.h"
#include "scene/embree_scene.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"
#include "scene/texture_set.h"

namespace snee {

enum class Integrator : uint8_t {
  kPathTracer,    // "pt": volumetric path tracing, NEE only where no refraction is in the way
  kSnee,          // "snee": pt plus subdivision next-event estimation at medium vertices
  kStraightLine,  // "sla": shadow rays pass dielectric boundaries with Fresnel transmittance
                  // (biased)
};
const char* integrator_name(Integrator i);
// Throws std::invalid_argument listing the valid names.
Integrator parse_integrator(const std::string& name);

struct SurfaceInfo {
  MaterialKind kind;
  DielectricParams dielectric;
  Rgb albedo;               // diffuse
  int32_t interior_medium;  // medium entered when crossing against the outward normal
  bool emissive;
  ConductorParams conductor;
  DiffuseTransmissionParams sheet;
  // The first-hit albedo AOV (first_hit_aovs.h), fixed per surface, so computed once here.
  Rgb aov_albedo;
  // Shaded with the mesh's interpolated vertex normals (Shape::smooth_shading; shading_normal.h).
  bool smooth_shading;
  // A sphere or a mesh without boundary edges (Shape::closed): a ray is on one side of it, which
  // the path tracks (kPathInsideVolume) for its dielectric and null boundaries.
  bool closed = false;
  // Diffuse: index into KernelContext::textures whose colour multiplies albedo (and
  // aov_albedo) at each hit (surface_texture.h); -1 for none.
  int32_t albedo_texture = -1;
  // Dielectric and conductor: index into KernelContext::textures that scales the GGX alpha at
  // each hit (Material::roughness_texture, surface_texture.h); -1 for none.
  int32_t roughness_texture = -1;
  bool roughness_texture_squared = false;
  // A mirror or a smooth dielectric: no light sampling, no AOV vertex.
  bool delta() const {
    return (kind == MaterialKind::kDielectric && dielectric.delta()) ||
           (kind == MaterialKind::kConductor && conductor.delta());
  }
};

struct MediumInfo {
  // The medium's physics. A homogeneous medium is `medium`; a grid medium is `grid` (its
  // grid.grid set). Stage code reaches either through visit, the one place that tells the kinds
  // apart; only SNEE's code, which runs where snee_eligible() holds, reads `medium` directly.
  HomogeneousMedium medium;
  GridMedium grid;
  bool is_grid() const { return grid.grid != nullptr; }
  // f(the medium as its own type), so each kind's members inline into the caller.
  template <class Visit>
  auto visit(Visit&& f) const {
    return is_grid() ? f(grid) : f(medium);
  }
  // Each medium kind declares whether SNEE's closed forms hold in it (kSneeEligible).
  bool snee_eligible() const {
    return visit([](const auto& m) { return m.kSneeEligible; });
  }
  Rgb transmittance(Vec3 x, Vec3 w, float t) const {
    return visit([&](const auto& m) -> Rgb { return m.transmittance(x, w, t); });
  }
  float asymmetry(Vec3 x) const {
    return visit([&](const auto& m) { return m.asymmetry(x); });
  }

  // True when every boundary of this medium is an index-matched (null) interface, so a
  // straight shadow ray from inside can reach a light: only then is medium NEE worth a ray.
  bool straight_nee;
  // The shape index of the smooth dielectric that is this medium's only boundary, where the
  // manifold strategy can find exit points: a sphere (docs/method.md 3.10) or a closed
  // flat-shaded mesh (3.13); -1 if there is none.
  int32_t manifold_boundary = -1;
  // The boundary's curvature as the manifold strategy's Jacobian takes it: 1 / radius for the
  // sphere, 0 for a mesh's flat facets.
  float manifold_curvature = 0.0f;
  // A sphere boundary's centre and radius (zero for a mesh).
  Vec3 manifold_centre{0.0f, 0.0f, 0.0f};
  float manifold_radius = 0.0f;
  // A mesh boundary's exit trees, one per directional light of the scene, and one per point or
  // spot light outside it (where point_facet_tree_applies); null for a sphere. Built for snee
  // only, the one integrator that runs the manifold strategy.
  std::shared_ptr<const std::vector<FacetExitTree>> manifold_mesh = nullptr;
  std::shared_ptr<const std::vector<PointFacetTree>> manifold_mesh_points = nullptr;
  // Its reflection chains' trees, one per directional light, where chains are on.
  std::shared_ptr<const std::vector<FacetChainTree>> manifold_mesh_chains = nullptr;
  // Whether the boundary is a smooth dielectric the manifold strategy has no solver for (a
  // smooth-shaded mesh, or several shapes): its single-scattered light under a directional
  // light is missing.
  bool manifold_unsupported = false;
  // Whether no other shape reaches into a sphere boundary (no bounding box meets it), so a path
  // inside it cannot be blocked: its reflection chains then need only their light segment.
  bool manifold_interior_clear = false;
  // The sphere or closed flat-shaded mesh that is this medium's only boundary, a dielectric of
  // any roughness (without a
  // roughness texture) and eta != 1, where the guided exit runs (docs/method.md 3.15); -1 if
  // none, or for integrators other than snee.
  int32_t guide_boundary = -1;
  // A sphere's centre and radius; or, for a closed flat-shaded mesh, its exit trees, one per
  // distant target (SneeOptions::probe_targets) as guide_tree_of_target says (-1: none, a
  // point or spot light, whose share of the guide then stays unused).
  Vec3 guide_centre{0.0f, 0.0f, 0.0f};
  float guide_radius = 0.0f;
  std::shared_ptr<const std::vector<FacetExitTree>> guide_mesh = nullptr;
  std::array<int, kMaxProbeTargets> guide_tree_of_target{-1, -1, -1, -1};
  // How often a vertex searches for reflection chains (chain_search_probability).
  double chain_search = 0.0;

  // The mesh boundary's exit tree for the directional light along `light` (as LightSample::wi
  // gives it); null for a sphere.
  const FacetExitTree* manifold_tree(Vec3 light) const {
    if (!manifold_mesh) return nullptr;
    for (const FacetExitTree& tree : *manifold_mesh) {
      if (tree.light() == light) return &tree;
    }
    return nullptr;
  }
  // The mesh boundary's chain tree for the directional light along `light`; null if none.
  const FacetChainTree* manifold_chain_tree(Vec3 light) const {
    if (!manifold_mesh_chains) return nullptr;
    for (const FacetChainTree& tree : *manifold_mesh_chains) {
      if (tree.light() == light) return &tree;
    }
    return nullptr;
  }
  // The mesh boundary's exit tree for the point or spot light scene.lights[light]; null for a
  // sphere, or where none applies.
  const PointFacetTree* manifold_point_tree(int light) const {
    if (!manifold_mesh_points) return nullptr;
    for (const PointFacetTree& tree : *manifold_mesh_points) {
      if (tree.light() == light) return &tree;
    }
    return nullptr;
  }
  // Whether the manifold strategy finds this medium's exit points for the delta light sampled
  // at `at`: a directional light over a sphere boundary or a mesh with a tree for it, or a point
  // or spot light outside a sphere boundary (sphere_exits_toward_point) or with a mesh tree.
  // Both the strategy (connect_manifold) and top-to-bottom's view of it (subdivision) ask this.
  bool manifold_solves_for(const LightSample& light, Vec3 at) const {
    if (manifold_boundary < 0 || !light.delta) return false;
    if (std::isinf(light.distance)) return !manifold_mesh || manifold_tree(light.wi) != nullptr;
    if (manifold_mesh) return manifold_point_tree(light.light) != nullptr;
    return length(at + light.wi * light.distance - manifold_centre) > manifold_radius;
  }
};

// The stage kernels that run their queue in SIMD chunks, for lane-occupancy counters.
enum class BatchedKernel : int {
  kCameraRays,
  kMediumFlights,
  kSurfaceSamples,
  kProbeDirections,
  kSubdivisionDraws,
  kSubdivisionSamples,
  kSubdivisionWeights,
  kCount
};
inline constexpr int kBatchedKernels = static_cast<int>(BatchedKernel::kCount);
// The stage's name: "generate", "medium_event", "shade_surface", "snee_probe", "subdivision";
// subdivision's later passes, which sample the strategies and weigh their proposals, are
// "subdivision_samples" and "subdivision_weights".
const char* batched_kernel_name(BatchedKernel k);

// Lanes that held a queued slot, and lanes computed (a short chunk still runs at full width).
struct LaneCount {
  uint64_t active = 0;
  uint64_t run = 0;
  double occupancy() const { return run > 0 ? static_cast<double>(active) / run : 0.0; }
};

// The rays the stages trace, for KernelCounters::rays: camera and extension rays (extend),
// shadow segments (shadow_connect) and SNEE exit-point probes (snee_probe).
enum class RayKind : int { kCamera, kExtension, kShadow, kProbe, kCount };
inline constexpr int kRayKinds = static_cast<int>(RayKind::kCount);
// "camera", "extension", "shadow", "probe": the keys of the statistics' "rays".
const char* ray_kind_name(RayKind k);

// Counters kept per thread and summed at the end.
struct KernelCounters {
  std::array<uint64_t, kRayKinds> rays{};  // by RayKind
  uint64_t paths = 0;
  uint64_t nonfinite_samples = 0;
  SneeCounters snee{};
  std::array<LaneCount, kBatchedKernels> lanes{};
  void count(SneeCounter c, uint64_t n = 1) { snee[static_cast<int>(c)] += n; }
  void count_rays(RayKind k, uint64_t n) { rays[static_cast<int>(k)] += n; }
  void count_lanes(BatchedKernel k, uint64_t active, uint64_t width) {
    lanes[static_cast<int>(k)].active += active;
    lanes[static_cast<int>(k)].run += width;
  }
  void add(const KernelCounters& o);
};

struct KernelContext {
  // Throws std::invalid_argument where what the scene makes the context build (the manifold
  // strategy's exit trees) would not fit in `budget`.
  KernelContext(const Scene& scene, const EmbreeScene& embree, const LightTable& lights,
                Integrator integrator, uint32_t seed, int max_depth, const SneeOptions& snee,
                const MemoryBudget& budget = MemoryBudget{});

  const Scene* scene;
  const EmbreeScene* embree;
  const LightTable* lights;
  std::vector<SurfaceInfo> surfaces;  // by shape index (= Embree geometry ID)
  std::vector<MediumInfo> media;
  Integrator integrator;
  uint32_t seed;
  int max_depth;
  SneeOptions snee;
  bool has_null_surfaces = false;
  // Some medium is a grid (MediumInfo::grid): medium_event then sorts its queue by kind.
  bool has_grid_media = false;
  // Each sample's RGB is clipped to this before it reaches the film (0: never). Biased: it
  // trades the energy of rare bright paths (fireflies) for less variance.
  float sample_clamp = 0.0f;
  // Paths record their first non-specular hit's albedo, normal and depth (first_hit_aovs.h).
  bool record_aovs = false;
  float epsilon;
  CameraFrame camera;
  int width, height;
  // The width of one pixel's footprint per unit of distance from the camera, for the texture
  // footprint of a hit (surface_texture.h).
  float pixel_spread;
  // The scene's textures; null when it has none.
  std::shared_ptr<const TextureSet> textures;
};

}  // namespace snee
