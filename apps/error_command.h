// `snee error`: how far one finished render is from a reference, from the two EXRs alone. It
// prints the relative MSE of `snee compare` (apps/image_error.h: the figure with the
// reference's noise subtracted, the raw one, the trimmed one and that noise) and how many
// samples the render's pixels hold, and can write the same as JSON. For measuring renders made
// elsewhere, e.g. adaptive against uniform sampling.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace snee {

class ErrorCommand {
 public:
  explicit ErrorCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  int run() const;

 private:
  CLI::App* command_;
  std::string render_;
  std::string reference_;
  std::string json_;
};

}  // namespace snee
