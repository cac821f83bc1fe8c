#include "kernels/wavefront/queues.h"

#include <cassert>

namespace snee {

uint32_t RayBatch::push(Vec3 origin, Vec3 direction, float tnear, float tfar) {
  // The stages size each batch for their worst case (e.g. kShadowSegmentsPerSlot).
  assert(size_ < capacity_);
  const size_t i = size_++;
  s_.org_x[i] = origin.x;
  s_.org_y[i] = origin.y;
  s_.org_z[i] = origin.z;
  s_.tnear[i] = tnear;
  s_.dir_x[i] = direction.x;
  s_.dir_y[i] = direction.y;
  s_.dir_z[i] = direction.z;
  s_.time[i] = 0.0f;
  s_.tfar[i] = tfar;
  s_.mask[i] = 0xFFFFFFFFu;
  s_.id[i] = static_cast<uint32_t>(i);
  s_.flags[i] = 0;
  s_.geom_id[i] = kInvalidId;
  s_.inst_id[i] = kInvalidId;
  s_.prim_id[i] = kInvalidId;
  return static_cast<uint32_t>(i);
}

RayArrays RayBatch::rays() {
  return {s_.org_x.data(), s_.org_y.data(), s_.org_z.data(), s_.tnear.data(),
          s_.dir_x.data(), s_.dir_y.data(), s_.dir_z.data(), s_.time.data(),
          s_.tfar.data(),  s_.mask.data(),  s_.id.data(),    s_.flags.data()};
}

HitArrays RayBatch::hits() {
  return {s_.ng_x.data(), s_.ng_y.data(),    s_.ng_z.data(),    s_.u.data(),
          s_.v.data(),    s_.prim_id.data(), s_.geom_id.data(), s_.inst_id.data()};
}

ShadowQueue::ShadowQueue(size_t segment_capacity) : segments_(segment_capacity) {
  connections_.reserve(segment_capacity);
  media_.reserve(segment_capacity);
  transmittance_.reserve(segment_capacity);
  scratch_indices_.reserve(segment_capacity);
  scratch_origins_.reserve(segment_capacity);
  scratch_lengths_.reserve(segment_capacity);
}

void ShadowQueue::clear() {
  connections_.clear();
  segments_.clear();
  media_.clear();
  transmittance_.clear();
}

uint32_t ShadowQueue::add_segment(Vec3 origin, Vec3 direction, float tmax, int32_t medium) {
  media_.push_back(medium);
  transmittance_.push_back(Rgb(1.0f));
  return segments_.push(origin, direction, 0.0f, tmax);
}

}  // namespace snee
