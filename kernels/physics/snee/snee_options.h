// The open choices of docs/method.md section 7, with the spec's recommendations as defaults. None
// of them changes the expected image; they trade variance only (and, for the enabled-strategy
// set, select which part of the handled transport is rendered: see StrategySet).
#pragma once

#include <cstdint>
#include <string>

#include "kernels/physics/snee/probe_targets.h"

namespace snee {

// The ways the suffix x_i -> x_j -> x_k -> light can be produced (docs/method.md 3.6, 3.10).
enum class Strategy : uint8_t {
  kTopToBottom,          // TB: light -> x_k -> x_j, then connect to x_i
  kBottomToTop,          // BT: x_i -> x_j (joint importance), connect to x_k, BTDF to the light
  kUnidirectionalBsdf,   // U_B: the tracer's random walk, BSDF-sampled exit reaching a light
  kUnidirectionalLight,  // U_L: the tracer's random walk, light sample at the exit point
  kManifold,             // MN: the walk to x_j, then every x_k whose refraction of a
                         // directional light reaches x_j (smooth sphere, docs/method.md 3.10)
};
inline constexpr int kStrategyCount = 5;

// Bit set of strategies allowed to carry weight on the suffixes SNEE handles. Disabling some
// isolates the others (docs/method.md 5.4): the remaining strategies share the handled class, the
// disabled ones get weight 0 there. Suffixes SNEE cannot produce always keep the tracer's own
// two-way weights, so a full render stays unbiased whenever every path the enabled set can
// reach is reachable (e.g. "TB only" in every case, "U_B only" in cases A and C).
class StrategySet {
 public:
  constexpr StrategySet() = default;
  static constexpr StrategySet all() { return StrategySet((1u << kStrategyCount) - 1); }
  static constexpr StrategySet only(Strategy s) { return StrategySet(bit(s)); }
  constexpr StrategySet with(Strategy s) const { return StrategySet(bits_ | bit(s)); }
  constexpr StrategySet without(Strategy s) const { return StrategySet(bits_ & ~bit(s)); }
  constexpr bool contains(Strategy s) const { return (bits_ & bit(s)) != 0; }

 private:
  constexpr explicit StrategySet(uint32_t bits) : bits_(bits) {}
  static constexpr uint32_t bit(Strategy s) { return 1u << static_cast<uint32_t>(s); }
  uint32_t bits_ = 0;
};

// Q1: direction of the probe ray that finds the exit point x_k from x_i.
enum class ProbeDirections : uint8_t {
  kUniformSphere,  // the talk's "random direction"
  kPhaseFunction,  // HG around the incoming direction; full support for |g| < 1
  kTowardLights,   // clamped cosines about the directions toward the small lights, plus a
                   // uniform share (probe_targets.h); full support
};

// Q5: multi-sample MIS heuristic over the enabled strategies.
enum class MisHeuristic : uint8_t {
  kBalance,  // w_s = p_s / sum p
  kPower,    // w_s = p_s^2 / sum p^2
};

// Where SNEE stops paying: measured on the paper grid's sphere under cones of 2.67 to 90
// degrees (docs/method.md 3.11).
inline constexpr float kDefaultLightLimitDegrees = 15.0f;
inline constexpr float kDefaultManifoldRate = 0.125f;
// Measured on the paper grid's sphere and bunny under the cone and the directional light
// (docs/method.md 3.2, docs/results.md): at a quarter of the vertices the probe, the
// subdivision and their rays cost a third as much, and the error grows far less than the time
// falls.
inline constexpr float kDefaultProbeRate = 0.25f;
// Levels (reflections and crossings) of the reflection chains behind a flat-shaded mesh: each
// level holds about twice the fragments of the one below and takes as much longer to build, and
// four hold most of the light of the paper grid's bunny (docs/method.md 3.14).
inline constexpr int kDefaultMeshChainLevels = 4;
// The guided exit's cap (docs/method.md 3.15): wide enough to hold the directions that a glossy
// boundary refracts toward a light of a few degrees.
inline constexpr float kDefaultGuideCapDegrees = 5.0f;
// Measured on the paper grid's sphere (docs/method.md 3.15): from a tenth to all of the
// vertices the error barely moves, and a quarter costs half the time of every one.
inline constexpr float kDefaultGuideRate = 0.25f;

struct SneeOptions {
  ProbeDirections probe = ProbeDirections::kUniformSphere;
  // The lights kTowardLights aims at: filled from the scene at render set-up (probe.h), not an
  // option a user sets.
  ProbeTargets probe_targets;
  // The probability that a medium vertex runs the probe (and with it top-to-bottom and
  // bottom-to-top); their densities carry it, so the weights still sum to one.
  float probe_rate = kDefaultProbeRate;
  // Q2: probability of drawing TB's distance from the free-flight (transmittance) sampler rather
  // than equiangularly toward x_i.
  float c_exponential = 0.5f;
  // Q4: probability of drawing BT's direction from the geometry-only joint-importance lobe
  // rather than from the phase function at x_i. Only used when g != 0 (for g = 0 the phase
  // function adds nothing the geometric lobe lacks, so the lobe is used alone).
  float c_joint = 0.5f;
  MisHeuristic heuristic = MisHeuristic::kBalance;
  StrategySet enabled = StrategySet::all();
  // SNEE runs only when some light looks no larger than this from the objects (the half-angle
  // of the cone it fills, kernels/physics/snee/light_extent.h; delta lights 0, environments 180);
  // otherwise `snee` renders exactly as `pt`. The default is measured (docs/method.md 3.11);
  // 180 keeps SNEE on under any light.
  float light_limit_degrees = kDefaultLightLimitDegrees;
  // Whether the manifold strategy also follows the light through internal reflections before it
  // reaches x_j (docs/method.md 3.12). Those paths have no other strategy under a delta light,
  // so turning this off leaves them out: it exists to measure what they add.
  bool reflection_chains = true;
  // How many levels of chains a flat-shaded mesh's chain tree holds (1 to kMaxMeshChainLevels);
  // the searches that draw more are counted as unsupported.
  int mesh_chain_levels = kDefaultMeshChainLevels;
  // The probability that the manifold strategy runs at a medium vertex x_j whose parent x_i is
  // a medium vertex too (docs/method.md 3.10); at the first scattering it always runs. There its
  // suffixes are the handled class, which top-to-bottom shares, and the rare V_first = 0 class,
  // so most of its solves (a few microseconds each) can be skipped; its density carries the
  // rate, so the weights still sum to one. The default is measured (docs/method.md 3.10).
  float manifold_rate = kDefaultManifoldRate;
  // The probability that the guided exit runs at a medium vertex whose parent is a surface
  // vertex, inside a sphere or closed flat-shaded mesh boundary (docs/method.md 3.15); 0 turns it
  // off. Its density carries the rate, so the walk's exit events weigh themselves against it at any
  // rate.
  float guide_rate = kDefaultGuideRate;
  // Half-angle in degrees of the cap the guided exit draws its direction in.
  float guide_cap_degrees = kDefaultGuideCapDegrees;
};

// Parses a comma-separated list of tb, bt, ub, ul (e.g. "tb,bt"); throws std::invalid_argument
// naming the offending item, or for an empty list.
StrategySet parse_strategy_set(const std::string& list);
// The inverse: "tb,bt,ub,ul" order.
std::string strategy_set_name(StrategySet set);

// "uniform", "phase" or "lights"; throws std::invalid_argument naming anything else.
ProbeDirections probe_directions_named(const std::string& name);
std::string probe_directions_name(ProbeDirections kind);

}  // namespace snee
