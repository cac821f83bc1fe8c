// `snee scale`: renders one workload at each of a list of thread counts, several times each,
// and reports the median time, speedup and parallel efficiency as a table, JSON and an SVG plot.
// Work units are fixed by the image and spp, never by the thread count, so every run does the
// same work.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "kernels/simd/simd_level.h"

namespace snee {

class ScaleCommand {
 public:
  explicit ScaleCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  int run() const;

 private:
  bool given(const std::string& option) const { return command_->count(option) > 0; }

  CLI::App* command_;
  std::string scene_ = "builtin:bunny-cone-r0.04";
  std::string threads_ = "1,2";
  std::optional<SimdLevel> simd_;
  int repeats_ = 3;
  int spp_ = 16;
  std::string resolution_;
  std::string integrator_;
  std::string schedule_ = "local";
  std::string json_;
  std::string plot_;
};

}  // namespace snee
