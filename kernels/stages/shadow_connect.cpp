#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

namespace {

// Segments that must account for media and index-matched (or, for "sla", dielectric)
// boundaries are traced hit by hit; the number of boundaries one segment may pass is bounded
// so a degenerate scene cannot loop forever (a segment that runs out counts as blocked).
constexpr int kMaxBoundaryCrossings = 64;

void trace_tracked_segments(const KernelContext& ctx, StageQueues& q, KernelCounters& counters) {
  ShadowQueue& shadow = q.shadow;
  RayBatch& segments = shadow.segments();
  std::vector<int32_t>& media = shadow.segment_media();
  std::vector<Rgb>& transmittance = shadow.segment_transmittance();
  // Working copies of the tracked segments: current origin, remaining length, medium.
  RayBatch& batch = q.rays;
  std::vector<uint32_t>& active = shadow.scratch_indices();
  active.clear();
  for (uint32_t i = 0; i < segments.size(); ++i) {
    if (media[i] != kVisibilityOnly) active.push_back(i);
  }
  std::vector<Vec3>& origins = shadow.scratch_origins();
  std::vector<float>& remaining = shadow.scratch_lengths();
  origins.resize(segments.size());
  remaining.resize(segments.size());
  for (const uint32_t i : active) {
    origins[i] = segments.origin(i);
    remaining[i] = segments.tfar(i);
  }
  const bool pass_dielectrics = ctx.integrator == Integrator::kStraightLine;
  for (int round = 0; round < kMaxBoundaryCrossings && !active.empty(); ++round) {
    for (size_t start = 0; start < active.size(); start += batch.capacity()) {
      const size_t end = std::min(active.size(), start + batch.capacity());
      batch.clear();
      for (size_t k = start; k < end; ++k) {
        const uint32_t i = active[k];
        batch.push(origins[i], segments.direction(i), 0.0f, remaining[i]);
      }
      ctx.embree->intersect(batch.rays(), batch.hits(), static_cast<unsigned>(batch.size()), false);
      counters.count_rays(RayKind::kShadow, batch.size());
      for (size_t k = start; k < end; ++k) {
        const uint32_t i = active[k];
        const size_t b = k - start;
        const Vec3 d = segments.direction(i);
        const bool hit = batch.geom(b) != kInvalidId;
        const float t = hit ? batch.tfar(b) : remaining[i];
        if (media[i] >= 0 && std::isfinite(t)) {
          transmittance[i] *=
              ctx.media[static_cast<size_t>(media[i])].transmittance(origins[i], d, t);
        }
        if (!hit) {
          active[k] = kInvalidId;  // reached the light
          continue;
        }
        const uint32_t geom = batch.geom(b);
        const SurfaceInfo& info = ctx.surfaces[geom];
        const auto [p, n] = ctx.embree->surface_point(geom, batch.prim(b), origins[i] + d * t);
        bool passes = info.kind == MaterialKind::kNull;
        if (!passes && pass_dielectrics && info.kind == MaterialKind::kDielectric) {
          // Straight-line approximation: the ray goes through unbent, weighted by Fresnel
          // transmittance seen from the side it arrives on.
          const float cos_i = std::fabs(dot(d, n));
          const float eta = dot(d, n) < 0 ? info.dielectric.eta : 1.0f / info.dielectric.eta;
          transmittance[i] *= 1.0f - fresnel_dielectric(cos_i, eta);
          passes = true;
        }
        if (!passes || is_black(transmittance[i])) {
          transmittance[i] = Rgb(0.0f);
          active[k] = kInvalidId;
          continue;
        }
        media[i] = medium_after_crossing(ctx, geom, d, n);
        origins[i] = offset_origin(p, n, d, ctx.epsilon);
        remaining[i] = std::isinf(remaining[i]) ? kInfinity : remaining[i] - t;
        if (!(remaining[i] > 0)) active[k] = kInvalidId;
      }
    }
    std::erase(active, kInvalidId);
  }
  for (const uint32_t i : active) transmittance[i] = Rgb(0.0f);
}

// Plain visibility segments become batched occlusion queries; the answer is stored as a
// transmittance of 0 or 1 so every connection is resolved the same way.
void trace_visibility_segments(const KernelContext& ctx, StageQueues& q, KernelCounters& counters) {
  ShadowQueue& shadow = q.shadow;
  RayBatch& segments = shadow.segments();
  const std::vector<int32_t>& media = shadow.segment_media();
  std::vector<Rgb>& transmittance = shadow.segment_transmittance();
  RayBatch& batch = q.rays;
  std::vector<uint32_t>& index = shadow.scratch_indices();
  index.clear();
  for (uint32_t i = 0; i < segments.size(); ++i) {
    if (media[i] == kVisibilityOnly) index.push_back(i);
  }
  for (size_t start = 0; start < index.size(); start += batch.capacity()) {
    const size_t end = std::min(index.size(), start + batch.capacity());
    batch.clear();
    for (size_t k = start; k < end; ++k) {
      const uint32_t i = index[k];
      batch.push(segments.origin(i), segments.direction(i), 0.0f, segments.tfar(i));
    }
    ctx.embree->occluded(batch.rays(), static_cast<unsigned>(batch.size()));
    for (size_t k = start; k < end; ++k) {
      if (batch.occluded(k - start)) transmittance[index[k]] = Rgb(0.0f);
    }
  }
  counters.count_rays(RayKind::kShadow, index.size());
}

}  // namespace

void shadow_connect(const KernelContext& ctx, PathState& state, StageQueues& q,
                    KernelCounters& counters) {
  ShadowQueue& shadow = q.shadow;
  if (shadow.empty()) return;
  trace_visibility_segments(ctx, q, counters);
  trace_tracked_segments(ctx, q, counters);
  const std::vector<Rgb>& transmittance = shadow.segment_transmittance();
  for (const ShadowConnection& c : shadow.connections()) {
    Rgb gate(1.0f);
    for (uint32_t k = c.first_segment; k < c.first_segment + c.segment_count; ++k)
      gate *= transmittance[k];
    if (is_black(gate)) {
      if (c.kind == ConnectionKind::kTopToBottom) counters.count(SneeCounter::kTopToBottomOccluded);
      if (c.kind == ConnectionKind::kBottomToTop) counters.count(SneeCounter::kBottomToTopOccluded);
      if (c.kind == ConnectionKind::kManifold) counters.count(SneeCounter::kManifoldOccluded);
      continue;
    }
    const bool selector_clear =
        c.selector_segment < 0 || !is_black(transmittance[static_cast<size_t>(c.selector_segment)]);
    state.add_radiance(c.slot, gate * (selector_clear ? c.if_clear : c.if_selector_blocked));
  }
  shadow.clear();
}

}  // namespace snee
