// How work units are interleaved over threads and stages. All three run the same stage kernels
// on the same work units, so they give bitwise-identical images; they differ only in batch
// size and in which path state is hot in the caches (docs/performance.md).
#pragma once

#include <string>

namespace snee {

enum class Schedule {
  kMegakernel,  // one slot per unit: a path runs to completion, every query is a single ray
  kLocal,       // one thread runs a unit's whole stage loop; its queues stay in its cache
  kGlobal,      // breadth-first: each stage runs over many units before the next stage
};

const char* schedule_name(Schedule s);
// Throws std::invalid_argument listing the valid names.
Schedule parse_schedule(const std::string& name);

}  // namespace snee
