#include "kernels/physics/snee/snee_options.h"

#include <array>
#include <stdexcept>
#include <string_view>

namespace snee {

namespace {

constexpr std::array<std::pair<std::string_view, Strategy>, kStrategyCount> kNames = {{
    {"tb", Strategy::kTopToBottom},
    {"bt", Strategy::kBottomToTop},
    {"ub", Strategy::kUnidirectionalBsdf},
    {"ul", Strategy::kUnidirectionalLight},
    {"mn", Strategy::kManifold},
}};

constexpr std::array<std::pair<std::string_view, ProbeDirections>, 3> kProbeNames = {{
    {"uniform", ProbeDirections::kUniformSphere},
    {"phase", ProbeDirections::kPhaseFunction},
    {"lights", ProbeDirections::kTowardLights},
}};

}  // namespace

ProbeDirections probe_directions_named(const std::string& name) {
  for (const auto& [n, kind] : kProbeNames) {
    if (name == n) return kind;
  }
  throw std::invalid_argument("unknown SNEE probe '" + name +
                              "' (expected uniform, phase or lights)");
}

std::string probe_directions_name(ProbeDirections kind) {
  for (const auto& [n, k] : kProbeNames) {
    if (k == kind) return std::string(n);
  }
  return "uniform";
}

StrategySet parse_strategy_set(const std::string& list) {
  StrategySet set;
  size_t begin = 0;
  while (begin <= list.size()) {
    const size_t end = std::min(list.find(',', begin), list.size());
    const std::string_view item(list.data() + begin, end - begin);
    bool known = false;
    for (const auto& [name, strategy] : kNames) {
      if (item == name) {
        set = set.with(strategy);
        known = true;
      }
    }
    if (!known) {
      throw std::invalid_argument("unknown SNEE strategy '" + std::string(item) +
                                  "' (expected a comma-separated list of tb, bt, ub, ul, mn)");
    }
    begin = end + 1;
  }
  return set;
}

std::string strategy_set_name(StrategySet set) {
  std::string out;
  for (const auto& [name, strategy] : kNames) {
    if (!set.contains(strategy)) continue;
    if (!out.empty()) out += ',';
    out += name;
  }
  return out;
}

}  // namespace snee
