#include "apps/sample_counts.h"

#include <algorithm>

namespace snee {

SampleCounts sample_counts(const Film& film) {
  if (film.pixel_spp.empty()) {
    const auto spp = static_cast<uint32_t>(std::max(film.meta.min_spp, 0));
    return {static_cast<double>(spp), spp, spp};
  }
  SampleCounts counts{0, film.pixel_spp.front(), 0};
  for (const uint32_t n : film.pixel_spp) {
    counts.mean += n;
    counts.fewest = std::min(counts.fewest, n);
    counts.most = std::max(counts.most, n);
  }
  counts.mean /= static_cast<double>(film.pixel_spp.size());
  return counts;
}

}  // namespace snee
