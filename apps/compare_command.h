// `snee compare`: renders one scene with several integrators at equal time (or equal spp)
// against a reference, and reports per integrator the spp reached, the time, the relative MSE,
// the efficiency 1 / (relMSE x time) and its ratio to the first integrator (pt by default). It
// writes each render, the reference, a JSON report and a contact sheet (apps/contact_sheet.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "kernels/simd/simd_level.h"

namespace snee {

class CompareCommand {
 public:
  explicit CompareCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  int run() const;

 private:
  bool given(const std::string& option) const { return command_->count(option) > 0; }

  CLI::App* command_;
  std::string scene_ = "builtin:sphere-cone-r0.04";
  std::vector<std::string> integrators_ = {"pt", "snee"};
  double seconds_ = 10;
  int spp_ = 0;
  std::string reference_;
  int reference_spp_ = 1024;
  std::string reference_integrator_ = "snee";
  std::string resolution_;
  std::string light_selection_;  // empty: the scene's
  int threads_ = 0;
  std::optional<SimdLevel> simd_;
  uint32_t seed_ = 1;
  std::string output_;
  std::string font_;
  bool quiet_ = false;
};

}  // namespace snee
