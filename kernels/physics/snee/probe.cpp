#include "kernels/physics/snee/probe.h"

#include <algorithm>
#include <vector>

#include "core/vec3d.h"
#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/snee/light_extent.h"
#include "scene/scene.h"
#include "scene/shape_bounds.h"

namespace snee {

Vec3 probe_direction_sample(const SneeOptions& options, Vec3 x_i, Vec3 omega_in, float g, Vec3 u) {
  return probe_direction_sample<float>(options, x_i, omega_in, g, u.x, u.y, u.z);
}

double probe_area_pdf(const SneeOptions& options, Vec3 omega_in, float g, Vec3 x_i, Vec3 x_k,
                      Vec3 n_k) {
  return probe_area_pdf<double>(options, Vec3d(omega_in), g, Vec3d(x_i), Vec3d(x_k), Vec3d(n_k));
}

ProbeTargets probe_targets_of(const Scene& scene, const LightTable& lights, float limit_degrees) {
  struct Candidate {
    ProbeTarget target;
    float pmf;
  };
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    const float pmf = lights.selection_pmf(static_cast<int>(i));
    if (!(pmf > 0) || light_half_angle_degrees(scene, light) > limit_degrees) continue;
    ProbeTarget target;
    switch (light.kind) {
      case LightKind::kDirectional:
      case LightKind::kCone:
        target.where = light.direction;
        target.delta = light.kind == LightKind::kDirectional;
        break;
      case LightKind::kPoint:
      case LightKind::kSpot:
        target.where = light.position;
        target.positional = true;
        target.delta = true;
        break;
      case LightKind::kArea: {
        ShapeBounds box;
        box.add(scene.shapes[static_cast<size_t>(light.shape)]);
        target.where = box.center();
        target.positional = true;
        break;
      }
      case LightKind::kConstantEnv:
      case LightKind::kEnvMap:
        continue;  // no direction to favour
    }
    candidates.push_back({target, pmf});
  }
  // Ties keep the scene's order, so the targets do not depend on the sort's implementation.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.pmf > b.pmf; });
  ProbeTargets out;
  out.count = static_cast<int>(std::min<size_t>(candidates.size(), kMaxProbeTargets));
  if (out.count == 0) return out;
  float total = 0;
  for (int t = 0; t < out.count; ++t) total += candidates[static_cast<size_t>(t)].pmf;
  for (int t = 0; t < out.count; ++t) {
    out.target[static_cast<size_t>(t)] = candidates[static_cast<size_t>(t)].target;
    out.target[static_cast<size_t>(t)].share = candidates[static_cast<size_t>(t)].pmf / total;
  }
  out.uniform_share = kDefaultProbeUniformShare;
  return out;
}

}  // namespace snee
