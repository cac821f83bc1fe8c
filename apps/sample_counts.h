// How many samples the pixels of an image hold: the mean, fewest and most, from its per-pixel
// counts (adaptive sampling, an interrupted render) or, without them, meta.min_spp everywhere.
#pragma once

#include <cstdint>

#include "scene/film.h"

namespace snee {

struct SampleCounts {
  double mean = 0;
  uint32_t fewest = 0;
  uint32_t most = 0;
};

SampleCounts sample_counts(const Film& film);

}  // namespace snee
