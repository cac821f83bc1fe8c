// The lights the light-favouring probe aims at (docs/method.md 3.2): under a small light about
// half of the uniform probes find an exit point with the light below its horizon, where top-to-
// bottom cannot connect, so the probe mostly draws a clamped cosine about the direction toward
// one of these lights and keeps a uniform share for the exits no lobe reaches. Scene data,
// gathered once at render set-up (probe.h: probe_targets_of).
#pragma once

#include <array>

#include "core/math.h"

namespace snee {

inline constexpr int kMaxProbeTargets = 4;
// Measured on the paper grid (docs/results.md, "The light-favouring probe").
inline constexpr float kDefaultProbeUniformShare = 0.25f;

struct ProbeTarget {
  // Distant lights (directional, cone): the unit direction toward the light; point and spot
  // lights: their position, the lobe's axis being the direction toward it from x_i.
  Vec3 where;
  bool positional = false;
  float share = 0;  // of the lobes' part, the shares summing to 1
  // Directional, point or spot: reached only by light samples (the guided exit behind a smooth
  // mesh has no use for it, docs/method.md 3.15).
  bool delta = false;
};

struct ProbeTargets {
  std::array<ProbeTarget, kMaxProbeTargets> target{};
  int count = 0;
  // The probability of a uniform direction; 1 where no target exists.
  float uniform_share = 1.0f;
};

}  // namespace snee
