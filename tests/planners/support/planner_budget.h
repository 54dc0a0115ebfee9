// Planner budgets for the planner tests: a count of the planner's iterations
// (evaluations of its termination condition), not a time, so that a seeded
// plan is the same on a fast machine and on a slow, loaded one. A generous
// wall-clock limit stays only as a safety net against a hang: it never
// decides a test on a working machine.
#pragma once

#include <ompl/base/PlannerTerminationCondition.h>

#include <atomic>
#include <memory>
#include <thread>

namespace mddual::testing {

/// Wall-clock safety net of every budget (seconds): far above any planner
/// run of the tests (at most 4 s, most well under a second).
constexpr double kPlannerSafetyNetSeconds = 300.0;

/// The tests' default budget: their problems (small, seeded) solve within
/// 721 iterations (test_exact_rrt_connect's; the front end's within 90), so
/// 20,000 leave a margin of more than 25 times.
constexpr long kPlannerIterations = 20000;

/// Stops the planner after `iterations` evaluations of the condition (OMPL's
/// planners evaluate it once per iteration of their main loop), or after the
/// safety net. The counter is atomic: some planners evaluate the condition
/// from several threads. With `calling_thread_only`, only the evaluations on
/// the thread that made the budget count (the others see the verdict): the
/// planners (PRM, SPARS) whose solution-checking thread evaluates it in a
/// busy loop would otherwise spend the budget as fast as the scheduler lets
/// that thread run.
inline ompl::base::PlannerTerminationCondition iterationBudget(long iterations, bool calling_thread_only = false) {
  auto count = std::make_shared<std::atomic<long>>(0);
  const std::thread::id owner = std::this_thread::get_id();
  return ompl::base::plannerOrTerminationCondition(
      ompl::base::PlannerTerminationCondition([count, iterations, owner, calling_thread_only] {
        if (calling_thread_only && std::this_thread::get_id() != owner) return count->load() > iterations;
        return ++*count > iterations;
      }),
      ompl::base::timedPlannerTerminationCondition(kPlannerSafetyNetSeconds));
}

}  // namespace mddual::testing
