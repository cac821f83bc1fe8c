#include "kernels/wavefront/queues.h"

namespace snee {

RayBatch::RayBatch(size_t capacity)
    : capacity_(capacity),
      org_x_(capacity),
      org_y_(capacity),
      org_z_(capacity),
      tnear_(capacity),
      dir_x_(capacity),
      dir_y_(capacity),
      dir_z_(capacity),
      time_(capacity),
      tfar_(capacity),
      mask_(capacity),
      id_(capacity),
      flags_(capacity),
      ng_x_(capacity),
      ng_y_(capacity),
      ng_z_(capacity),
      u_(capacity),
      v_(capacity),
      prim_id_(capacity),
      geom_id_(capacity),
      inst_id_(capacity) {}

uint32_t RayBatch::push(Vec3 origin, Vec3 direction, float tnear, float tfar) {
  const size_t i = size_++;
  org_x_[i] = origin.x;
  org_y_[i] = origin.y;
  org_z_[i] = origin.z;
  tnear_[i] = tnear;
  dir_x_[i] = direction.x;
  dir_y_[i] = direction.y;
  dir_z_[i] = direction.z;
  time_[i] = 0.0f;
  tfar_[i] = tfar;
  mask_[i] = 0xFFFFFFFFu;
  id_[i] = static_cast<uint32_t>(i);
  flags_[i] = 0;
  geom_id_[i] = kInvalidId;
  inst_id_[i] = kInvalidId;
  prim_id_[i] = kInvalidId;
  return static_cast<uint32_t>(i);
}

RayArrays RayBatch::rays() {
  return {org_x_.data(), org_y_.data(), org_z_.data(), tnear_.data(), dir_x_.data(), dir_y_.data(),
          dir_z_.data(), time_.data(),  tfar_.data(),  mask_.data(),  id_.data(),    flags_.data()};
}

HitArrays RayBatch::hits() {
  return {ng_x_.data(), ng_y_.data(),    ng_z_.data(),    u_.data(),
          v_.data(),    prim_id_.data(), geom_id_.data(), inst_id_.data()};
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
