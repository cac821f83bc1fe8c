// Fixed-capacity work queues of one work unit. A queue is filled by one stage and drained by
// the next; filling is in slot order (a stable compaction), so no atomics are needed and the
// order never depends on timing.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#include "kernels/wavefront/aligned_array.h"
#include "kernels/wavefront/work_items.h"
#include "scene/embree_scene.h"

namespace snee {

// A list of path slots waiting for one stage.
class SlotQueue {
 public:
  explicit SlotQueue(size_t capacity) : slots_(capacity) {}
  void clear() { size_ = 0; }
  void push(uint32_t slot) { slots_[size_++] = slot; }
  uint32_t operator[](size_t i) const { return slots_[i]; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Compaction in place by a stage that reads the queue front to back: it writes the slots it
  // keeps at indices no further than it has read, then truncates to their count.
  void overwrite(size_t i, uint32_t slot) { slots_[i] = slot; }
  void truncate(size_t n) { size_ = n; }
  const uint32_t* begin() const { return slots_.data(); }
  const uint32_t* end() const { return slots_.data() + size_; }
  // Moves the slots for which first(slot) holds to the front, each group in its order, and
  // returns how many there are (a stage then runs each group its own way).
  template <class Predicate>
  size_t partition(Predicate first) {
    uint32_t* data = slots_.data();
    return static_cast<size_t>(std::stable_partition(data, data + size_, first) - data);
  }

 private:
  AlignedArray<uint32_t> slots_;
  size_t size_ = 0;
};

// SNEE exit points found by the probe stage, waiting for subdivision (ExitPointItems,
// work_items.h).
class ExitPointQueue {
 public:
  explicit ExitPointQueue(size_t capacity) : items_(capacity) {}
  void clear() { size_ = 0; }
  bool empty() const { return size_ == 0; }
  size_t size() const { return size_; }
  void push(uint32_t slot, uint32_t geom, Vec3 x_k, Vec3 n_k, Vec3 ns_k, float alpha) {
    const size_t i = size_++;
    items_.slot[i] = slot;
    items_.geom[i] = geom;
    items_.x[i] = x_k.x;
    items_.y[i] = x_k.y;
    items_.z[i] = x_k.z;
    items_.nx[i] = n_k.x;
    items_.ny[i] = n_k.y;
    items_.nz[i] = n_k.z;
    items_.snx[i] = ns_k.x;
    items_.sny[i] = ns_k.y;
    items_.snz[i] = ns_k.z;
    items_.alpha[i] = alpha;
  }
  uint32_t slot(size_t i) const { return items_.slot[i]; }
  const uint32_t* slots() const { return items_.slot.data(); }
  // Component axis (0, 1, 2) of x_k and n_k by queue position, for batched loads.
  const float* x_k_component(int axis) const {
    return (axis == 0 ? items_.x : axis == 1 ? items_.y : items_.z).data();
  }
  const float* n_k_component(int axis) const {
    return (axis == 0 ? items_.nx : axis == 1 ? items_.ny : items_.nz).data();
  }
  const float* ns_k_component(int axis) const {
    return (axis == 0 ? items_.snx : axis == 1 ? items_.sny : items_.snz).data();
  }
  uint32_t geom(size_t i) const { return items_.geom[i]; }
  Vec3 x_k(size_t i) const { return {items_.x[i], items_.y[i], items_.z[i]}; }
  Vec3 n_k(size_t i) const { return {items_.nx[i], items_.ny[i], items_.nz[i]}; }
  Vec3 ns_k(size_t i) const { return {items_.snx[i], items_.sny[i], items_.snz[i]}; }
  float alpha(size_t i) const { return items_.alpha[i]; }

 private:
  ExitPointItems items_;
  size_t size_ = 0;
};

// Rays and hits in Embree's SoA stream layout (RayStream, work_items.h), so a batch is traced
// with no copy.
class RayBatch {
 public:
  explicit RayBatch(size_t capacity) : capacity_(capacity), s_(capacity) {}
  void clear() { size_ = 0; }
  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  // Appends a ray; returns its index.
  uint32_t push(Vec3 origin, Vec3 direction, float tnear, float tfar);
  Vec3 origin(size_t i) const { return {s_.org_x[i], s_.org_y[i], s_.org_z[i]}; }
  Vec3 direction(size_t i) const { return {s_.dir_x[i], s_.dir_y[i], s_.dir_z[i]}; }
  float tfar(size_t i) const { return s_.tfar[i]; }
  uint32_t geom(size_t i) const { return s_.geom_id[i]; }
  uint32_t prim(size_t i) const { return s_.prim_id[i]; }
  bool occluded(size_t i) const { return s_.tfar[i] < 0; }
  RayArrays rays();
  HitArrays hits();

 private:
  size_t capacity_, size_ = 0;
  RayStream s_;
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
