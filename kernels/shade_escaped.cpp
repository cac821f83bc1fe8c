#include "kernels/path_ops.h"
#include "kernels/stages.h"

namespace snee {

void shade_escaped(const KernelContext& ctx, PathState& state, StageQueues& q) {
  for (const uint32_t s : q.escaped) {
    // An exit that SNEE could also have produced was already turned into a deferred
    // connection with its four-strategy weight (exit_event.h).
    if ((state.flags[s] & (kPathEscapeDeferred | kPathLightSkipped)) == 0) {
      const Vec3 d = state.direction(s);
      const Rgb le = ctx.lights->escaped_radiance(d);
      if (!is_black(le)) {
        const float pdf = state.mis_pdf[s];
        const float weight = pdf > 0 ? power_heuristic(pdf, ctx.lights->escaped_pdf(d)) : 1.0f;
        state.add_radiance(s, state.throughput(s) * le * weight);
      }
    }
    q.retire.push(s);
  }
  q.escaped.clear();
}

}  // namespace snee
