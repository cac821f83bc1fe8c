// The wavefront stage kernels. Each is a plain function over a queue slice: it reads the slots
// listed in its input queue, updates their path state and appends them to the queues of the
// stages that come next, in input order. None of them allocates, locks or touches files. Their
// order, inputs and contracts with each other are the stage table's (stage_table.h).
#pragma once

#include <algorithm>

#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/path_state.h"
#include "kernels/wavefront/queues.h"
#include "kernels/wavefront/subdivision_scratch.h"

namespace snee {

// Exit points of a mesh boundary one vertex connects (exit_event.cpp): a mesh has more exit
// points than the sphere's few, so more of them are connected in full.
inline constexpr int kMeshExitsConnected =
    kMaxSphereExits + static_cast<int>(kChainSegmentBudget) / 3;
// Shadow segments one slot may queue in one turn: top-to-bottom and bottom-to-top (3 each) or an
// exit event's, with room to spare, plus three per exit point of the manifold strategy (two and
// its V_first selector), on a mesh as on the sphere, plus its reflection chains
// (kChainSegmentBudget).
inline constexpr size_t kShadowSegmentsPerSlot =
    8 + 3 * static_cast<size_t>(std::max(kMaxSphereExits, kMeshExitsConnected)) +
    kChainSegmentBudget;

// The queues one work unit cycles through: the inputs of the stage table (stage_table.h) and
// the scratch of the stages' batched passes.
struct StageQueues {
  explicit StageQueues(size_t slots)
      : extend(slots),
        medium(slots),
        surface(slots),
        escaped(slots),
        probe(slots),
        subdivide(slots),
        retire(slots),
        flights(slots),
        surfaces(slots),
        subdivision(slots),
        rays(slots),
        shadow(slots * kShadowSegmentsPerSlot) {}
  SlotQueue extend;                // rays to trace
  SlotQueue medium;                // traced rays travelling inside a medium
  SlotQueue surface;               // rays that reached a surface
  SlotQueue escaped;               // rays that left the scene
  SlotQueue probe;                 // SNEE: medium vertices waiting for an exit-point probe
  ExitPointQueue subdivide;        // SNEE: probes that found the medium's exit, waiting for x_j
  SlotQueue retire;                // finished paths
  FlightResults flights;           // scratch of medium_event's batched part
  SurfaceResults surfaces;         // scratch of shade_surface's batched part
  SubdivisionScratch subdivision;  // scratch of the subdivision stage's passes
  RayBatch rays;                   // scratch for batched Embree queries
  ShadowQueue shadow;
};

// Starts camera paths in `slots` for (pixel, sample) pairs; appends them to q.extend.
void generate_camera_rays(const KernelContext& ctx, PathState& state, const uint32_t* slots,
                          const uint32_t* pixels, const uint32_t* samples, size_t n, StageQueues& q,
                          KernelCounters& counters);

// Traces q.extend in one batch and routes each slot to q.medium, q.surface or q.escaped.
void extend(const KernelContext& ctx, PathState& state, StageQueues& q, KernelCounters& counters);

// Free flight inside media: scatter (NEE, SNEE probe, phase sampling -> q.extend) or pass to
// the surface/escape queues.
void medium_event(const KernelContext& ctx, PathState& state, StageQueues& q,
                  KernelCounters& counters);

// Surface interactions: emission, null crossings, diffuse and dielectric BSDFs with NEE and MIS.
void shade_surface(const KernelContext& ctx, PathState& state, StageQueues& q,
                   KernelCounters& counters);

// Environment and distant lights seen by escaped rays; the path is retired.
void shade_escaped(const KernelContext& ctx, PathState& state, StageQueues& q);

// SNEE exit-point query: traces the probes of q.probe in one batch; those whose first hit is
// the medium's own dielectric boundary, reached from inside, go on to q.subdivide.
void snee_probe(const KernelContext& ctx, PathState& state, StageQueues& q,
                KernelCounters& counters);

// SNEE subdivision: places the middle vertex x_j of every exit point in q.subdivide with the
// enabled strategies (top-to-bottom, bottom-to-top) and queues their shadow connections.
void subdivision(const KernelContext& ctx, PathState& state, StageQueues& q,
                 KernelCounters& counters);

// Resolves every pending light connection in batches and adds the visible ones' radiance.
void shadow_connect(const KernelContext& ctx, PathState& state, StageQueues& q,
                    KernelCounters& counters);

}  // namespace snee
