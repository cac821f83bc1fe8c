#include <algorithm>
#include <array>

#include "kernels/physics/bsdf/conductor.h"
#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/physics/bsdf/diffuse.h"
#include "kernels/physics/bsdf/diffuse_transmission.h"
#include "kernels/simd/dielectric_batch.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/stages/exit_event.h"
#include "kernels/stages/first_hit_aovs.h"
#include "kernels/stages/guided_exit.h"
#include "kernels/stages/shading_normal.h"
#include "kernels/stages/stages.h"
#include "kernels/stages/surface_texture.h"
#include "kernels/wavefront/batched_pass.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

using simd::FloatBatch;
using simd::UintBatch;

// Hit point, normals and interface of every queued surface hit, by queue position, and the
// dielectric bucket with its sampling inputs; the padding after the last entry of either
// repeats the first, so whole batches read defined values.
void gather_hits(const KernelContext& ctx, const PathState& state, const SlotQueue& queue,
                 SurfaceResults& out) {
  const size_t n = queue.size();
  size_t bucket = 0;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t s = queue[k];
    const uint32_t geom = state.hit_geom[s];
    const auto [p, normal] = ctx.embree->surface_point(
        geom, state.hit_prim[s], state.origin(s) + state.direction(s) * state.hit_t[s]);
    const SurfaceInfo& info = ctx.surfaces[geom];
    const Vec3 shading = shading_normal(ctx, geom, state.hit_prim[s], p, normal);
    out.px[k] = p.x, out.py[k] = p.y, out.pz[k] = p.z;
    out.nx[k] = normal.x, out.ny[k] = normal.y, out.nz[k] = normal.z;
    out.snx[k] = shading.x, out.sny[k] = shading.y, out.snz[k] = shading.z;
    // Only a dielectric's interface is read (textured_surface); the others get the default.
    const DielectricParams interface = info.kind == MaterialKind::kDielectric
                                           ? dielectric_at(ctx, info, geom, state.hit_prim[s], p)
                                           : DielectricParams{};
    out.eta[k] = interface.eta, out.alpha[k] = interface.alpha;
    if (info.kind == MaterialKind::kDielectric) {
      out.bucket_of[k] = static_cast<uint32_t>(bucket);
      out.bucket_slots[bucket] = s;
      out.bucket_snx[bucket] = shading.x, out.bucket_sny[bucket] = shading.y;
      out.bucket_snz[bucket] = shading.z;
      out.bucket_eta[bucket] = interface.eta, out.bucket_alpha[bucket] = interface.alpha;
      ++bucket;
    }
    // The per-slot pass samples a light at every surface but null and delta ones.
    out.light_sampled[k] = info.kind != MaterialKind::kNull && !info.delta();
  }
  out.bucket_size = bucket;
  const auto pad = [](size_t size, std::initializer_list<AlignedArray<float>*> fields) {
    for (size_t k = size; k < (size + simd::kLanes - 1) / simd::kLanes * simd::kLanes; ++k) {
      for (AlignedArray<float>* field : fields) (*field)[k] = (*field)[0];
    }
  };
  pad(n, {&out.px, &out.py, &out.pz, &out.nx, &out.ny, &out.nz, &out.snx, &out.sny, &out.snz});
  pad(bucket,
      {&out.bucket_snx, &out.bucket_sny, &out.bucket_snz, &out.bucket_eta, &out.bucket_alpha});
}

// The light-sample and roulette numbers of one chunk of the queue at position k.
void draw_chunk(const KernelContext& ctx, const PathState& state, const simd::SlotChunk& chunk,
                SurfaceResults& out, size_t k) {
  const UintBatch pixel = chunk.load(state.pixel), sample = chunk.load(state.sample);
  const UintBatch event = chunk.load(state.event);
  // Only for chunks where some path may use them (a non-delta surface; the fourth vertex on),
  // so the one-slot megakernel draws what it needs.
  if (!ctx.lights->empty() &&
      std::any_of(out.light_sampled.data() + k, out.light_sampled.data() + k + chunk.count(),
                  [](uint32_t b) { return b != 0; })) {
    const simd::RandomBlockBatch light =
        simd::random_block(ctx.seed, pixel, sample, event, RngPurpose::kLightSample, chunk.count());
    light.u[0].store_aligned(out.u_light0.data() + k);
    light.u[1].store_aligned(out.u_light1.data() + k);
    light.u[2].store_aligned(out.u_light2.data() + k);
  }
  if (xsimd::any(chunk.load(state.depth) >= UintBatch(3u))) {
    simd::random_block(ctx.seed, pixel, sample, event, RngPurpose::kRussianRoulette, chunk.count())
        .u[0]
        .store_aligned(out.u_roulette.data() + k);
  }
}

// The dielectric BSDF sample of one chunk of the dielectric bucket at index j, in the frame of
// the shading normal (the geometric one on flat surfaces), as the per-slot pass would draw it.
// The side rule of a smooth-shaded surface is the per-slot pass's, which knows the surface.
void sample_dielectric_chunk(const KernelContext& ctx, const PathState& state,
                             const simd::SlotChunk& chunk, SurfaceResults& out, size_t j) {
  const auto at = [j](const AlignedArray<float>& a) {
    return FloatBatch::load_aligned(a.data() + j);
  };
  const simd::FrameBatch frame =
      simd::FrameBatch::from_normal({at(out.bucket_snx), at(out.bucket_sny), at(out.bucket_snz)});
  const simd::Vec3Batch wo = frame.to_local(
      simd::negate({chunk.load(state.dir_x), chunk.load(state.dir_y), chunk.load(state.dir_z)}));
  const simd::RandomBlockBatch r =
      simd::random_block(ctx.seed, chunk.load(state.pixel), chunk.load(state.sample),
                         chunk.load(state.event), RngPurpose::kBsdf, chunk.count());
  const simd::BsdfSampleBatch bs = simd::dielectric_sample(
      simd::DielectricLanes{at(out.bucket_eta), at(out.bucket_alpha)}, wo, r.u[0], r.u[1], r.u[2]);
  const simd::Vec3Batch wi = frame.to_world(bs.wi);
  simd::store_aligned(wi, out.wx.data() + j, out.wy.data() + j, out.wz.data() + j);
  xsimd::abs(bs.wi.z).store_aligned(out.cos_local.data() + j);
  bs.f.store_aligned(out.f.data() + j);
  bs.pdf.store_aligned(out.pdf.data() + j);
  alignas(64) bool valid[simd::kLanes], transmission[simd::kLanes], delta[simd::kLanes];
  bs.valid.store_aligned(valid);
  bs.transmission.store_aligned(transmission);
  bs.delta.store_aligned(delta);
  for (size_t l = 0; l < simd::kLanes; ++l) {
    out.flags[j + l] = (valid[l] ? kSurfaceSampleValid : 0u) |
                       (transmission[l] ? kSurfaceSampleTransmission : 0u) |
                       (delta[l] ? kSurfaceSampleDelta : 0u);
  }
}

// The batched sample of bucket index k as the scalar BsdfSample (local z only as |cos|).
BsdfSample batched_sample(const SurfaceResults& r, size_t k) {
  BsdfSample bs;
  bs.wi = {0.0f, 0.0f, r.cos_local[k]};
  bs.f = r.f[k];
  bs.pdf = r.pdf[k];
  bs.valid = (r.flags[k] & kSurfaceSampleValid) != 0;
  bs.transmission = (r.flags[k] & kSurfaceSampleTransmission) != 0;
  bs.delta = (r.flags[k] & kSurfaceSampleDelta) != 0;
  return bs;
}

// The BSDF sample of the surfaces the per-slot pass samples (all but the dielectric), in the
// frame turned to wo's side, and its colour.
BsdfSample sample_opaque(const SurfaceInfo& info, Vec3 wo_local, const RandomBlock& r, Rgb* tint) {
  BsdfSample bs;
  switch (info.kind) {
    case MaterialKind::kConductor:
      bs = conductor_sample(info.conductor, wo_local, {r.u[0], r.u[1]});
      *tint = conductor_fresnel(info.conductor, wo_local, bs.wi);
      break;
    case MaterialKind::kDiffuseTransmission:
      bs = diffuse_transmission_sample(info.sheet, wo_local, {r.u[0], r.u[1]}, r.u[2]);
      *tint = diffuse_transmission_tint(info.sheet, wo_local, bs.wi);
      break;
    default:
      bs = diffuse_sample(wo_local, {r.u[0], r.u[1]});
      *tint = info.albedo;
  }
  return bs;
}

// Medium on the side of the surface that direction w points into.
int32_t medium_on_side(const SurfaceInfo& info, Vec3 w, Vec3 n) {
  return dot(w, n) >= 0 ? -1 : info.interior_medium;
}

// Whether the ray is inside the closed boundary it crosses after a crossing in direction w.
void track_inside(PathState& state, uint32_t s, const SurfaceInfo& info, Vec3 w, Vec3 n) {
  if (!info.closed) return;
  if (dot(w, n) < 0) {
    state.flags[s] |= kPathInsideVolume;
  } else {
    state.flags[s] &= ~kPathInsideVolume;
  }
}

bool needs_tracking(const KernelContext& ctx, int32_t medium) {
  return medium >= 0 || ctx.has_null_surfaces;
}

// Light sample at a non-delta surface vertex, weighted against BSDF sampling; u are the first
// three numbers of the event's kLightSample block. n is the geometric normal, ns the shading
// normal that `frame` is built on.
void surface_nee(const KernelContext& ctx, PathState& state, uint32_t s, Vec3 p, Vec3 n, Vec3 ns,
                 const Frame& frame, Vec3 wo_local, const SurfaceInfo& info, ShadowQueue& shadow,
                 const ExitEvent* exit, float guide_ratio, const std::array<float, 3>& u) {
  const LightSample ls = ctx.lights->sample(p, u[0], {u[1], u[2]});
  if (!ls.valid || ls.pdf <= 0) return;
  if (info.smooth_shading && !shading_sides_agree(-state.direction(s), ls.wi, n, ns)) {
    return;
  }
  const Vec3 wi_local = frame.to_local(ls.wi);
  float f = 0, bsdf_pdf = 0;
  Rgb reflectance(1.0f);
  switch (info.kind) {
    case MaterialKind::kDiffuse:
      f = diffuse_eval(wo_local, wi_local);
      bsdf_pdf = diffuse_pdf(wo_local, wi_local);
      reflectance = info.albedo;
      break;
    case MaterialKind::kConductor:
      f = conductor_eval(info.conductor, wo_local, wi_local);
      bsdf_pdf = conductor_pdf(info.conductor, wo_local, wi_local);
      reflectance = conductor_fresnel(info.conductor, wo_local, wi_local);
      break;
    case MaterialKind::kDiffuseTransmission:
      f = diffuse_transmission_eval(wo_local, wi_local);
      bsdf_pdf = diffuse_transmission_pdf(info.sheet, wo_local, wi_local);
      reflectance = diffuse_transmission_tint(info.sheet, wo_local, wi_local);
      break;
    default:
      f = dielectric_eval(info.dielectric, wo_local, wi_local);
      bsdf_pdf = dielectric_pdf(info.dielectric, wo_local, wi_local);
  }
  if (f <= 0) return;
  const Rgb unweighted =
      state.throughput(s) * reflectance * ls.radiance * (f * std::fabs(wi_local.z) / ls.pdf);
  const Vec3 origin = offset_origin(p, n, ls.wi, ctx.epsilon);
  const ShadowRay ray = shadow_ray_to_light(ls, p, origin);
  const int32_t medium = needs_tracking(ctx, medium_on_side(info, ls.wi, n))
                             ? medium_on_side(info, ls.wi, n)
                             : kVisibilityOnly;
  const uint32_t seg = shadow.add_segment(origin, ray.direction, ray.t_max, medium);
  if (exit && exit->snee_possible && wi_local.z > 0) {
    // A light-sampled exit after two medium vertices: SNEE could have made this path too.
    connect_exit_light_sample(ctx, s, *exit, ls.wi, ls.pdf, ls.delta, std::isinf(ls.distance),
                              unweighted, seg, shadow);
    return;
  }
  // Only a light sample through the boundary competes with the guided exit (guided_exit.h).
  const float weight = walk_light_sample_weight(wi_local.z > 0 ? guide_ratio : 0.0f, ls.pdf,
                                                bsdf_pdf, ls.delta, std::isinf(ls.distance));
  shadow.add_connection({ConnectionKind::kLight, s, seg, 1, -1, unweighted * weight, Rgb(0.0f)});
}

}  // namespace

// Two passes: hit geometry, dielectric BSDF samples and random numbers for the whole queue (in
// SIMD chunks), then, per slot in queue order, what branches: emission, null crossings, exit
// events, light sampling, the other surfaces' BSDF sampling, roulette and routing.
void shade_surface(const KernelContext& ctx, PathState& state, StageQueues& q,
                   KernelCounters& counters) {
  SurfaceResults& hits = q.surfaces;
  const size_t n_hits = q.surface.size();
  gather_hits(ctx, state, q.surface, hits);
  for_each_chunk(q.surface.begin(), n_hits, [&](const simd::SlotChunk& chunk, size_t k) {
    draw_chunk(ctx, state, chunk, hits, k);
  });
  for_each_chunk(hits.bucket_slots.data(), hits.bucket_size, BatchedKernel::kSurfaceSamples,
                 counters, [&](const simd::SlotChunk& chunk, size_t j) {
                   sample_dielectric_chunk(ctx, state, chunk, hits, j);
                 });
  for (size_t k = 0; k < n_hits; ++k) {
    const uint32_t s = q.surface[k];
    const Vec3 d = state.direction(s);
    const Vec3 p{hits.px[k], hits.py[k], hits.pz[k]};
    const uint32_t geom = state.hit_geom[s];
    const Vec3 n{hits.nx[k], hits.ny[k], hits.nz[k]};
    const Vec3 ns{hits.snx[k], hits.sny[k], hits.snz[k]};  // n on flat surfaces
    SurfaceInfo textured;
    // A dielectric's interface is the one its batched sample took (gather_hits).
    const SurfaceInfo& info =
        textured_surface(ctx, ctx.surfaces[geom], geom, state.hit_prim[s], p, state.hit_t[s],
                         {hits.eta[k], hits.alpha[k]}, textured);
    // A closed boundary reached from the side the ray is not on: the ray grazed it where an
    // entry and an exit lie within float error of each other (at a silhouette edge), and the
    // closest hit found was the exit. Taken as a crossing it would be an exit without an
    // entry (eta^2 too much, FurnaceCrossing.*) or an entry without an exit. The ray crossed
    // the boundary twice at one point, so it goes on unchanged in its medium, as through a
    // null boundary; the flight that reached here was weighted like any boundary hit.
    if (info.closed &&
        (info.kind == MaterialKind::kDielectric || info.kind == MaterialKind::kNull) &&
        (dot(d, n) > 0) != ((state.flags[s] & kPathInsideVolume) != 0)) {
      extend_aov_chain(state, s, state.hit_t[s]);
      state.set_ray(s, offset_origin(p, n, d, ctx.epsilon), d);
      state.event[s] += 1;
      q.extend.push(s);
      continue;
    }
    const bool light_skipped = (state.flags[s] & kPathLightSkipped) != 0;
    const bool after_exit = (state.flags[s] & kPathAfterSneeExit) != 0;

    if (info.emissive && dot(d, n) < 0 && !light_skipped) {
      // The light pdf is the one NEE used at the path's last real vertex (null crossings in
      // between move the ray origin, not the vertex).
      const Rgb le = ctx.lights->area_radiance(static_cast<int>(geom), n, d);
      const auto light_pdf = [&] {
        return ctx.lights->area_pdf(static_cast<int>(geom), state.vertex_j(s), p, n);
      };
      if (after_exit) {
        connect_exit_emission(ctx, state, s, d, le, light_pdf(), false, q.shadow);
      } else {
        const float pdf = state.mis_pdf[s];
        const float weight = walk_bsdf_sample_weight(guide_ratio_after_exit(state, s), pdf,
                                                     light_pdf(), !(pdf > 0), false);
        state.add_radiance(s, state.throughput(s) * le * weight);
      }
    }

    if (info.kind == MaterialKind::kNull) {
      // An index-matched boundary only changes the medium; the ray goes on unchanged (and what
      // its last real vertex remembered stays valid).
      state.medium[s] = medium_after_crossing(ctx, geom, d, n);
      track_inside(state, s, info, d, n);
      extend_aov_chain(state, s, state.hit_t[s]);
      state.set_ray(s, offset_origin(p, n, d, ctx.epsilon), d);
      state.event[s] += 1;
      q.extend.push(s);
      continue;
    }
    state.flags[s] &= ~(kPathAfterSneeExit | kPathLightSkipped | kPathAfterGuidedExit);
    const bool delta_bsdf = info.delta();
    if (delta_bsdf) {
      extend_aov_chain(state, s, state.hit_t[s]);
    } else {
      // The normal faces the arriving ray.
      close_aov_chain(state, s, state.hit_t[s], info.aov_albedo, dot(d, n) > 0 ? -n : n);
    }

    // The exit-event bookkeeping of SNEE needs the vertices before this one.
    const ExitEvent exit = make_exit_event(ctx, state, s, p, n, ns, info, geom);
    const float guide_ratio = walk_guide_ratio(ctx, state, s, p, n, info, geom);
    if (exit.snee_possible) counters.count(SneeCounter::kFourWayExitEvents);
    state.depth[s] += 1;
    state.push_vertex(s, p, d, false);
    if (static_cast<int>(state.depth[s]) > ctx.max_depth) {
      q.retire.push(s);
      continue;
    }

    // Every surface but the dielectric interface scatters alike from both sides; the geometric
    // normal says which side the ray came from.
    const bool two_sided_flip = info.kind != MaterialKind::kDielectric && dot(d, n) > 0;
    const Vec3 shading_n = two_sided_flip ? -ns : ns;
    const Frame frame = Frame::from_normal(shading_n);
    const Vec3 wo_local = frame.to_local(-d);
    if (!delta_bsdf && !ctx.lights->empty() && !exit.light_handled_elsewhere) {
      surface_nee(ctx, state, s, p, n, ns, frame, wo_local, info, q.shadow,
                  exit.snee_possible ? &exit : nullptr, guide_ratio,
                  {hits.u_light0[k], hits.u_light1[k], hits.u_light2[k]});
    }

    BsdfSample bs;
    Vec3 wi;
    Rgb reflectance(1.0f);
    if (info.kind != MaterialKind::kDielectric) {
      const RandomBlock r = draw(ctx, state, s, RngPurpose::kBsdf);
      bs = sample_opaque(info, wo_local, r, &reflectance);
      wi = frame.to_world(bs.wi);
    } else {
      const uint32_t j = hits.bucket_of[k];
      bs = batched_sample(hits, j);
      wi = {hits.wx[j], hits.wy[j], hits.wz[j]};
    }
    if (!bs.valid || bs.pdf <= 0 || bs.f <= 0 ||
        (info.smooth_shading && !shading_sides_agree(-d, wi, n, ns))) {
      q.retire.push(s);
      continue;
    }
    state.set_throughput(s,
                         state.throughput(s) * reflectance * (bs.f * std::fabs(bs.wi.z) / bs.pdf));
    state.mis_pdf[s] = bs.delta ? 0.0f : bs.pdf;
    // A diffuse transmitter is a sheet: the medium and the index stay as they were.
    if (bs.transmission && info.kind == MaterialKind::kDielectric) {
      const bool entering = dot(wi, n) < 0;
      const float eta2 = info.dielectric.eta * info.dielectric.eta;
      state.eta_scale[s] *= entering ? eta2 : 1.0f / eta2;
      state.medium[s] = medium_on_side(info, wi, n);
      track_inside(state, s, info, wi, n);
      if (!entering && guide_ratio > 0) {
        state.flags[s] |= kPathAfterGuidedExit;
        state.guide_ratio[s] = guide_ratio;
      }
      if (!entering && exit.snee_possible) {
        remember_exit(state, s, exit);
      } else if (!entering && exit.light_handled_elsewhere) {
        state.flags[s] |= kPathLightSkipped;
      }
    }
    if (!survive_russian_roulette(state, s, hits.u_roulette[k])) {
      q.retire.push(s);
      continue;
    }
    state.set_ray(s, offset_origin(p, n, wi, ctx.epsilon), wi);
    state.event[s] += 1;
    q.extend.push(s);
  }
  q.surface.clear();
}

}  // namespace snee
