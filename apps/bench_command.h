// `snee bench`: renders the fixed workloads (bench_workloads.h) under every schedule, thread
// count and chosen SIMD level, measures raw Embree traversal on the same geometry, prints a table
// per workload and optionally writes everything as JSON. docs/performance.md explains each figure.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "scheduler/render.h"

namespace snee {

class BenchCommand {
 public:
  explicit BenchCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  int run() const;

 private:
  bool given(const std::string& option) const { return command_->count(option) > 0; }

  CLI::App* command_;
  std::string threads_ = "1,2";
  int spp_ = 16;
  std::string resolution_ = "128x128";
  int repeats_ = 3;
  int samples_per_unit_ = RenderOptions{}.samples_per_unit;
  int queue_capacity_ = RenderOptions{}.queue_capacity;
  bool quick_ = false;
  std::string json_;
  std::string dragon_;
  std::string only_;
  std::string simd_;
};

}  // namespace snee
