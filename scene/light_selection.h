// How a light sample picks its light (docs/lights.md): each light with the same probability, or
// in proportion to an estimate of its emitted power. Named the same in scene JSON
// (render.light_selection) and on the command line (--light-selection).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace snee {

enum class LightSelection : uint8_t { kUniform, kPower };

inline const char* light_selection_name(LightSelection s) {
  return s == LightSelection::kPower ? "power" : "uniform";
}

inline std::optional<LightSelection> parse_light_selection(std::string_view name) {
  if (name == "uniform") return LightSelection::kUniform;
  if (name == "power") return LightSelection::kPower;
  return std::nullopt;
}

}  // namespace snee
