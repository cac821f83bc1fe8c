#include "scene/aov_selection.h"

#include <stdexcept>
#include <string_view>
#include <utility>

namespace snee {

AovSelection parse_aov_list(const std::string& list) {
  AovSelection selection;
  std::string_view rest = list;
  for (;;) {
    const size_t comma = rest.find(',');
    const std::string_view name = rest.substr(0, comma);
    bool* chosen = name == "albedo"   ? &selection.albedo
                   : name == "normal" ? &selection.normal
                   : name == "depth"  ? &selection.depth
                                      : nullptr;
    if (!chosen)
      throw std::invalid_argument("unknown AOV '" + std::string(name) + "' in '" + list +
                                  "': expected a comma-separated list of "
                                  "albedo, normal, depth");
    if (*chosen)
      throw std::invalid_argument("AOV '" + std::string(name) + "' given twice in '" + list + "'");
    *chosen = true;
    if (comma == std::string_view::npos) return selection;
    rest.remove_prefix(comma + 1);
  }
}

std::string aov_list(const AovSelection& selection) {
  std::string list;
  for (const auto& [chosen, name] :
       {std::pair{selection.albedo, "albedo"}, std::pair{selection.normal, "normal"},
        std::pair{selection.depth, "depth"}}) {
    if (!chosen) continue;
    if (!list.empty()) list += ',';
    list += name;
  }
  return list;
}

}  // namespace snee
