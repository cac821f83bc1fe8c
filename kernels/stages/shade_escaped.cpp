#include "kernels/stages/exit_event.h"
#include "kernels/stages/guided_exit.h"
#include "kernels/stages/stages.h"
#include "kernels/wavefront/path_ops.h"

namespace snee {

void shade_escaped(const KernelContext& ctx, PathState& state, StageQueues& q) {
  for (const uint32_t s : q.escaped) {
    const uint32_t flags = state.flags[s];
    const Vec3 d = state.direction(s);
    if (flags & kPathLightSkipped) {
      // "sla": the medium vertices' straight shadow rays already counted this light.
    } else if (flags & kPathAfterSneeExit) {
      // An exit that SNEE could also have produced: the four-strategy weight (exit_event.h).
      connect_exit_emission(ctx, state, s, d, ctx.lights->escaped_radiance(d),
                            ctx.lights->escaped_pdf(d), true, q.shadow);
    } else {
      const Rgb le = ctx.lights->escaped_radiance(d);
      if (!is_black(le)) {
        const float pdf = state.mis_pdf[s];
        const float weight = walk_bsdf_sample_weight(guide_ratio_after_exit(state, s), pdf,
                                                     ctx.lights->escaped_pdf(d), !(pdf > 0), true);
        state.add_radiance(s, state.throughput(s) * le * weight);
      }
    }
    q.retire.push(s);
  }
  q.escaped.clear();
}

}  // namespace snee
