// CheckerCounters: exact counts, and a timed call nested in another checker's
// timed call (a motion validator's state checks) counted once, by the outer
// call, so that the checkers' times add up to the time spent checking.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "mddual/planning/counters.h"

namespace mddual::planning {
namespace {

void busy(std::chrono::microseconds span) {
  const auto end = std::chrono::steady_clock::now() + span;
  while (std::chrono::steady_clock::now() < end) {
  }
}

TEST(CheckerCounters, NestedTimersCountOnceInTheOuterCall) {
  CheckerCounters motion, state;
  const auto start = std::chrono::steady_clock::now();
  {
    const CheckerCounters::Timer outer(motion);
    for (int i = 0; i < 3; ++i) {
      const CheckerCounters::Timer inner(state);
      state.addStateCheck();
      busy(std::chrono::microseconds(200));
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(state.read().state_checks, 3u);
  EXPECT_EQ(state.read().seconds, 0.0) << "the inner calls are the outer call's time";
  EXPECT_GE(motion.read().seconds, 600e-6);
  EXPECT_LE(motion.read().seconds + state.read().seconds, wall);
  // Alone, the inner checker's calls count again.
  {
    const CheckerCounters::Timer alone(state);
    busy(std::chrono::microseconds(100));
  }
  EXPECT_GE(state.read().seconds, 100e-6);
}

TEST(CheckerCounters, TimersOnOtherThreadsAreNotNested) {
  CheckerCounters a, b;
  {
    const CheckerCounters::Timer outer(a);
    std::thread other([&b] {
      const CheckerCounters::Timer t(b);
      busy(std::chrono::microseconds(100));
    });
    other.join();
  }
  EXPECT_GE(b.read().seconds, 100e-6);
  EXPECT_GE(a.read().seconds, b.read().seconds);
}

TEST(CheckerCounters, TimingOffCountsNoTime) {
  CheckerCounters c;
  c.setTiming(false);
  {
    const CheckerCounters::Timer t(c);
    busy(std::chrono::microseconds(100));
  }
  EXPECT_EQ(c.read().seconds, 0.0);
  c.setTiming(true);
  {
    const CheckerCounters::Timer t(c);
    busy(std::chrono::microseconds(100));
  }
  EXPECT_GE(c.read().seconds, 100e-6);
  // Inside a call that is not timed, a timed one counts its own time.
  CheckerCounters outer_off, inner_on;
  outer_off.setTiming(false);
  {
    const CheckerCounters::Timer outer(outer_off);
    const CheckerCounters::Timer inner(inner_on);
    busy(std::chrono::microseconds(100));
  }
  EXPECT_EQ(outer_off.read().seconds, 0.0);
  EXPECT_GE(inner_on.read().seconds, 100e-6);
}

}  // namespace
}  // namespace mddual::planning
