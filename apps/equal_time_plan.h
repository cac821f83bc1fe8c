// How `snee compare` spends an equal-time budget. Predicting the spp that fits from pilot
// renders misses the budget by however much the machine's speed drifts between the pilot and
// the render (a lot on a shared machine), so the render runs under the renderer's own time
// budget instead (RenderOptions::time_seconds, docs/budgets.md): its clock starts with the
// render, scene set-up included, as RenderStats::seconds does, and it stops at the first round
// boundary after the clock runs out. The pilots only size the rounds, short enough that the
// last one overshoots little.
#pragma once

namespace snee {

// A compared render's time must be within this share of the budget (`within_budget`).
inline constexpr double kBudgetTolerance = 0.05;
// A round may take at most this share of the budget: the round running when the clock runs out
// finishes, so the render ends on average half a round late, at worst a whole one.
inline constexpr double kRoundShareOfBudget = 0.02;
// The renderer's default unit size; rounds are never made longer than with it.
inline constexpr int kLongestRoundSpp = 8;
// The render may take this many times the samples the pilots predict fit, so a machine that
// speeds up after the pilots (others' work ending) still spends the whole budget.
inline constexpr int kSppHeadroom = 8;
inline constexpr int kMaxEqualTimeSpp = 1 << 30;

struct EqualTimePlan {
  int samples_per_unit = 1;  // one round's spp
  double time_seconds = 0;   // RenderOptions::time_seconds
  int max_spp = 1;           // a whole number of rounds
};

// The options under which a render whose samples take `seconds_per_spp` (a pilot's sampling
// time over its spp) takes `budget_seconds` in all: the clock stops new rounds half a round
// before the budget, so the expected end is the budget.
EqualTimePlan plan_equal_time(double budget_seconds, double seconds_per_spp);

// Whether `seconds` is within kBudgetTolerance of `budget_seconds`.
bool within_budget(double seconds, double budget_seconds);

}  // namespace snee
