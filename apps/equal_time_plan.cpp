#include "apps/equal_time_plan.h"

#include <algorithm>
#include <cmath>

namespace snee {

EqualTimePlan plan_equal_time(double budget_seconds, double seconds_per_spp) {
  EqualTimePlan plan;
  const double per_spp = std::max(seconds_per_spp, 1e-12);
  const double round_spp = std::floor(kRoundShareOfBudget * budget_seconds / per_spp);
  plan.samples_per_unit = static_cast<int>(std::clamp(round_spp, 1.0, double{kLongestRoundSpp}));
  const double round_seconds = plan.samples_per_unit * per_spp;
  // A budget of 0 would mean none; the smallest positive one stops after the first round.
  plan.time_seconds = std::max(budget_seconds - 0.5 * round_seconds, 1e-9);
  // In double first: a long budget over a cheap sample would overflow an int.
  const double fitting = kSppHeadroom * budget_seconds / per_spp;
  const int spu = plan.samples_per_unit;
  const double rounds = std::ceil(std::clamp(fitting, 1.0, double{kMaxEqualTimeSpp}) / spu);
  plan.max_spp = static_cast<int>(
      std::min(rounds * spu, static_cast<double>(kMaxEqualTimeSpp - kMaxEqualTimeSpp % spu)));
  return plan;
}

bool within_budget(double seconds, double budget_seconds) {
  return std::abs(seconds - budget_seconds) <= kBudgetTolerance * budget_seconds;
}

}  // namespace snee
