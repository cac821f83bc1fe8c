// Discrete distribution over n entries with O(1) sampling (Vose's alias method): light
// selection draws from it once per light sample, where Distribution1D's binary search over the
// cdf would grow with the light count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace snee {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights need not be normalized. Negative and NaN weights count as zero and zero-weight
  // entries are never sampled; if every weight is zero the table is uniform.
  explicit AliasTable(std::span<const float> weights);

  // The entry for u in [0,1), its probability in *pmf and, in *u_remapped, what is left of u
  // after the choice: again uniform on [0,1) and independent of it, for a caller that needs
  // one more number (an area light picking its triangle).
  int sample(float u, float* pmf, float* u_remapped) const;
  float pmf(int entry) const { return bins_[entry].pmf; }
  int size() const { return static_cast<int>(bins_.size()); }

 private:
  struct Bin {
    float keep = 1;      // probability that a draw landing in this bin keeps its own entry
    int32_t alias = -1;  // the entry it yields otherwise
    float pmf = 0;       // this entry's own probability
  };
  std::vector<Bin> bins_;
};

}  // namespace snee
