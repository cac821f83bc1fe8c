// Path state of one work unit in structure-of-arrays form. The field list is declared once
// (SNEE_PATH_FIELDS) and expanded into storage, the per-slot byte count reported in the stats,
// and the tests; adding a field is one line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#include "core/math.h"

namespace snee {

// Flags of a path slot.
enum PathFlags : uint32_t {
  kPathMediumVertexJ = 1u << 0,    // the previous vertex x_j was a medium scattering vertex
  kPathMediumVertexI = 1u << 1,    // the vertex before it, x_i, was a medium scattering vertex
  kPathAfterSneeExit = 1u << 2,    // the ray left a medium by an exit SNEE competes with
  kPathLightSkipped = 1u << 3,     // "sla": any light this ray reaches was counted by NEE
  kPathAovOpen = 1u << 4,          // AOVs: the camera ray's specular chain has not ended yet
  kPathInsideVolume = 1u << 5,     // the ray is inside a closed refracting or null boundary
  kPathAfterGuidedExit = 1u << 6,  // the ray left a medium by an exit the guided exit competes with
};

// X(type, name): one SoA array per field.
// clang-format off
#define SNEE_PATH_FIELDS(X)                                                                     \
  X(uint32_t, pixel)      /* film pixel index */                                                \
  X(uint32_t, sample)     /* sample index within the pixel */                                   \
  X(uint32_t, event)      /* RNG event counter, +1 per stage visit (null crossings included) */ \
  X(uint32_t, depth)      /* scattering events so far (null crossings excluded) */              \
  X(uint32_t, flags)      /* PathFlags */                                                       \
  X(int32_t, medium)      /* medium the ray travels in, -1 = none */                            \
  X(float, throughput_r) X(float, throughput_g) X(float, throughput_b)                          \
  X(float, radiance_r) X(float, radiance_g) X(float, radiance_b)                                \
  X(float, origin_x) X(float, origin_y) X(float, origin_z)                                      \
  X(float, dir_x) X(float, dir_y) X(float, dir_z)                                               \
  X(float, hit_t)         /* closest hit distance of the current ray (inf on a miss) */         \
  X(uint32_t, hit_geom)                                                                         \
  X(uint32_t, hit_prim)                                                                         \
  X(float, mis_pdf)       /* direction pdf at the last vertex if it also sampled lights */      \
  X(float, eta_scale)     /* undoes the eta^2 radiance scaling for Russian roulette */          \
  X(float, channel_p_r) X(float, channel_p_g) X(float, channel_p_b) /* spectral MIS weights */  \
  X(float, xj_x) X(float, xj_y) X(float, xj_z)     /* the latest vertex x_j (area-light MIS) */ \
  X(float, aov_albedo_r) X(float, aov_albedo_g) X(float, aov_albedo_b) /* first_hit_aovs.h */  \
  X(float, aov_normal_x) X(float, aov_normal_y) X(float, aov_normal_z)                         \
  X(float, aov_depth)

// SNEE's memory of the path, allocated only for the snee integrator (the only one that reads
// it): the vertex x_i before x_j, the directions arriving at both, and what an exit event
// SNEE competes with remembers until the next hit.
#define SNEE_PATH_SNEE_FIELDS(X)                                                                \
  X(float, xi_x) X(float, xi_y) X(float, xi_z)     /* medium vertex x_i */                      \
  X(float, win_x) X(float, win_y) X(float, win_z)  /* propagation direction arriving at x_i */  \
  X(float, wjn_x) X(float, wjn_y) X(float, wjn_z)  /* propagation direction arriving at x_j */ \
  X(uint32_t, exit_geom)                           /* the exit surface */                      \
  X(float, exit_xi_x) X(float, exit_xi_y) X(float, exit_xi_z)     /* x_i of the exit's suffix */ \
  X(float, exit_win_x) X(float, exit_win_y) X(float, exit_win_z)  /* arriving at that x_i */   \
  X(float, exit_nk_x) X(float, exit_nk_y) X(float, exit_nk_z)     /* normal at the exit x_k */ \
  X(float, exit_nsk_x) X(float, exit_nsk_y) X(float, exit_nsk_z)  /* its shading normal */     \
  X(float, exit_alpha)                           /* the interface's roughness at x_k */       \
  X(float, guide_ratio)        /* guided exit's density over the walk's at that exit */
// clang-format on

struct PathState {
#define SNEE_DECLARE_FIELD(type, name) type* name = nullptr;
  SNEE_PATH_FIELDS(SNEE_DECLARE_FIELD)
  SNEE_PATH_SNEE_FIELDS(SNEE_DECLARE_FIELD)  // null unless allocated
#undef SNEE_DECLARE_FIELD

  static constexpr size_t bytes_per_slot(bool snee_memory) {
    size_t bytes = 0;
#define SNEE_COUNT_FIELD(type, name) bytes += sizeof(type);
    SNEE_PATH_FIELDS(SNEE_COUNT_FIELD)
    if (snee_memory) {
      SNEE_PATH_SNEE_FIELDS(SNEE_COUNT_FIELD)
    }
#undef SNEE_COUNT_FIELD
    return bytes;
  }

  // snee_memory: whether to allocate SNEE_PATH_SNEE_FIELDS (the snee integrator needs them).
  PathState(size_t capacity, bool snee_memory) : capacity_(round_up(capacity)) {
    storage_.reset(static_cast<std::byte*>(
        ::operator new (capacity_* bytes_per_slot(snee_memory), std::align_val_t{64})));
    std::byte* p = storage_.get();
#define SNEE_ASSIGN_FIELD(type, name) \
  name = reinterpret_cast<type*>(p);  \
  p += capacity_ * sizeof(type);
    SNEE_PATH_FIELDS(SNEE_ASSIGN_FIELD)
    if (snee_memory) {
      SNEE_PATH_SNEE_FIELDS(SNEE_ASSIGN_FIELD)
    }
#undef SNEE_ASSIGN_FIELD
  }

  bool has_snee_memory() const {
    return xi_x != nullptr;
  }

  size_t capacity() const {
    return capacity_;
  }
  // Every field of every slot from a workspace of the same capacity (benchmarks rerun a stage
  // from one starting state).
  void copy_from(const PathState& other) {
    std::memcpy(storage_.get(), other.storage_.get(),
                capacity_ * bytes_per_slot(has_snee_memory()));
  }

  Rgb throughput(uint32_t s) const {
    return {throughput_r[s], throughput_g[s], throughput_b[s]};
  }
  void set_throughput(uint32_t s, Rgb v) {
    throughput_r[s] = v.x;
    throughput_g[s] = v.y;
    throughput_b[s] = v.z;
  }
  Rgb radiance(uint32_t s) const {
    return {radiance_r[s], radiance_g[s], radiance_b[s]};
  }
  void add_radiance(uint32_t s, Rgb v) {
    radiance_r[s] += v.x;
    radiance_g[s] += v.y;
    radiance_b[s] += v.z;
  }
  // Probabilities of the colour channels that free-flight sampling follows (free_flight.h).
  Rgb channel_probabilities(uint32_t s) const {
    return {channel_p_r[s], channel_p_g[s], channel_p_b[s]};
  }
  void set_channel_probabilities(uint32_t s, Rgb p) {
    channel_p_r[s] = p.x;
    channel_p_g[s] = p.y;
    channel_p_b[s] = p.z;
  }
  Vec3 origin(uint32_t s) const {
    return {origin_x[s], origin_y[s], origin_z[s]};
  }
  Vec3 direction(uint32_t s) const {
    return {dir_x[s], dir_y[s], dir_z[s]};
  }
  void set_ray(uint32_t s, Vec3 o, Vec3 d) {
    origin_x[s] = o.x;
    origin_y[s] = o.y;
    origin_z[s] = o.z;
    dir_x[s] = d.x;
    dir_y[s] = d.y;
    dir_z[s] = d.z;
  }
  Vec3 vertex_i(uint32_t s) const {
    return {xi_x[s], xi_y[s], xi_z[s]};
  }
  Vec3 direction_in_i(uint32_t s) const {
    return {win_x[s], win_y[s], win_z[s]};
  }
  Vec3 vertex_j(uint32_t s) const {
    return {xj_x[s], xj_y[s], xj_z[s]};
  }
  Vec3 direction_in_j(uint32_t s) const {
    return {wjn_x[s], wjn_y[s], wjn_z[s]};
  }
  // Records a new vertex x (with the propagation direction arriving at it); x_j becomes x_i.
  void push_vertex(uint32_t s, Vec3 x, Vec3 w_arriving, bool medium_vertex) {
    const bool j_was_medium = (flags[s] & kPathMediumVertexJ) != 0;
    if (has_snee_memory()) {
      xi_x[s] = xj_x[s];
      xi_y[s] = xj_y[s];
      xi_z[s] = xj_z[s];
      win_x[s] = wjn_x[s];
      win_y[s] = wjn_y[s];
      win_z[s] = wjn_z[s];
      wjn_x[s] = w_arriving.x;
      wjn_y[s] = w_arriving.y;
      wjn_z[s] = w_arriving.z;
    }
    xj_x[s] = x.x;
    xj_y[s] = x.y;
    xj_z[s] = x.z;
    flags[s] = (flags[s] & ~(kPathMediumVertexI | kPathMediumVertexJ)) |
               (j_was_medium ? kPathMediumVertexI : 0u) | (medium_vertex ? kPathMediumVertexJ : 0u);
  }

 private:
  static size_t round_up(size_t n) {
    return (n + 15) & ~size_t{15};
  }
  struct AlignedDelete {
    void operator()(std::byte* p) const { ::operator delete (p, std::align_val_t{64}); }
  };
  std::unique_ptr<std::byte, AlignedDelete> storage_;
  size_t capacity_;
};

}  // namespace snee
