// Which denoiser AOV layers a render writes (`snee render --aov`; docs/output-images.md).
#pragma once

#include <string>

namespace snee {

struct AovSelection {
  bool albedo = false;
  bool normal = false;
  bool depth = false;
  bool any() const { return albedo || normal || depth; }
};

// A comma-separated list of "albedo", "normal" and "depth" (each at most once, in any order).
// Throws std::invalid_argument naming the offending entry and the valid names.
AovSelection parse_aov_list(const std::string& list);
// The selection as parse_aov_list reads it ("albedo,normal,depth" order); "" for none.
std::string aov_list(const AovSelection& selection);

}  // namespace snee
