// The fixed workloads of `snee bench` (docs/performance.md lists them): camera rays alone, and
// path tracing and SNEE on the sphere, the bunny, the 871k-triangle Stanford dragon and the
// bunny filled with a ten times denser and a ten times thinner medium. All are the SNEE test
// grid's translucent object under its cone light, so they differ in one thing at a time.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace snee {

struct BenchWorkload {
  std::string name;  // e.g. "bunny-snee"
  std::string description;
  std::string source;  // the scene it is built from
  std::string integrator;
  int max_depth = 1024;
  int spp_factor = 1;  // camera rays are cheap: that workload takes more samples per pixel
  Scene scene;
};

struct BenchWorkloads {
  std::vector<BenchWorkload> workloads;
  std::vector<std::string> skipped;  // why a workload is missing
};

// The dragon is read from `dragon_path` (too large for the repository); without it, or with
// include_dragon false, its workloads are skipped with a message.
BenchWorkloads bench_workloads(const std::string& dragon_path, bool include_dragon);

// Where the dragon lies beside a checkout: ../shared/data/meshes/dragon_vrip.ply.
std::string default_dragon_path();

}  // namespace snee
