// What the SNEE stages count, for the statistics JSON: how often each step of a subdivision
// connection ran, succeeded or failed, and why it failed.
#pragma once

#include <array>
#include <cstdint>

namespace snee {

enum class SneeCounter : int {
  kProbes,                  // exit-point probe rays traced
  kProbesSkipped,           // medium vertices the probe rate left without one
  kProbeMissed,             // the probe left the scene (an open boundary)
  kProbeOtherSurface,       // its first hit was not this medium's dielectric boundary
  kTopToBottomConnections,  // TB candidates queued for visibility
  kBottomToTopConnections,  // BT candidates queued for visibility
  kTopToBottomNoLight,      // TB: no distant light sample above the exit point's horizon
  kTopToBottomRefraction,   // TB: the inward transmission sample failed (TIR, wrong side)
  kTopToBottomZero,         // TB: the distance sample or the contribution failed
  kBottomToTopPlacement,    // BT: the middle vertex fell on the outer side of the exit point
  kBottomToTopRefraction,   // BT: the outward transmission sample failed (TIR, wrong side)
  kBottomToTopNoLight,      // BT: the outward direction sees no light
  kBottomToTopZero,         // BT: zero or non-finite contribution
  kTopToBottomOccluded,     // TB connections with a blocked segment
  kBottomToTopOccluded,     // BT connections with a blocked segment
  kConnectionRays,          // visibility segments of TB and BT connections
  kFourWayExitEvents,       // exit events of the walk weighted against SNEE (U_B, U_L)
  kScalarWeighings,         // TB/BT proposals whose float weighing left float's range
  kManifoldConnections,     // manifold-strategy connections queued (one per exit point found)
  kManifoldOccluded,        // manifold connections with a blocked segment
  kManifoldNoExit,          // medium vertices under a delta light with no exit point
  // Medium vertices under a delta light behind a smooth boundary the manifold strategy has no
  // solver for (a smooth-shaded mesh, several shapes; a point or spot light behind a mesh or
  // inside the sphere): their light through one refraction is not rendered.
  kManifoldUnsupportedBoundary,
  // Manifold connections along chains of internal reflections (docs/method.md 3.12, 3.14), one
  // per chain connected, and chains found but not connected: beyond the solutions one query
  // keeps (none in tests).
  kManifoldReflectionConnections,
  kManifoldReflectionDropped,
  // Mesh boundaries (docs/method.md 3.13, 3.14): medium vertices whose reflection-last light is
  // not searched (a point or spot light, or more reflections than the mesh's chain tree holds);
  // vertices that saw the light through more facets, or along more chains, than their shadow
  // segments can connect, and connected a random run of them (unbiased); exit points beyond
  // what one query returns (none seen in tests), not connected.
  kManifoldChainsUnsupported,
  kManifoldExitsSubsampled,
  kManifoldExitsDropped,
  // The guided exit (docs/method.md 3.15): connections queued (light- and BSDF-sampled), and
  // vertices where it ran and found no direction (no refraction toward a small light).
  kGuidedExitConnections,
  kGuidedExitNoAxis,
  kCount
};
inline constexpr int kSneeCounterCount = static_cast<int>(SneeCounter::kCount);
using SneeCounters = std::array<uint64_t, kSneeCounterCount>;

inline const char* snee_counter_name(SneeCounter c) {
  static const char* names[] = {"probes",
                                "probes_skipped",
                                "probe_missed",
                                "probe_other_surface",
                                "top_to_bottom_connections",
                                "bottom_to_top_connections",
                                "top_to_bottom_no_light",
                                "top_to_bottom_refraction_failed",
                                "top_to_bottom_zero",
                                "bottom_to_top_placement_failed",
                                "bottom_to_top_refraction_failed",
                                "bottom_to_top_no_light",
                                "bottom_to_top_zero",
                                "top_to_bottom_occluded",
                                "bottom_to_top_occluded",
                                "connection_rays",
                                "four_way_exit_events",
                                "scalar_weighings",
                                "manifold_connections",
                                "manifold_occluded",
                                "manifold_no_exit",
                                "manifold_unsupported_boundary",
                                "manifold_reflection_connections",
                                "manifold_reflection_dropped",
                                "manifold_chains_unsupported",
                                "manifold_exits_subsampled",
                                "manifold_exits_dropped",
                                "guided_exit_connections",
                                "guided_exit_no_axis"};
  static_assert(sizeof(names) / sizeof(names[0]) == kSneeCounterCount);
  return names[static_cast<int>(c)];
}

}  // namespace snee
