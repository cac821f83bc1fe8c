// What the subdivision stage keeps per exit of its queue between its passes (kernels/
// subdivision.cpp): the random numbers, each strategy's batched part, the light samples of
// top-to-bottom, and the proposals waiting to be weighed. Sized once per work unit; filling it
// never allocates.
#pragma once

#include <array>
#include <vector>

#include "kernels/physics/snee/snee_strategies.h"
#include "kernels/wavefront/queues.h"

namespace snee {

// The exits' random numbers by queue position: for each of the two strategies two Philox
// blocks of four numbers (drawn in SIMD chunks, used per exit), read by the names of
// kernels/physics/snee/strategy_randoms.h.
struct SubdivisionRandoms {
  static constexpr int kBlocks = 4;  // top-to-bottom: 2, bottom-to-top: 2
  static_assert(kTopToBottomDimensions == 8 && kBottomToTopDimensions <= 8);
  explicit SubdivisionRandoms(size_t capacity) {
    for (AlignedArray<float>& a : u) a = AlignedArray<float>(padded_capacity(capacity));
  }
  // Number n of top-to-bottom's u (TopToBottomRandoms), and of bottom-to-top's.
  const AlignedArray<float>& top_to_bottom(int n) const { return u[n]; }
  const AlignedArray<float>& bottom_to_top(int n) const { return u[kTopToBottomDimensions + n]; }
  // u[4 b + j]: number j of block b at each queue position.
  std::array<AlignedArray<float>, 4 * kBlocks> u;
};

// Top-to-bottom's light samples at each exit, taken per exit before its batched part, and the
// same in lanes (work_items.h).
struct TopToBottomLights : TopToBottomLightLanes {
  explicit TopToBottomLights(size_t capacity)
      : TopToBottomLightLanes(capacity), samples(capacity) {}
  std::vector<LightSample> samples;
};

// The proposals that sampled something, in exit order, waiting for the batched weighing, as a
// structure of arrays (work_items.h) the weighing loads its lanes from; room for two per exit.
class ProposalQueue {
 public:
  explicit ProposalQueue(size_t capacity) : items_(2 * capacity) {}
  void clear() { size_ = 0; }
  size_t size() const { return size_; }
  const ProposalItems& items() const { return items_; }
  void push(const SneeProposal& p, Strategy strategy, uint32_t slot);
  // Proposal i as the scalar functions take it (finish_proposal).
  SneeProposal proposal(size_t i) const;
  Strategy strategy(size_t i) const { return static_cast<Strategy>(items_.strategy[i]); }
  uint32_t slot(size_t i) const { return items_.slot[i]; }
  bool manifold(size_t i) const { return items_.manifold[i] != 0; }
  std::array<ShadowSegment, 3> segments(size_t i) const;

 private:
  ProposalItems items_;
  size_t size_ = 0;
};

struct SubdivisionScratch {
  explicit SubdivisionScratch(size_t capacity)
      : randoms(capacity),
        lights(capacity),
        top_to_bottom(capacity),
        bottom_to_top(capacity),
        proposals(capacity) {}
  SubdivisionRandoms randoms;
  TopToBottomLights lights;
  StrategyResults top_to_bottom, bottom_to_top;
  ProposalQueue proposals;
};

}  // namespace snee
