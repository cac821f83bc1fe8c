#include "kernels/stages/exit_event.h"

#include <algorithm>
#include <cmath>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

// The suffix of an exit at x_k on surface geom, whose interface there is `interface` (its
// roughness texture applied) and whose normals are n_k (geometric) and ns_k (shading).
SneeSuffix exit_suffix(const KernelContext& ctx, Vec3 x_i, Vec3 omega_in, Vec3 x_j, Vec3 x_k,
                       Vec3 n_k, Vec3 ns_k, const DielectricParams& interface, uint32_t geom,
                       Vec3 omega_o, float light_pdf, bool delta, bool distant) {
  const SurfaceInfo& surface = ctx.surfaces[geom];
  const MediumInfo& m = ctx.media[static_cast<size_t>(surface.interior_medium)];
  SneeSuffix s;
  s.x_i = x_i;
  s.omega_in = omega_in;
  s.x_j = x_j;
  s.x_k = x_k;
  s.n_k = n_k;
  s.ns_k = ns_k;
  s.omega_o = omega_o;
  s.medium = m.medium;
  s.interface = interface;
  s.light_pdf = light_pdf;
  s.light_delta = delta;
  s.light_distant = distant;
  s.x_i_medium = true;
  s.x_j_medium = true;
  return s;
}

// A visibility segment from `from` to `stop_short` before `to`. A medium vertex can lie on the
// point it connects to (within the clearance of the boundary): nothing lies between them, and
// the empty segment still needs a unit direction, as Embree aborts on a NaN ray.
uint32_t add_visibility_segment(ShadowQueue& shadow, Vec3 from, Vec3 to, float stop_short) {
  const Vec3 d = to - from;
  const float distance = length(d);
  if (!(distance > 0)) return shadow.add_segment(from, Vec3(0, 0, 1), 0.0f, kVisibilityOnly);
  return shadow.add_segment(from, d / distance, std::max(0.0f, distance - stop_short),
                            kVisibilityOnly);
}

// Queues `unweighted` times the four-way weight of strategy st, chosen by V_first(x_i, x_k),
// gated by the segments [first, first + count).
void queue_weighted(const KernelContext& ctx, Strategy st, const SneeSuffix& s, uint32_t slot,
                    Rgb unweighted, uint32_t first, uint32_t count, ShadowQueue& shadow,
                    ConnectionKind kind = ConnectionKind::kLight) {
  const ExitWeights w = snee_exit_weights(st, s, ctx.snee);
  const float w_first = static_cast<float>(w.if_first_hit);
  const float w_not_first = static_cast<float>(w.if_not_first_hit);
  // V_first as a segment from x_i toward x_k that stops just short of it.
  const uint32_t selector = add_visibility_segment(shadow, s.x_i, s.x_k, ctx.epsilon);
  shadow.add_connection({kind, slot, first, count, static_cast<int32_t>(selector),
                         unweighted * w_first, unweighted * w_not_first});
}

}  // namespace

ExitEvent make_exit_event(const KernelContext& ctx, const PathState& state, uint32_t slot, Vec3 p,
                          Vec3 n, Vec3 ns, const SurfaceInfo& info, uint32_t geom) {
  ExitEvent e;
  const Vec3 d = state.direction(slot);
  const bool leaving_medium = dot(d, n) > 0 && state.medium[slot] >= 0 &&
                              info.kind == MaterialKind::kDielectric &&
                              info.interior_medium == state.medium[slot];
  const uint32_t flags = state.flags[slot];
  const bool after_medium_vertex = (flags & kPathMediumVertexJ) != 0;
  if (ctx.integrator == Integrator::kStraightLine) {
    e.light_handled_elsewhere = leaving_medium && after_medium_vertex;
    return e;
  }
  // SNEE competes only for exits from media it runs in (MediumInfo::snee_eligible).
  if (ctx.integrator != Integrator::kSnee || !leaving_medium || !after_medium_vertex ||
      (flags & kPathMediumVertexI) == 0 ||
      !ctx.media[static_cast<size_t>(state.medium[slot])].snee_eligible()) {
    return e;
  }
  e.snee_possible = true;
  e.x_i = state.vertex_i(slot);
  e.omega_in = state.direction_in_i(slot);
  e.x_j = state.vertex_j(slot);
  e.x_k = p;
  e.n_k = n;
  e.ns_k = ns;
  e.interface = info.dielectric;
  e.geom = geom;
  return e;
}

void connect_exit_light_sample(const KernelContext& ctx, uint32_t slot, const ExitEvent& exit,
                               Vec3 omega_o, float light_pdf, bool delta, bool distant,
                               Rgb unweighted, uint32_t segment, ShadowQueue& shadow) {
  const SneeSuffix s =
      exit_suffix(ctx, exit.x_i, exit.omega_in, exit.x_j, exit.x_k, exit.n_k, exit.ns_k,
                  exit.interface, exit.geom, omega_o, light_pdf, delta, distant);
  queue_weighted(ctx, Strategy::kUnidirectionalLight, s, slot, unweighted, segment, 1, shadow);
}

void remember_exit(PathState& state, uint32_t slot, const ExitEvent& exit) {
  state.flags[slot] |= kPathAfterSneeExit;
  state.exit_geom[slot] = exit.geom;
  state.exit_xi_x[slot] = exit.x_i.x;
  state.exit_xi_y[slot] = exit.x_i.y;
  state.exit_xi_z[slot] = exit.x_i.z;
  state.exit_win_x[slot] = exit.omega_in.x;
  state.exit_win_y[slot] = exit.omega_in.y;
  state.exit_win_z[slot] = exit.omega_in.z;
  state.exit_nk_x[slot] = exit.n_k.x;
  state.exit_nk_y[slot] = exit.n_k.y;
  state.exit_nk_z[slot] = exit.n_k.z;
  state.exit_nsk_x[slot] = exit.ns_k.x;
  state.exit_nsk_y[slot] = exit.ns_k.y;
  state.exit_nsk_z[slot] = exit.ns_k.z;
  state.exit_alpha[slot] = exit.interface.alpha;
}

void connect_exit_emission(const KernelContext& ctx, const PathState& state, uint32_t slot,
                           Vec3 omega_o, Rgb le, float light_pdf, bool distant,
                           ShadowQueue& shadow) {
  if (is_black(le)) return;
  // The exit pushed x_k, so the path's memory now holds x_j (as its x_i) and x_k (as its x_j);
  // null crossings since then push nothing.
  const uint32_t geom = state.exit_geom[slot];
  const SneeSuffix s =
      exit_suffix(ctx, {state.exit_xi_x[slot], state.exit_xi_y[slot], state.exit_xi_z[slot]},
                  {state.exit_win_x[slot], state.exit_win_y[slot], state.exit_win_z[slot]},
                  state.vertex_i(slot), state.vertex_j(slot),
                  {state.exit_nk_x[slot], state.exit_nk_y[slot], state.exit_nk_z[slot]},
                  {state.exit_nsk_x[slot], state.exit_nsk_y[slot], state.exit_nsk_z[slot]},
                  {ctx.surfaces[geom].dielectric.eta, state.exit_alpha[slot]}, geom, omega_o,
                  light_pdf, false, distant);
  queue_weighted(ctx, Strategy::kUnidirectionalBsdf, s, slot, state.throughput(slot) * le, 0, 0,
                 shadow);
}

namespace {

// One reflection chain of the manifold strategy (docs/method.md 3.12, 3.14): the light
// refracted in at chain.y and reflected specularly inside (or, in a mesh, crossing out and in
// again) before it reaches x_j. No other strategy makes these paths under a delta light, so it
// counts with weight 1, over the probability of having searched its reflection count (`choice`)
// at a vertex where the strategy ran (`rate`) and of its having been connected (1 / share).
// `light` is the light as sampled at x_j, `at_y` as seen from the entry; `fresnel(F_r)` is the
// share of the light its reflections and crossings keep, given the entry's Fresnel
// reflectance; add_path_segments(shadow) queues the segments between x_j and the entry that
// can be blocked and returns how many.
template <typename Chain, typename Fresnel, typename AddPathSegments>
void connect_chain(const KernelContext& ctx, const PathState& state, uint32_t slot,
                   const MediumInfo& m, const DielectricParams& interface, const Chain& chain,
                   const LightSample& light, const LightSample& at_y, const ChainChoice& choice,
                   double share, float rate, const Fresnel& fresnel,
                   const AddPathSegments& add_path_segments, ShadowQueue& shadow,
                   KernelCounters& counters) {
  const Vec3 x_j = state.vertex_j(slot);
  const double cos_l = dot(chain.n, at_y.wi);
  if (!(at_y.pdf > 0) || !(cos_l > 0)) return;
  const double reflectance = fresnel_dielectric(static_cast<float>(cos_l), interface.eta);
  const double scale =
      share *
      hg_phase(dot(state.direction_in_j(slot), -chain.omega_last), m.medium.asymmetry(x_j)) *
      (1.0 - reflectance) * fresnel(reflectance) * cos_l /
      (chain.jacobian * light.pdf * choice.probability * rate);
  // The chain bends at its reflections; in a homogeneous medium (the manifold strategy's
  // premise) its transmittance is that of its total length inside.
  const Rgb unweighted =
      state.throughput(slot) * at_y.radiance *
      m.medium.transmittance(x_j, -chain.omega_last, static_cast<float>(chain.length)) *
      static_cast<float>(scale);
  if (is_black(unweighted) || !is_finite(unweighted)) return;
  const Vec3 outer = chain.y + ctx.epsilon * chain.n;
  const ShadowRay to_light = shadow_ray_to_light(at_y, chain.y, outer);
  const uint32_t first =
      shadow.add_segment(outer, to_light.direction, to_light.t_max, kVisibilityOnly);
  const uint32_t segments = 1 + add_path_segments(shadow);
  shadow.add_connection(
      {ConnectionKind::kManifold, slot, first, segments, -1, unweighted, Rgb(0.0f)});
  counters.count(SneeCounter::kManifoldReflectionConnections);
}

// The reflection count a vertex searches chains of (`u`), if any, within the depth limit: the
// walk would have spent one depth per reflection and one for the exit, so chains stop where the
// path tracer's depth limit would.
ChainChoice chain_choice(const KernelContext& ctx, const PathState& state, uint32_t slot,
                         const MediumInfo& m, float u) {
  ChainChoice choice = choose_chain_reflections(u, m.chain_search);
  const int depth_left = ctx.max_depth - static_cast<int>(state.depth[slot]) - 1;
  if (choice.reflections > depth_left) choice.reflections = 0;
  return choice;
}

// The sphere's chains (docs/method.md 3.12). `light_at(y)` is the light as seen from an entry
// point y (the same light; a point light's direction and irradiance there).
template <typename LightAt>
void connect_reflection_chains(const KernelContext& ctx, const PathState& state, uint32_t slot,
                               const MediumInfo& m, const Shape& sphere,
                               const DielectricParams& interface, const LightSample& light,
                               const LightAt& light_at, float u, float rate, ShadowQueue& shadow,
                               KernelCounters& counters) {
  const ChainChoice choice = chain_choice(ctx, state, slot, m, u);
  if (choice.reflections < 1 || choice.reflections > kMaxChainReflections) return;
  const Vec3 x_j = state.vertex_j(slot);
  const SphereChains chains =
      std::isinf(light.distance)
          ? sphere_reflection_chains_toward_light(sphere.center, sphere.radius, interface.eta,
                                                  light.wi, x_j, choice.reflections)
          : sphere_reflection_chains_toward_point(sphere.center, sphere.radius, interface.eta,
                                                  x_j + light.wi * light.distance, x_j,
                                                  choice.reflections);
  counters.count(SneeCounter::kManifoldReflectionDropped, static_cast<uint64_t>(chains.dropped));
  const size_t per_chain =
      m.manifold_interior_clear ? 1 : static_cast<size_t>(choice.reflections) + 2;
  // More chains than the segment budget holds: a run of those that fit, cyclically from a start
  // drawn with what the choice left of u, each standing for n / run (every chain is in the run
  // with probability run / n, so the estimate stays unbiased).
  const int n = chains.count;
  const int run = std::min(n, static_cast<int>(kChainSegmentBudget / per_chain));
  const int start = n > run ? std::min(static_cast<int>(choice.leftover * n), n - 1) : 0;
  if (n > run) counters.count(SneeCounter::kManifoldExitsSubsampled);
  const double share = static_cast<double>(n) / run;
  for (int k = 0; k < run; ++k) {
    const SphereChain& chain = chains.chain[static_cast<size_t>((start + k) % n)];
    // Every reflection meets the boundary at the refracted angle of the entry, so each
    // reflects the entry's Fresnel reflectance F_r (the same from both sides of the pair).
    const auto reflected = [&chain](double f) { return std::pow(f, chain.reflections); };
    // Unless nothing else reaches into the sphere, every chord can be blocked: from x_j back
    // along the light's path, to the last reflection, then chord by chord to the entry (each
    // ending just inside).
    const auto add_chords = [&](ShadowQueue& queue) -> uint32_t {
      if (m.manifold_interior_clear) return 0;
      Vec3 from = x_j;
      for (int b = chain.reflections - 1; b >= -1; --b) {
        const Vec3 q = b >= 0 ? chain.bounce[static_cast<size_t>(b)] : chain.y;
        const Vec3 to = q - ctx.epsilon * normalize(q - sphere.center);
        add_visibility_segment(queue, from, to, 0.0f);
        from = to;
      }
      return static_cast<uint32_t>(chain.reflections) + 1;
    };
    connect_chain(ctx, state, slot, m, interface, chain, light, light_at(chain.y), choice, share,
                  rate, reflected, add_chords, shadow, counters);
  }
}

// A mesh's chains under a directional light (docs/method.md 3.14): the tree returns a run of
// those that fit the segment budget, each standing for found / returned. The mesh itself can
// block every segment, so all are traced.
void connect_mesh_chains(const KernelContext& ctx, const PathState& state, uint32_t slot,
                         const MediumInfo& m, const FacetChainTree& tree,
                         const DielectricParams& interface, const LightSample& light, float u,
                         float rate, ShadowQueue& shadow, KernelCounters& counters) {
  const ChainChoice choice = chain_choice(ctx, state, slot, m, u);
  if (choice.reflections < 1) return;
  // Beyond the levels asked for (SneeOptions::mesh_chain_levels), or the memory allowance held.
  if (choice.reflections > tree.levels_solved()) {
    counters.count(SneeCounter::kManifoldChainsUnsupported);
    return;
  }
  // A crossing needs one segment more than a reflection.
  static_assert(2 * kMaxMeshChainLevels + 2 <= static_cast<int>(kChainSegmentBudget));
  const int per_chain = 2 * choice.reflections + 2;
  const Vec3 x_j = state.vertex_j(slot);
  const MeshChains chains = tree.chains_toward(
      x_j, choice.reflections, static_cast<int>(kChainSegmentBudget) / per_chain, choice.leftover);
  counters.count(SneeCounter::kManifoldReflectionDropped, static_cast<uint64_t>(chains.dropped));
  if (chains.found > chains.returned) counters.count(SneeCounter::kManifoldExitsSubsampled);
  const double share = static_cast<double>(chains.found) / std::max(1, chains.returned);
  const int depth_left = ctx.max_depth - static_cast<int>(state.depth[slot]) - 1;
  for (int k = 0; k < chains.returned; ++k) {
    const MeshChain& chain = chains.chain[static_cast<size_t>(k)];
    // A crossing spends two depths (out and in again).
    if (chain.events > depth_left) continue;
    const auto fresnel = [&chain](double) { return chain.fresnel; };
    // The mesh itself can block every stretch: from x_j back along the light's path, point by
    // point to the entry, each stretch ending just off the boundary on its own side (outside
    // where the light crossed out of the mesh).
    const auto add_stretches = [&](ShadowQueue& queue) -> uint32_t {
      Vec3 from = x_j;
      for (int b = chain.events - 1; b >= -1; --b) {
        const bool outside = b >= 0 && chain.leaves[static_cast<size_t>(b)];
        const Vec3 q = b >= 0 ? chain.point[static_cast<size_t>(b)] : chain.y;
        const Vec3 n = b >= 0 ? chain.normal[static_cast<size_t>(b)] : chain.n;
        if (outside) {
          // `from` lies just inside the point where the light came back in; start just outside.
          const Vec3 back_in = chain.point[static_cast<size_t>(b + 1)];
          from = back_in + ctx.epsilon * chain.normal[static_cast<size_t>(b + 1)];
        }
        const Vec3 to = q + (outside ? ctx.epsilon : -ctx.epsilon) * n;
        add_visibility_segment(queue, from, to, 0.0f);
        from = outside ? q - ctx.epsilon * n : to;
      }
      return static_cast<uint32_t>(chain.events) + 1;
    };
    connect_chain(ctx, state, slot, m, interface, chain, light, light, choice, share, rate, fresnel,
                  add_stretches, shadow, counters);
  }
}

// A mesh's exit points, connected by `connect(y, n, omega_r, t, share)`. A vertex deep in a
// folded mesh can see the light through dozens of facets (most of them behind another part of
// the mesh, which only the connection's rays find), more than the shadow segments one slot may
// queue: then a run of kMeshExitsConnected of them, cyclically from a start drawn with `u`, is
// connected, each standing for n / kMeshExitsConnected (every exit point is in the run with
// probability kMeshExitsConnected / n, so the estimate stays unbiased).
template <typename Connect>
void connect_mesh_exits(const MeshExits& exits, float u, const Connect& connect,
                        KernelCounters& counters) {
  counters.count(SneeCounter::kManifoldExitsDropped, static_cast<uint64_t>(exits.dropped));
  if (exits.count == 0) counters.count(SneeCounter::kManifoldNoExit);
  const int n = exits.count;
  const int run = std::min(n, kMeshExitsConnected);
  const int start = n > run ? std::min(static_cast<int>(u * static_cast<float>(n)), n - 1) : 0;
  if (n > run) counters.count(SneeCounter::kManifoldExitsSubsampled);
  const double share = static_cast<double>(n) / run;
  for (int k = 0; k < run; ++k) {
    const MeshExit& exit = exits.exit[static_cast<size_t>((start + k) % n)];
    connect(exit.y, exit.n, exit.omega_r, exit.t, share);
  }
}

}  // namespace

void connect_manifold(const KernelContext& ctx, const PathState& state, uint32_t slot,
                      const MediumInfo& m, ShadowQueue& shadow, KernelCounters& counters) {
  if (ctx.lights->empty() || (m.manifold_boundary < 0 && !m.manifold_unsupported)) return;
  const Vec3 x_j = state.vertex_j(slot);
  const RandomBlock r = draw(ctx, state, slot, RngPurpose::kSneeManifold);
  // Below the first scattering it runs at the rate SneeOptions::manifold_rate, decided by u[3],
  // which is then stretched back to a uniform number for the choices below.
  const bool x_i_medium = (state.flags[slot] & kPathMediumVertexI) != 0;
  const float rate = x_i_medium ? ctx.snee.manifold_rate : 1.0f;
  if (!(r.u[3] < rate)) return;
  const float u_choice = r.u[3] / rate;
  const LightSample light = ctx.lights->sample(x_j, r.u[0], {r.u[1], r.u[2]});
  // A spot light may leave x_j dark and still light the exit points, so only a directional
  // light's radiance can end the search here.
  const bool distant = std::isinf(light.distance);
  if (!light.delta || !(light.pdf > 0) || (distant && is_black(light.radiance))) return;
  if (!m.manifold_solves_for(light, x_j)) {
    counters.count(SneeCounter::kManifoldUnsupportedBoundary);
    return;
  }
  const FacetExitTree* mesh = distant ? m.manifold_tree(light.wi) : nullptr;
  const PointFacetTree* mesh_for_point = distant ? nullptr : m.manifold_point_tree(light.light);
  const size_t boundary = static_cast<size_t>(m.manifold_boundary);
  const DielectricParams& interface = ctx.surfaces[boundary].dielectric;
  const Vec3 w_before = state.direction_in_j(slot);
  SneeSuffix s;
  s.x_i = state.vertex_i(slot);
  s.omega_in = state.direction_in_i(slot);
  s.x_j = x_j;
  s.medium = m.medium;
  s.interface = interface;
  s.light_pdf = light.pdf;
  s.light_delta = true;
  s.light_distant = distant;
  s.x_i_medium = x_i_medium;
  s.x_j_medium = true;
  s.manifold = true;
  s.manifold_rate = rate;
  s.boundary_curvature = m.manifold_curvature;
  const Rgb beta = state.throughput(slot);
  // One exit point y (outward normal n) whose refracted light reaches x_j along omega_r after
  // t, its contribution scaled by `share` (the inverse of the probability it was chosen, the
  // rate aside: the rate is in the density the weights divide by).
  // A point or spot light as seen from an exit point y: its direction, distance and irradiance
  // there (the same light: the selection does not depend on the point).
  const auto light_at = [&](Vec3 y) {
    return distant ? light : ctx.lights->sample(y, r.u[0], {r.u[1], r.u[2]});
  };
  const auto connect = [&](Vec3 y, Vec3 n, Vec3 omega_r, double t, double share) {
    const LightSample at_y = light_at(y);
    const double cos_l = dot(n, at_y.wi);
    const double jacobian = refraction_volume_jacobian(n, at_y.wi, interface.eta,
                                                       m.manifold_curvature, t, at_y.distance);
    if (!(at_y.pdf > 0) || !(cos_l > 0) || !(jacobian > 0)) return;
    // docs/method.md 3.10: f_p T (1 - F_r) E cos_L / J per unit volume at x_j, over the
    // light's selection probability.
    const double scale = share * hg_phase(dot(w_before, -omega_r), m.medium.asymmetry(x_j)) *
                         (1.0 - fresnel_dielectric(static_cast<float>(cos_l), interface.eta)) *
                         cos_l / (jacobian * light.pdf * rate);
    const Rgb unweighted = beta * at_y.radiance *
                           m.medium.transmittance(x_j, -omega_r, static_cast<float>(t)) *
                           static_cast<float>(scale);
    if (is_black(unweighted) || !is_finite(unweighted)) return;
    s.x_k = y;
    s.n_k = s.ns_k = n;
    s.omega_o = at_y.wi;
    s.manifold_light_distance = at_y.distance;
    const Vec3 inner = y - ctx.epsilon * n, outer = y + ctx.epsilon * n;
    const uint32_t first = add_visibility_segment(shadow, x_j, inner, 0.0f);
    const ShadowRay to_light = shadow_ray_to_light(at_y, y, outer);
    shadow.add_segment(outer, to_light.direction, to_light.t_max, kVisibilityOnly);
    if (s.x_i_medium) {
      queue_weighted(ctx, Strategy::kManifold, s, slot, unweighted, first, 2, shadow,
                     ConnectionKind::kManifold);
    } else {
      // x_i is a surface vertex: no probe-based strategy competes, V_first does not matter.
      const float w = static_cast<float>(snee_exit_weight(Strategy::kManifold, s, ctx.snee));
      shadow.add_connection(
          {ConnectionKind::kManifold, slot, first, 2, -1, unweighted * w, Rgb(0.0f)});
    }
    counters.count(SneeCounter::kManifoldConnections);
  };
  if (mesh != nullptr || mesh_for_point != nullptr) {
    connect_mesh_exits(
        mesh != nullptr ? mesh->exits_toward(x_j) : mesh_for_point->exits_toward(x_j), u_choice,
        connect, counters);
    if (!ctx.snee.reflection_chains) return;
    const FacetChainTree* chains = distant ? m.manifold_chain_tree(light.wi) : nullptr;
    if (chains != nullptr) {
      connect_mesh_chains(ctx, state, slot, m, *chains, interface, light, u_choice, rate, shadow,
                          counters);
    } else if (chain_choice(ctx, state, slot, m, u_choice).reflections > 0) {
      // A point or spot light: where a chain would have been searched.
      counters.count(SneeCounter::kManifoldChainsUnsupported);
    }
    return;
  }
  const Shape& sphere = ctx.scene->shapes[boundary];
  const SphereExits exits =
      distant
          ? sphere_exits_toward_light(sphere.center, sphere.radius, interface.eta, light.wi, x_j)
          : sphere_exits_toward_point(sphere.center, sphere.radius, interface.eta,
                                      x_j + light.wi * light.distance, x_j);
  if (exits.count == 0) counters.count(SneeCounter::kManifoldNoExit);
  for (int e = 0; e < exits.count; ++e) {
    const SphereExit& exit = exits.exit[static_cast<size_t>(e)];
    connect(exit.y, exit.n, exit.omega_r, exit.t, 1.0);
  }
  if (ctx.snee.reflection_chains) {
    connect_reflection_chains(ctx, state, slot, m, sphere, interface, light, light_at, u_choice,
                              rate, shadow, counters);
  }
}

}  // namespace snee
