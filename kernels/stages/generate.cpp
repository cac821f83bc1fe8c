#include <algorithm>

#include "kernels/physics/camera.h"
#include "kernels/simd/divide.h"
#include "kernels/simd/philox_batch.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/simd/vec3_batch.h"
#include "kernels/stages/stages.h"

namespace snee {

// Batched: each lane computes what random_block and camera_ray compute for its slot, exactly for
// a pinhole (tests/test_camera_batch.cpp); lanes are independent, so images do not depend on
// the batch width. A pinhole leaves the lens numbers u[2], u[3] unused.
void generate_camera_rays(const KernelContext& ctx, PathState& state, const uint32_t* slots,
                          const uint32_t* pixels, const uint32_t* samples, size_t n, StageQueues& q,
                          KernelCounters& counters) {
  using simd::FloatBatch;
  using simd::IntBatch;
  using simd::UintBatch;
  const FilmCamera camera = film_camera(ctx.camera, ctx.width, ctx.height);
  for (size_t begin = 0; begin < n; begin += simd::kLanes) {
    const size_t count = std::min(simd::kLanes, n - begin);
    const simd::SlotChunk chunk(slots + begin, count);
    const UintBatch pixel = simd::load_padded(pixels + begin, count);
    const UintBatch sample = simd::load_padded(samples + begin, count);
    const simd::RandomBlockBatch r =
        simd::random_block(ctx.seed, pixel, sample, UintBatch(0u), RngPurpose::kCamera, count);
    // divide()'s precondition: pixel indices below 2^31 (Film indexes pixels with int) and
    // image edges below 2^22, which the scene loader's limit of 2^16 guarantees.
    const simd::QuotientRemainder row_col = simd::divide(pixel, camera.width);
    const FloatBatch px = xsimd::to_float(xsimd::bitwise_cast<IntBatch>(row_col.remainder));
    const FloatBatch py = xsimd::to_float(xsimd::bitwise_cast<IntBatch>(row_col.quotient));
    simd::Vec3Batch o = splat<FloatBatch>(camera.frame.origin);
    simd::Vec3Batch d;
    if (camera.frame.thin_lens) {
      const CameraRayOf<FloatBatch> ray =
          thin_lens_ray(camera, px, py, r.u[0], r.u[1], r.u[2], r.u[3]);
      o = ray.origin;
      d = ray.direction;
    } else {
      d = camera_direction(camera, px, py, r.u[0], r.u[1]);
    }
    chunk.store(state.pixel, pixel);
    chunk.store(state.sample, sample);
    for (uint32_t* field : {state.event, state.depth}) chunk.store(field, UintBatch(0u));
    chunk.store(state.flags, UintBatch(ctx.record_aovs ? uint32_t{kPathAovOpen} : 0u));
    if (ctx.record_aovs) chunk.store(state.aov_depth, FloatBatch(0.0f));
    chunk.store(state.medium, IntBatch(-1));
    for (float* field :
         {state.throughput_r, state.throughput_g, state.throughput_b, state.eta_scale})
      chunk.store(field, FloatBatch(1.0f));
    for (float* field : {state.radiance_r, state.radiance_g, state.radiance_b, state.mis_pdf})
      chunk.store(field, FloatBatch(0.0f));
    // Spectral MIS starts with every colour channel equally likely to be the path's hero.
    for (float* field : {state.channel_p_r, state.channel_p_g, state.channel_p_b})
      chunk.store(field, FloatBatch(1.0f / 3.0f));
    chunk.store(state.origin_x, o.x);
    chunk.store(state.origin_y, o.y);
    chunk.store(state.origin_z, o.z);
    chunk.store(state.dir_x, d.x);
    chunk.store(state.dir_y, d.y);
    chunk.store(state.dir_z, d.z);
    counters.count_lanes(BatchedKernel::kCameraRays, count, simd::kLanes);
  }
  for (size_t i = 0; i < n; ++i) q.extend.push(slots[i]);
  counters.count_rays(RayKind::kCamera, n);
  counters.paths += n;
}

}  // namespace snee
