// Fixed-capacity work queues of one work unit. A queue is filled by one stage and drained by
// the next; filling is in slot order (a stable compaction), so no atomics are needed and the
// order never depends on timing.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#include "scene/embree_scene.h"

namespace snee {

template <typename T>
class AlignedArray {
 public:
  AlignedArray() = default;
  explicit AlignedArray(size_t n)
      : data_(static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}))), size_(n) {}
  T* data() const { return data_.get(); }
  T& operator[](size_t i) { return data_.get()[i]; }
  const T& operator[](size_t i) const { return data_.get()[i]; }
  size_t size() const { return size_; }

 private:
  struct Delete {
    void operator()(T* p) const { ::operator delete (p, std::align_val_t{64}); }
  };
  std::unique_ptr<T, Delete> data_;
  size_t size_ = 0;
};

// A list of path slots waiting for one stage.
class SlotQueue {
 public:
  explicit SlotQueue(size_t capacity) : slots_(capacity) {}
  void clear() { size_ = 0; }
  void push(uint32_t slot) { slots_[size_++] = slot; }
  uint32_t operator[](size_t i) const { return slots_[i]; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const uint32_t* begin() const { return slots_.data(); }
  const uint32_t* end() const { return slots_.data() + size_; }

 private:
  AlignedArray<uint32_t> slots_;
  size_t size_ = 0;
};

// SNEE exit points found by the probe stage, waiting for subdivision: the slot of the medium
// vertex x_i and the probe's first hit x_k on that medium's dielectric boundary, with its
// geometric and shading normals and the interface's roughness there.
class ExitPointQueue {
 public:
  explicit ExitPointQueue(size_t capacity)
      : slot_(capacity),
        geom_(capacity),
        x_(capacity),
        y_(capacity),
        z_(capacity),
        nx_(capacity),
        ny_(capacity),
        nz_(capacity),
        snx_(capacity),
        sny_(capacity),
        snz_(capacity),
        alpha_(capacity) {}
  void clear() { size_ = 0; }
  bool empty() const { return size_ == 0; }
  size_t size() const { return size_; }
  void push(uint32_t slot, uint32_t geom, Vec3 x_k, Vec3 n_k, Vec3 ns_k, float alpha) {
    const size_t i = size_++;
    slot_[i] = slot;
    geom_[i] = geom;
    x_[i] = x_k.x;
    y_[i] = x_k.y;
    z_[i] = x_k.z;
    nx_[i] = n_k.x;
    ny_[i] = n_k.y;
    nz_[i] = n_k.z;
    snx_[i] = ns_k.x;
    sny_[i] = ns_k.y;
    snz_[i] = ns_k.z;
    alpha_[i] = alpha;
  }
  uint32_t slot(size_t i) const { return slot_[i]; }
  const uint32_t* slots() const { return slot_.data(); }
  // Component axis (0, 1, 2) of x_k and n_k by queue position, for batched loads.
  const float* x_k_component(int axis) const {
    return (axis == 0 ? x_ : axis == 1 ? y_ : z_).data();
  }
  const float* n_k_component(int axis) const {
    return (axis == 0 ? nx_ : axis == 1 ? ny_ : nz_).data();
  }
  const float* ns_k_component(int axis) const {
    return (axis == 0 ? snx_ : axis == 1 ? sny_ : snz_).data();
  }
  uint32_t geom(size_t i) const { return geom_[i]; }
  Vec3 x_k(size_t i) const { return {x_[i], y_[i], z_[i]}; }
  Vec3 n_k(size_t i) const { return {nx_[i], ny_[i], nz_[i]}; }
  Vec3 ns_k(size_t i) const { return {snx_[i], sny_[i], snz_[i]}; }
  float alpha(size_t i) const { return alpha_[i]; }

 private:
  AlignedArray<uint32_t> slot_, geom_;
  AlignedArray<float> x_, y_, z_, nx_, ny_, nz_, snx_, sny_, snz_, alpha_;
  size_t size_ = 0;
};

// Scratch arrays indexed by queue position are rounded up to 16 entries, a whole number of
// batches at every x86 SIMD width, so a short last chunk is stored with whole vector stores.
inline size_t padded_capacity(size_t n) {
  return (n + 15) / 16 * 16;
}

// What the batched part of medium_event computed for each entry of its queue: the sampled
// flight distance, the scattering point it reaches and the phase-sampled direction from there,
// with its pdf, and the event's roulette number.
struct FlightResults {
  explicit FlightResults(size_t capacity) {
    for (AlignedArray<float>* a : {&t, &x, &y, &z, &wx, &wy, &wz, &phase_pdf, &u_roulette})
      *a = AlignedArray<float>(padded_capacity(capacity));
  }
  AlignedArray<float> t, x, y, z, wx, wy, wz, phase_pdf, u_roulette;
};

// What shade_surface's batched part computed for each entry of its queue: the hit point and
// geometric normal, the dielectric's parameters there, its BSDF sample (the light-side
// direction in world space, the local cosine, f, pdf and flags kSurfaceSample*), and the
// event's light-sample and roulette numbers (drawn for the chunks that may use them).
inline constexpr uint32_t kSurfaceSampleValid = 1, kSurfaceSampleTransmission = 2,
                          kSurfaceSampleDelta = 4;
struct SurfaceResults {
  explicit SurfaceResults(size_t capacity) {
    for (AlignedArray<float>* a :
         {&px,         &py,         &pz,         &nx,         &ny,         &nz,           &snx,
          &sny,        &snz,        &eta,        &alpha,      &u_light0,   &u_light1,     &u_light2,
          &u_roulette, &bucket_snx, &bucket_sny, &bucket_snz, &bucket_eta, &bucket_alpha, &wx,
          &wy,         &wz,         &cos_local,  &f,          &pdf})
      *a = AlignedArray<float>(padded_capacity(capacity));
    for (AlignedArray<uint32_t>* a : {&light_sampled, &bucket_slots, &bucket_of, &flags})
      *a = AlignedArray<uint32_t>(padded_capacity(capacity));
  }
  // By queue position. n: the outward geometric normal; sn: the shading normal (n itself on
  // flat surfaces), the frame the dielectric is sampled in.
  AlignedArray<float> px, py, pz, nx, ny, nz, snx, sny, snz, eta, alpha;
  AlignedArray<float> u_light0, u_light1, u_light2, u_roulette;
  AlignedArray<uint32_t> light_sampled;  // 1 where the per-slot pass may sample a light

  // The dielectric bucket: the entries whose surface is a dielectric, in queue order, which
  // alone get the batched BSDF sample (no lane samples a dielectric for a diffuse hit).
  size_t bucket_size = 0;
  AlignedArray<uint32_t> bucket_slots;  // their slots
  AlignedArray<uint32_t> bucket_of;     // by queue position: the entry's index in the bucket
  // By bucket index: the sample's inputs (shading normal, interface) and its results.
  AlignedArray<float> bucket_snx, bucket_sny, bucket_snz, bucket_eta, bucket_alpha;
  AlignedArray<float> wx, wy, wz, cos_local, f, pdf;
  AlignedArray<uint32_t> flags;
};

// Rays and hits in Embree's SoA stream layout, so a batch is traced with no copy.
class RayBatch {
 public:
  explicit RayBatch(size_t capacity);
  void clear() { size_ = 0; }
  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  // Appends a ray; returns its index.
  uint32_t push(Vec3 origin, Vec3 direction, float tnear, float tfar);
  Vec3 origin(size_t i) const { return {org_x_[i], org_y_[i], org_z_[i]}; }
  Vec3 direction(size_t i) const { return {dir_x_[i], dir_y_[i], dir_z_[i]}; }
  float tfar(size_t i) const { return tfar_[i]; }
  uint32_t geom(size_t i) const { return geom_id_[i]; }
  uint32_t prim(size_t i) const { return prim_id_[i]; }
  bool occluded(size_t i) const { return tfar_[i] < 0; }
  RayArrays rays();
  HitArrays hits();

 private:
  size_t capacity_, size_ = 0;
  AlignedArray<float> org_x_, org_y_, org_z_, tnear_, dir_x_, dir_y_, dir_z_, time_, tfar_;
  AlignedArray<uint32_t> mask_, id_, flags_;
  AlignedArray<float> ng_x_, ng_y_, ng_z_, u_, v_;
  AlignedArray<uint32_t> prim_id_, geom_id_, inst_id_;
};

// Medium code of a shadow segment that only needs a visibility answer (no transmittance, no
// passing through index-matched boundaries): traced as a plain occlusion query.
inline constexpr int32_t kVisibilityOnly = -2;

// A pending light connection: radiance that reaches the path's pixel if every one of its
// segments is unoccluded. A SNEE or exit-event connection may also carry a `selector`
// segment whose visibility does not gate the contribution but picks between two MIS-weighted
// values (docs/method.md 3.6: the weight needs V_first(x_i, x_k)).
// What produced a connection, for the statistics of failed connections.
enum class ConnectionKind : uint8_t { kLight, kTopToBottom, kBottomToTop, kManifold };

struct ShadowConnection {
  ConnectionKind kind;
  uint32_t slot;
  uint32_t first_segment;
  uint32_t segment_count;    // gating segments, stored consecutively from first_segment
  int32_t selector_segment;  // -1 if none
  Rgb if_clear;              // contribution when the selector is clear (or absent)
  Rgb if_selector_blocked;
};

class ShadowQueue {
 public:
  explicit ShadowQueue(size_t segment_capacity);
  void clear();
  bool empty() const { return connections_.empty(); }
  size_t segment_count() const { return segments_.size(); }
  size_t segment_capacity() const { return segments_.capacity(); }
  // Adds a segment from origin along unit direction up to tmax, starting in `medium` (-1 =
  // vacuum, tracked through index-matched boundaries; kVisibilityOnly = plain occlusion).
  uint32_t add_segment(Vec3 origin, Vec3 direction, float tmax, int32_t medium);
  void add_connection(const ShadowConnection& c) { connections_.push_back(c); }

  std::vector<ShadowConnection>& connections() { return connections_; }
  RayBatch& segments() { return segments_; }
  std::vector<int32_t>& segment_media() { return media_; }
  std::vector<Rgb>& segment_transmittance() { return transmittance_; }
  // Scratch space for tracing segments boundary by boundary (kept to avoid reallocation).
  std::vector<uint32_t>& scratch_indices() { return scratch_indices_; }
  std::vector<Vec3>& scratch_origins() { return scratch_origins_; }
  std::vector<float>& scratch_lengths() { return scratch_lengths_; }

 private:
  std::vector<ShadowConnection> connections_;
  RayBatch segments_;
  std::vector<int32_t> media_;
  std::vector<Rgb> transmittance_;
  std::vector<uint32_t> scratch_indices_;
  std::vector<Vec3> scratch_origins_;
  std::vector<float> scratch_lengths_;
};

}  // namespace snee
