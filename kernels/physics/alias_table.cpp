#include "kernels/physics/alias_table.h"

#include <algorithm>

namespace snee {

AliasTable::AliasTable(std::span<const float> weights) : bins_(weights.size()) {
  const size_t n = weights.size();
  if (n == 0) return;
  double sum = 0;
  for (const float w : weights) sum += w > 0 ? w : 0.0f;
  // Each bin holds 1/n of the probability; scaled[i] is entry i's probability in bins. Kept in
  // double so that the leftovers moved between bins do not drift away from the pmf.
  std::vector<double> scaled(n);
  for (size_t i = 0; i < n; ++i) {
    const double p = sum > 0 ? (weights[i] > 0 ? weights[i] / sum : 0.0) : 1.0 / n;
    bins_[i].pmf = static_cast<float>(p);
    scaled[i] = p * static_cast<double>(n);
  }
  std::vector<int32_t> small, large;
  for (size_t i = 0; i < n; ++i)
    (scaled[i] < 1.0 ? small : large).push_back(static_cast<int32_t>(i));
  // Vose: fill each under-full bin from an over-full entry, which then may become under-full.
  while (!small.empty() && !large.empty()) {
    const int32_t s = small.back(), l = large.back();
    small.pop_back();
    bins_[s].keep = static_cast<float>(scaled[s]);
    bins_[s].alias = l;
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What is left is full up to rounding and keeps its own entry, except a zero-weight entry,
  // which must never be returned: its bin goes wholly to an entry that may be.
  const int32_t positive = static_cast<int32_t>(
      std::find_if(bins_.begin(), bins_.end(), [](const Bin& b) { return b.pmf > 0; }) -
      bins_.begin());
  for (const int32_t i : large) bins_[i].keep = 1.0f;
  for (const int32_t i : small) {
    bins_[i].keep = scaled[i] > 0 ? 1.0f : 0.0f;
    if (scaled[i] == 0) bins_[i].alias = positive;
  }
}

int AliasTable::sample(float u, float* pmf_out, float* u_remapped) const {
  const int n = size();
  const float scaled = u * static_cast<float>(n);
  const int bin = std::min(static_cast<int>(scaled), n - 1);
  // Uniform on [0,1) within the bin; float rounding may reach 1.
  const float within = std::min(scaled - static_cast<float>(bin), 0x1.fffffep-1f);
  const Bin& b = bins_[bin];
  int entry = bin;
  float rest = 0;
  if (within < b.keep || b.alias < 0) {
    rest = within / b.keep;
  } else {
    entry = b.alias;
    rest = (within - b.keep) / (1.0f - b.keep);
  }
  if (pmf_out) *pmf_out = bins_[entry].pmf;
  if (u_remapped) *u_remapped = std::min(rest, 0x1.fffffep-1f);
  return entry;
}

}  // namespace snee
