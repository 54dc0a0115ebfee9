// MeteredPlanner: a planner wrapped so that a callback runs the moment its
// solve() returns, before OMPL's benchmark checks the solution path (those
// checks call the checkers too): the benchmark runners read the checkers'
// counters there, and the wall time of the wrapped planner's solve() alone.
// OMPL 1.5's benchmark times solve(ptc, 0.1), whose termination-condition
// thread sleeps in steps of 1 ms and is joined after the planner returns: its
// "time" adds up to 1 ms to every run, whatever the checker (a planner that
// solves in 0.2 ms is logged at about 1.3 ms; docs/arms.md). Shared by
// bench_runner.cpp and arm_bench.cpp.
#pragma once

#include <ompl/base/Planner.h>
#include <ompl/util/Exception.h>

#include <chrono>
#include <functional>
#include <ostream>
#include <string>
#include <utility>

#include "mddual/error.h"

namespace mddual::planning::detail {

namespace ob = ompl::base;

/// planner.setup(), with OMPL's errors there given the planner's place in the
/// cfg (`where`): some parameters are checked only then (KPIECE1's
/// min_valid_path_fraction and failed_expansion_score_factor).
inline void setUpPlanner(ob::Planner& planner, const std::string& where) {
  try {
    planner.setup();
  } catch (const ompl::Exception& e) {
    throw InvalidInputError(where + e.what() + " (OMPL's check at the planner's set-up)");
  }
}

/// Runs a planner and calls `solved(seconds)` the moment its solve() returns,
/// before OMPL's benchmark checks the solution path: the checkers' counters
/// are read there; `seconds` is the wall time of the wrapped solve() alone.
/// Everything else is the wrapped planner's: name, parameters (the log's
/// settings), specs, progress properties, planner data.
class MeteredPlanner : public ob::Planner {
 public:
  /// `where`: the planner's place in the cfg (ProblemSetup::plannerWhere), for
  /// the errors of OMPL's checks of its parameters at set-up.
  MeteredPlanner(ob::PlannerPtr inner, std::function<void(double)> solved, std::string where)
      : ob::Planner(inner->getSpaceInformation(), inner->getName()),
        inner_(std::move(inner)),
        solved_(std::move(solved)),
        where_(std::move(where)) {
    specs_ = inner_->getSpecs();
    params_.include(inner_->params());
    plannerProgressProperties_ = inner_->getPlannerProgressProperties();
  }
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    const auto start = std::chrono::steady_clock::now();
    const auto seconds = [&start] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    ob::PlannerStatus status;
    try {
      status = inner_->solve(ptc);
    } catch (...) {
      solved_(seconds());
      throw;
    }
    solved_(seconds());
    return status;
  }
  void setProblemDefinition(const ob::ProblemDefinitionPtr& pdef) override {
    ob::Planner::setProblemDefinition(pdef);
    inner_->setProblemDefinition(pdef);
  }
  void clear() override { inner_->clear(); }
  void clearQuery() override { inner_->clearQuery(); }
  void setup() override {
    setUpPlanner(*inner_, where_);
    setup_ = true;
  }
  void checkValidity() override { inner_->checkValidity(); }
  void getPlannerData(ob::PlannerData& data) const override { inner_->getPlannerData(data); }
  void printProperties(std::ostream& out) const override { inner_->printProperties(out); }
  void printSettings(std::ostream& out) const override { inner_->printSettings(out); }
  const ob::PlannerPtr& inner() const { return inner_; }

 private:
  ob::PlannerPtr inner_;
  std::function<void(double)> solved_;
  std::string where_;
};

}  // namespace mddual::planning::detail
