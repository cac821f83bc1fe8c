// `snee scenes`: lists the built-in scenes that `snee render builtin:NAME` accepts.
#pragma once

#include <CLI/CLI.hpp>

namespace snee {

class ScenesCommand {
 public:
  explicit ScenesCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  int run() const;

 private:
  CLI::App* command_;
};

}  // namespace snee
