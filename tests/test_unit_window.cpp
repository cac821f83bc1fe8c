// The unit window hands units out in order and never lets the newest run more than `lead`
// units ahead of the oldest unfinished one: the property the film's sample-buffer ring relies on.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <random>
#include <set>
#include <stdexcept>

#include "scheduler/unit_window.h"

namespace snee {
namespace {

TEST(UnitWindow, HandsOutUnitsInOrderUpToTheLead) {
  UnitWindow window(10, 3);
  EXPECT_EQ(window.take(false), 0u);
  EXPECT_EQ(window.take(false), 1u);
  EXPECT_EQ(window.take(false), 2u);
  EXPECT_EQ(window.take(false), std::nullopt) << "full: 0 is unfinished and 3 = 0 + lead";
  window.finish(2);
  window.finish(1);
  EXPECT_EQ(window.take(false), std::nullopt) << "later units finishing do not move the window";
  window.finish(0);
  // 0, 1 and 2 have all finished, so the window moves by three at once.
  EXPECT_EQ(window.take(false), 3u);
  EXPECT_EQ(window.take(false), 4u);
  EXPECT_EQ(window.take(false), 5u);
  EXPECT_EQ(window.take(false), std::nullopt);
}

TEST(UnitWindow, EndsAfterTheLastUnitEvenWhileUnitsAreUnfinished) {
  UnitWindow window(2, 8);
  EXPECT_EQ(window.take(true), 0u);
  EXPECT_EQ(window.take(true), 1u);
  // Every unit is out, so a waiting take must return at once instead of waiting for a finish.
  EXPECT_EQ(window.take(true), std::nullopt);
}

TEST(UnitWindow, RejectsUnitsFinishedTwiceOrNeverTaken) {
  UnitWindow window(4, 2);
  ASSERT_EQ(window.take(false), 0u);
  EXPECT_THROW(window.finish(1), std::logic_error);
  window.finish(0);
  EXPECT_THROW(window.finish(0), std::logic_error);
  EXPECT_THROW(UnitWindow(4, 0), std::invalid_argument);
}

TEST(UnitWindow, AWaitingTakeWakesWhenTheOldestUnitFinishes) {
  UnitWindow window(3, 1);
  ASSERT_EQ(window.take(true), 0u);
  auto waiting = std::async(std::launch::async, [&] { return window.take(true); });
  EXPECT_EQ(waiting.wait_for(std::chrono::milliseconds(50)), std::future_status::timeout)
      << "the window is full, so the take must wait";
  window.finish(0);
  ASSERT_EQ(waiting.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(waiting.get(), 1u);
}

TEST(UnitWindow, AbortStopsHandingOutAndWakesWaitingTakes) {
  UnitWindow window(5, 1);
  ASSERT_EQ(window.take(true), 0u);
  auto waiting = std::async(std::launch::async, [&] { return window.take(true); });
  EXPECT_EQ(waiting.wait_for(std::chrono::milliseconds(50)), std::future_status::timeout);
  window.abort();  // unit 0 will never finish
  ASSERT_EQ(waiting.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(waiting.get(), std::nullopt);
  EXPECT_EQ(window.take(false), std::nullopt);
}

// Random interleavings of takes and finishes: the lead bound holds after every step and every
// unit is handed out exactly once.
TEST(UnitWindow, TheLeadBoundHoldsUnderRandomFinishOrders) {
  std::mt19937 rng(7);
  for (const size_t lead : {1, 2, 5, 16}) {
    const size_t units = 200;
    UnitWindow window(units, lead);
    std::set<size_t> unfinished;
    size_t handed_out = 0;
    while (handed_out < units || !unfinished.empty()) {
      if (std::uniform_int_distribution<int>(0, 2)(rng) != 0) {
        if (const auto k = window.take(false)) {
          ASSERT_EQ(*k, handed_out);
          ++handed_out;
          unfinished.insert(*k);
        }
      } else if (!unfinished.empty()) {
        auto it = unfinished.begin();
        std::advance(it, std::uniform_int_distribution<size_t>(0, unfinished.size() - 1)(rng));
        window.finish(*it);
        unfinished.erase(it);
      }
      if (!unfinished.empty()) {
        ASSERT_LT(handed_out - 1, *unfinished.begin() + lead);
      }
    }
    EXPECT_EQ(window.take(false), std::nullopt);
  }
}

}  // namespace
}  // namespace snee
