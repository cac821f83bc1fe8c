#include "kernels/wavefront/kernel_context.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/physics/snee/probe.h"
#include "scene/shape_bounds.h"

namespace snee {

const char* integrator_name(Integrator i) {
  switch (i) {
    case Integrator::kPathTracer:
      return "pt";
    case Integrator::kSnee:
      return "snee";
    case Integrator::kStraightLine:
      return "sla";
  }
  return "?";
}

const char* ray_kind_name(RayKind k) {
  switch (k) {
    case RayKind::kCamera:
      return "camera";
    case RayKind::kExtension:
      return "extension";
    case RayKind::kShadow:
      return "shadow";
    case RayKind::kProbe:
      return "probe";
    case RayKind::kCount:
      break;
  }
  return "?";
}

const char* batched_kernel_name(BatchedKernel k) {
  switch (k) {
    case BatchedKernel::kCameraRays:
      return "generate";
    case BatchedKernel::kMediumFlights:
      return "medium_event";
    case BatchedKernel::kSurfaceSamples:
      return "shade_surface";
    case BatchedKernel::kProbeDirections:
      return "snee_probe";
    case BatchedKernel::kSubdivisionDraws:
      return "subdivision";
    case BatchedKernel::kSubdivisionSamples:
      return "subdivision_samples";
    case BatchedKernel::kSubdivisionWeights:
      return "subdivision_weights";
    case BatchedKernel::kCount:
      break;
  }
  return "?";
}

Integrator parse_integrator(const std::string& name) {
  if (name == "pt") return Integrator::kPathTracer;
  if (name == "snee") return Integrator::kSnee;
  if (name == "sla") return Integrator::kStraightLine;
  throw std::invalid_argument("unknown integrator '" + name + "' (expected pt, snee or sla)");
}

void KernelCounters::add(const KernelCounters& o) {
  for (size_t i = 0; i < rays.size(); ++i) rays[i] += o.rays[i];
  for (size_t i = 0; i < snee.size(); ++i) snee[i] += o.snee[i];
  paths += o.paths;
  nonfinite_samples += o.nonfinite_samples;
  for (size_t i = 0; i < lanes.size(); ++i) {
    lanes[i].active += o.lanes[i].active;
    lanes[i].run += o.lanes[i].run;
  }
}

namespace {

// The diffuse colour, the metal's normal-incidence reflectance, the sheet's reflectance plus
// transmittance; a rough dielectric is colourless (white).
Rgb aov_albedo(const SurfaceInfo& info) {
  switch (info.kind) {
    case MaterialKind::kDiffuse:
      return info.albedo;
    case MaterialKind::kConductor:
      return fresnel_conductor(1.0f, info.conductor.eta, info.conductor.k);
    case MaterialKind::kDiffuseTransmission:
      return info.sheet.reflectance + info.sheet.transmittance;
    default:
      return Rgb(1.0f);
  }
}

// Whether no shape but `sphere` has a bounding box that meets the sphere (a conservative test:
// a box that only grazes it counts as reaching in).
bool nothing_reaches_into(const Scene& s, size_t sphere) {
  const Shape& ball = s.shapes[sphere];
  for (size_t j = 0; j < s.shapes.size(); ++j) {
    if (j == sphere) continue;
    ShapeBounds box;
    box.add(s.shapes[j]);
    if (box.empty()) continue;
    const Vec3 nearest = vmin(vmax(ball.center, box.lo), box.hi);
    if (length(nearest - ball.center) <= ball.radius) return false;
  }
  return true;
}

// A mesh boundary's exit trees for the manifold strategy, one per directional light and one per
// point or spot light outside it, and with `chains` a chain tree per directional light; their
// size grows with the mesh, so it is checked against the budget before any is built.
// The guided exit's exit trees of a closed flat-shaded mesh (docs/method.md 3.15), one per
// distant target; behind a smooth interface only the cones', as nothing but a light sample
// reaches a directional light and a smooth interface has none. False, building nothing, where no
// target needs a tree: the guided exit then does not run in the mesh.
bool build_guide_trees(const Shape& mesh, const DielectricParams& interface,
                       const ProbeTargets& targets, const MemoryBudget& budget, MediumInfo& m) {
  const auto wanted = [&](const ProbeTarget& target) {
    return !target.positional && !(target.delta && interface.delta());
  };
  int distant = 0;
  for (int t = 0; t < targets.count; ++t)
    distant += wanted(targets.target[static_cast<size_t>(t)]) ? 1 : 0;
  if (distant == 0) return false;
  const uint64_t triangles = mesh.mesh.triangle_count();
  const uint64_t bytes =
      saturating_multiply(static_cast<uint64_t>(distant), FacetExitTree::bytes_at_most(triangles));
  if (!budget.allows(bytes)) {
    throw std::invalid_argument(
        budget.exceeded("the guided exit's exit trees of the mesh '" + mesh.name + "' (" +
                            std::to_string(triangles) + " triangles, a tree for each of " +
                            std::to_string(distant) + " small distant lights)",
                        bytes));
  }
  auto trees = std::make_shared<std::vector<FacetExitTree>>();
  trees->reserve(static_cast<size_t>(distant));
  for (int t = 0; t < targets.count; ++t) {
    const ProbeTarget& target = targets.target[static_cast<size_t>(t)];
    if (!wanted(target)) continue;
    m.guide_tree_of_target[static_cast<size_t>(t)] = static_cast<int>(trees->size());
    trees->emplace_back(mesh.mesh, interface.eta, target.where);
  }
  m.guide_mesh = std::move(trees);
  return true;
}

void build_facet_exit_trees(const Scene& s, const Shape& mesh, float eta, bool chains,
                            int chain_levels, const MemoryBudget& budget, MediumInfo& m) {
  std::vector<int> directional, point;
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& light = s.lights[i];
    if (light.kind == LightKind::kDirectional) directional.push_back(static_cast<int>(i));
    if ((light.kind == LightKind::kPoint || light.kind == LightKind::kSpot) &&
        point_facet_tree_applies(mesh.mesh, eta, light.position)) {
      point.push_back(static_cast<int>(i));
    }
  }
  const uint64_t triangles = mesh.mesh.triangle_count();
  const uint64_t bytes = saturating_add(
      saturating_multiply(directional.size(), FacetExitTree::bytes_at_most(triangles)),
      saturating_multiply(point.size(), PointFacetTree::bytes_at_most(triangles)));
  if (!budget.allows(bytes)) {
    throw std::invalid_argument(
        budget.exceeded("the manifold strategy's exit trees of the mesh '" + mesh.name + "' (" +
                            std::to_string(triangles) + " triangles, a tree for each of " +
                            std::to_string(directional.size()) + " directional and " +
                            std::to_string(point.size()) + " point or spot lights)",
                        bytes));
  }
  auto trees = std::make_shared<std::vector<FacetExitTree>>();
  trees->reserve(directional.size());
  for (const int i : directional) trees->emplace_back(mesh.mesh, eta, s.lights[i].direction);
  auto point_trees = std::make_shared<std::vector<PointFacetTree>>();
  point_trees->reserve(point.size());
  for (const int i : point) point_trees->emplace_back(mesh.mesh, eta, s.lights[i].position, i);
  m.manifold_mesh = std::move(trees);
  m.manifold_mesh_points = std::move(point_trees);
  if (!chains) return;
  // The search rate of a sphere as large as the mesh's bounding sphere (under a point or spot
  // light too, where the searches it would make are counted as unsupported).
  ShapeBounds box;
  box.add(mesh);
  m.chain_search = chain_search_probability(m.medium.sigma_t, 0.5f * length(box.hi - box.lo));
  if (directional.empty()) return;
  auto chain_trees = std::make_shared<std::vector<FacetChainTree>>();
  chain_trees->reserve(directional.size());
  // The chains are the light's smaller part: they get what the exit trees leave of the budget,
  // shared by the lights, and the levels that do not fit are counted where a vertex would have
  // searched them.
  const uint64_t per_light = (budget.bytes - bytes) / directional.size();
  for (const int i : directional) {
    chain_trees->emplace_back(mesh.mesh, eta, s.lights[i].direction, chain_levels, per_light);
  }
  m.manifold_mesh_chains = std::move(chain_trees);
}

}  // namespace

KernelContext::KernelContext(const Scene& s, const EmbreeScene& e, const LightTable& l,
                             Integrator integ, uint32_t seed_, int max_depth_,
                             const SneeOptions& snee_, const MemoryBudget& budget)
    : scene(&s),
      embree(&e),
      lights(&l),
      integrator(integ),
      seed(seed_),
      max_depth(max_depth_),
      snee(snee_),
      epsilon(e.ray_epsilon()),
      camera(camera_frame(s.camera)),
      width(s.camera.width),
      height(s.camera.height),
      pixel_spread(2.0f * image_half_extents(s.camera).y / static_cast<float>(s.camera.height)),
      textures(s.textures.empty() ? nullptr : std::make_shared<const TextureSet>(s.textures)) {
  if (snee.probe == ProbeDirections::kTowardLights || snee.guide_rate > 0)
    snee.probe_targets = probe_targets_of(s, l, snee.light_limit_degrees);
  media.reserve(s.media.size());
  for (const Medium& m : s.media) {
    const GridMedium grid =
        m.density ? GridMedium{m.density.get(), m.sigma_s, m.sigma_t(), m.g} : GridMedium{};
    has_grid_media = has_grid_media || m.density;
    media.push_back({{m.sigma_s, m.sigma_t(), m.g}, grid, true});
  }
  std::vector<int> boundaries(s.media.size(), 0);
  surfaces.reserve(s.shapes.size());
  for (const Shape& shape : s.shapes) {
    const Material& mat = s.materials.at(static_cast<size_t>(shape.material));
    SurfaceInfo info{mat.kind,
                     {mat.ior, mat.roughness},
                     mat.albedo,
                     shape.interior_medium,
                     !is_black(shape.emission),
                     {mat.conductor_eta, mat.conductor_k, mat.roughness},
                     {mat.albedo, mat.transmittance},
                     Rgb(0.0f),
                     shape.smooth_shading};
    info.aov_albedo = aov_albedo(info);
    info.closed = shape.closed;
    info.albedo_texture = mat.albedo_texture;
    info.roughness_texture = mat.roughness_texture;
    info.roughness_texture_squared = mat.roughness_texture_squared;
    surfaces.push_back(info);
    if (mat.kind == MaterialKind::kNull) has_null_surfaces = true;
    if (shape.interior_medium >= 0 && mat.kind != MaterialKind::kNull) {
      media[static_cast<size_t>(shape.interior_medium)].straight_nee = false;
      ++boundaries[static_cast<size_t>(shape.interior_medium)];
    }
  }
  for (size_t i = 0; i < s.shapes.size(); ++i) {
    const Shape& shape = s.shapes[i];
    const SurfaceInfo& info = surfaces[i];
    if (shape.interior_medium < 0 || info.kind != MaterialKind::kDielectric ||
        info.dielectric.eta == 1.0f) {
      continue;
    }
    MediumInfo& inside = media[static_cast<size_t>(shape.interior_medium)];
    if (integ == Integrator::kSnee && snee_.guide_rate > 0 && inside.snee_eligible() &&
        boundaries[static_cast<size_t>(shape.interior_medium)] == 1 && info.roughness_texture < 0) {
      if (shape.kind == ShapeKind::kSphere) {
        inside.guide_boundary = static_cast<int32_t>(i);
        inside.guide_centre = shape.center;
        inside.guide_radius = shape.radius;
      } else if (shape.kind == ShapeKind::kMesh && shape.closed && !shape.smooth_shading) {
        if (build_guide_trees(shape, info.dielectric, snee.probe_targets, budget, inside))
          inside.guide_boundary = static_cast<int32_t>(i);
      }
    }
    if (!info.dielectric.delta()) continue;
    MediumInfo& m = media[static_cast<size_t>(shape.interior_medium)];
    // The manifold strategy is SNEE's; a grid medium runs none of SNEE.
    if (!m.snee_eligible()) continue;
    const bool only_boundary = boundaries[static_cast<size_t>(shape.interior_medium)] == 1;
    if (only_boundary && shape.kind == ShapeKind::kSphere) {
      m.manifold_boundary = static_cast<int32_t>(i);
      m.manifold_curvature = 1.0f / shape.radius;
      m.manifold_centre = shape.center;
      m.manifold_radius = shape.radius;
      m.manifold_interior_clear = nothing_reaches_into(s, i);
      m.chain_search = chain_search_probability(m.medium.sigma_t, shape.radius);
    } else if (only_boundary && shape.kind == ShapeKind::kMesh && shape.closed &&
               !shape.smooth_shading) {
      if (integ == Integrator::kSnee) {
        m.manifold_boundary = static_cast<int32_t>(i);
        build_facet_exit_trees(s, shape, info.dielectric.eta, snee_.reflection_chains,
                               snee_.mesh_chain_levels, budget, m);
      }
    } else {
      m.manifold_unsupported = true;
    }
  }
}

}  // namespace snee
