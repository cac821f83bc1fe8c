// The work items and per-stage scratch records of a work unit, and the Embree ray streams, each
// declared once as its field list and generated as a structure of arrays (soa_record.h),
// indexed by queue position. The path state's own fields are listed in path_state.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "kernels/wavefront/soa_record.h"

namespace snee {

// SNEE exit points found by the probe stage, waiting for subdivision (ExitPointQueue): the slot
// of the medium vertex x_i and the probe's first hit x_k on that medium's dielectric boundary,
// with its geometric normal n and shading normal sn there and the interface's roughness.
// clang-format off
#define SNEE_EXIT_POINT_FIELDS(X)                                                               \
  X(uint32_t, slot) X(uint32_t, geom)                                                           \
  X(float, x) X(float, y) X(float, z)                                                           \
  X(float, nx) X(float, ny) X(float, nz)                                                        \
  X(float, snx) X(float, sny) X(float, snz)                                                     \
  X(float, alpha)
// clang-format on
SNEE_SOA_RECORD(ExitPointItems, SNEE_EXIT_POINT_FIELDS);

// What the batched part of medium_event computed for each entry of its queue: the sampled
// flight distance, the scattering point it reaches and the phase-sampled direction from there,
// with its pdf, and the event's roulette number.
// clang-format off
#define SNEE_FLIGHT_RESULT_FIELDS(X)                                                            \
  X(float, t)                                                                                   \
  X(float, x) X(float, y) X(float, z)                                                           \
  X(float, wx) X(float, wy) X(float, wz)                                                        \
  X(float, phase_pdf) X(float, u_roulette)
// clang-format on
SNEE_SOA_RECORD(FlightResults, SNEE_FLIGHT_RESULT_FIELDS);

// What shade_surface's batched part computed for each entry of its queue. By queue position:
// the hit point p and outward geometric normal n, the shading normal sn (n itself on flat
// surfaces, the frame the dielectric is sampled in), the dielectric's eta and alpha there, the
// event's light-sample and roulette numbers, and whether the per-slot pass may sample a light.
// The dielectric bucket holds the entries whose surface is a dielectric, in queue order, which
// alone get the batched BSDF sample (no lane samples a dielectric for a diffuse hit):
// bucket_slots their slots, bucket_of each queue position's index in the bucket, and by bucket
// index the sample's inputs (bucket_sn, eta, alpha) and its results: the light-side direction
// w in world space, the local cosine, f, pdf and flags kSurfaceSample*.
inline constexpr uint32_t kSurfaceSampleValid = 1, kSurfaceSampleTransmission = 2,
                          kSurfaceSampleDelta = 4;
// clang-format off
#define SNEE_SURFACE_RESULT_FIELDS(X)                                                           \
  X(float, px) X(float, py) X(float, pz)                                                        \
  X(float, nx) X(float, ny) X(float, nz)                                                        \
  X(float, snx) X(float, sny) X(float, snz)                                                     \
  X(float, eta) X(float, alpha)                                                                 \
  X(float, u_light0) X(float, u_light1) X(float, u_light2) X(float, u_roulette)                 \
  X(uint32_t, light_sampled)                                                                    \
  X(uint32_t, bucket_slots) X(uint32_t, bucket_of)                                              \
  X(float, bucket_snx) X(float, bucket_sny) X(float, bucket_snz)                                \
  X(float, bucket_eta) X(float, bucket_alpha)                                                   \
  X(float, wx) X(float, wy) X(float, wz)                                                        \
  X(float, cos_local) X(float, f) X(float, pdf)                                                 \
  X(uint32_t, flags)
// clang-format on
SNEE_SOA_RECORD(SurfaceArrays, SNEE_SURFACE_RESULT_FIELDS);
struct SurfaceResults : SurfaceArrays {
  using SurfaceArrays::SurfaceArrays;
  size_t bucket_size = 0;  // entries in the dielectric bucket
};

// How far a SNEE strategy's batched part got at an exit (StrategyResults::status).
inline constexpr uint32_t kSneeSampled = 0, kSneeNotPlaced = 1, kSneeNotRefracted = 2,
                          kSneeNoDistance = 3;

// A strategy's batched part at each exit of the subdivision queue: the middle vertex, the
// direction it found (bottom-to-top: omega_o; top-to-bottom keeps the light's), the sampling
// density and the status.
// clang-format off
#define SNEE_STRATEGY_RESULT_FIELDS(X)                                                          \
  X(float, x) X(float, y) X(float, z)                                                           \
  X(float, wx) X(float, wy) X(float, wz)                                                        \
  X(float, pdf)                                                                                 \
  X(uint32_t, status)
// clang-format on
SNEE_SOA_RECORD(StrategyResults, SNEE_STRATEGY_RESULT_FIELDS);

// Top-to-bottom's light sample at each exit in lanes: direction, pdf, whether it is a delta
// light, and whether it gives a usable direction (lit = 1).
// clang-format off
#define SNEE_TOP_TO_BOTTOM_LIGHT_FIELDS(X)                                                      \
  X(float, wx) X(float, wy) X(float, wz)                                                        \
  X(float, pdf) X(float, delta) X(float, lit)
// clang-format on
SNEE_SOA_RECORD(TopToBottomLightLanes, SNEE_TOP_TO_BOTTOM_LIGHT_FIELDS);

// The SNEE proposals waiting for the subdivision stage's batched weighing (ProposalQueue), by
// proposal index: the slot and strategy; the suffix (kernels/physics/snee/snee_suffix.h: the
// vertices x_i, x_j, x_k, the direction omega_in arriving at x_i, the normals n_k and ns_k at
// x_k and the direction omega_o to the light; the medium and the interface; the light's pdf and
// kind as 1 / 0; whether the manifold strategy shares it, with its rate, the boundary's
// curvature and the distance to its point light); the light's radiance, the sampling density and
// the three shadow segments (origin o, unit direction d and length t of each). A subdivision
// strategy's suffix always has x_i and x_j as medium vertices and x_k as the probe's first hit, so
// those flags are not stored.
// clang-format off
#define SNEE_PROPOSAL_SEGMENT(X, n) SNEE_SOA_VECTOR(X, o##n) SNEE_SOA_VECTOR(X, d##n) X(float, t##n)
#define SNEE_PROPOSAL_FIELDS(X)                                                                 \
  X(uint32_t, slot) X(uint32_t, strategy)                                                       \
  SNEE_SOA_VECTOR(X, xi) SNEE_SOA_VECTOR(X, win) SNEE_SOA_VECTOR(X, xj) SNEE_SOA_VECTOR(X, xk)    \
  SNEE_SOA_VECTOR(X, nk) SNEE_SOA_VECTOR(X, snk) SNEE_SOA_VECTOR(X, wo)                         \
  SNEE_SOA_VECTOR(X, sigma_s) SNEE_SOA_VECTOR(X, sigma_t)                                       \
  X(float, g) X(float, eta) X(float, alpha)                                                     \
  X(float, light_pdf) X(float, light_delta) X(float, light_distant)                             \
  X(uint32_t, manifold) X(float, manifold_rate) X(float, boundary_curvature)                    \
  X(float, manifold_light_distance)                                                             \
  X(float, emitted_r) X(float, emitted_g) X(float, emitted_b) X(double, sampling_pdf)           \
  SNEE_PROPOSAL_SEGMENT(X, 0) SNEE_PROPOSAL_SEGMENT(X, 1) SNEE_PROPOSAL_SEGMENT(X, 2)
// clang-format on
SNEE_SOA_RECORD(ProposalItems, SNEE_PROPOSAL_FIELDS);

// A stream of rays and their hits as Embree's stream queries read and write them (RTCRayNp and
// RTCHitNp take one pointer per field, so every field is an array of its own): RayBatch.
// clang-format off
#define SNEE_RAY_STREAM_FIELDS(X)                                                               \
  X(float, org_x) X(float, org_y) X(float, org_z) X(float, tnear)                               \
  X(float, dir_x) X(float, dir_y) X(float, dir_z) X(float, time) X(float, tfar)                 \
  X(uint32_t, mask) X(uint32_t, id) X(uint32_t, flags)                                          \
  X(float, ng_x) X(float, ng_y) X(float, ng_z) X(float, u) X(float, v)                          \
  X(uint32_t, prim_id) X(uint32_t, geom_id) X(uint32_t, inst_id)
// clang-format on
SNEE_SOA_RECORD(RayStream, SNEE_RAY_STREAM_FIELDS);

}  // namespace snee
