#include "kernels/path_ops.h"
#include "kernels/stages.h"

namespace snee {

StageQueues::StageQueues(size_t slots)
    : extend(slots),
      medium(slots),
      surface(slots),
      escaped(slots),
      probe(slots),
      retire(slots),
      rays(slots),
      shadow(slots * 8) {}

void generate_camera_rays(const KernelContext& ctx, PathState& state, const uint32_t* slots,
                          const uint32_t* pixels, const uint32_t* samples, size_t n, StageQueues& q,
                          KernelCounters& counters) {
  const float inv_w = 1.0f / static_cast<float>(ctx.width);
  const float inv_h = 1.0f / static_cast<float>(ctx.height);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t s = slots[i];
    state.pixel[s] = pixels[i];
    state.sample[s] = samples[i];
    state.event[s] = 0;
    state.depth[s] = 0;
    state.flags[s] = 0;
    state.medium[s] = -1;
    state.set_throughput(s, Rgb(1.0f));
    state.radiance_r[s] = state.radiance_g[s] = state.radiance_b[s] = 0.0f;
    state.mis_pdf[s] = 0.0f;
    state.eta_scale[s] = 1.0f;
    const RandomBlock r = draw(ctx, state, s, RngPurpose::kCamera);
    const float px = static_cast<float>(pixels[i] % static_cast<uint32_t>(ctx.width));
    const float py = static_cast<float>(pixels[i] / static_cast<uint32_t>(ctx.width));
    const float x = 2.0f * (px + r.u[0]) * inv_w - 1.0f;
    const float y = 1.0f - 2.0f * (py + r.u[1]) * inv_h;
    const Vec3 d = normalize(ctx.camera_forward + ctx.camera_right * x + ctx.camera_up * y);
    state.set_ray(s, ctx.camera_origin, d);
    q.extend.push(s);
  }
  counters.rays[0] += n;
  counters.paths += n;
}

}  // namespace snee
