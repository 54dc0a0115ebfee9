// The collision checkers of the benchmarks, in one table per kind of problem:
//   rigidCheckers()  a cfg's rigid body (ProblemSetup, `mddual bench CFG`);
//   armCheckers()    a robot arm in joint space (runArmBench, `mddual bench
//                    PROBLEM_DIR --robot URDF --srdf SRDF`).
// Each checker is one file of planners/frontend/src/checkers/ that returns
// its entry (name, one-line description, install function), and one line in
// its kind's table in planners/frontend/src/checkers/registry.cpp; the
// command line, the logs and the tests take the names and the order from
// the tables (docs/extending.md). A checker in an optional library (the
// Bullet peer, mddual_hull_cast) is not in these tables: that library's
// registration function appends its entries (addRigidChecker,
// addArmChecker), and the program calls it once at start-up (the CLI does
// when built with Bullet; docs/extending.md).
//
// An install function puts a state validity checker and a motion validator
// on the context's SpaceInformation and returns what the caller reads of
// them afterwards (InstalledChecker). The rigid set-up wraps whatever was
// installed to count the checks and time them itself, so rigid checkers turn
// their own timing off; the arm bench reads the checkers' own state checks
// and time.
#pragma once

#include <ompl/base/SpaceInformation.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/counters.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/mdd_checkers.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

/// What an install function leaves to its caller.
struct InstalledChecker {
  /// The checkers' own counts since reset_counts(), summed over the objects
  /// installed (see countsOf). ProblemSetup reads pair_queries and sub_edges,
  /// the arm bench state_checks and seconds.
  std::function<CheckerCounts()> counts;
  std::function<void()> reset_counts;
  /// Optional: drops lastValid fractions at or below the argument
  /// (MddMotionValidator::setDiscardedLastValidFraction); empty when the
  /// checker's lastValid needs no such setting.
  std::function<void(double)> set_discarded_last_valid_fraction;
  /// Optional: the MDD scene the checkers use (ProblemSetup::mddScene).
  std::shared_ptr<const MddScene> mdd_scene;
};

/// An InstalledChecker whose counts() sums the parts' counts() and whose
/// reset_counts() resets every part (objects with counts() and resetCounts()).
template <class... Parts>
InstalledChecker countsOf(std::shared_ptr<Parts>... parts) {
  InstalledChecker out;
  out.counts = [=] {
    CheckerCounts sum;
    const auto add = [&sum](const CheckerCounts& c) {
      sum.state_checks += c.state_checks;
      sum.motion_checks += c.motion_checks;
      sum.pair_queries += c.pair_queries;
      sum.sub_edges += c.sub_edges;
      sum.seconds += c.seconds;
    };
    (add(parts->counts()), ...);
    return sum;
  };
  out.reset_counts = [=] { (parts->resetCounts(), ...); };
  return out;
}

// ---- Rigid bodies (cfg problems) ----------------------------------------------------

/// Options of a ProblemSetup's checkers (each checker reads its own).
struct SetupOptions {
  /// fcl-continuous: FCL's solver (FclCcdOptions; the other settings FCL's defaults).
  FclCcdSolver continuous_solver = FclCcdSolver::kConservativeAdvancement;
  /// mdd: the MddScene's options (rotation tolerance, refinement levels).
  MddSceneOptions mdd;
  /// Set up even when the checker finds the start or the goal in collision
  /// (ProblemSetup otherwise throws): the planners then refuse them in every
  /// run. For a config whose endpoints the user trusts more than the checker.
  bool allow_invalid_endpoints = false;
};

/// What a rigid checker is installed on.
struct RigidCheckerContext {
  ompl::base::SpaceInformationPtr si;  ///< the checkers go here
  PlanningSpacePtr space;              ///< the space of si, with the pose of a state
  std::shared_ptr<const scene::RigidBody> robot;
  std::shared_ptr<const scene::World> world;
  SetupOptions options;
};

/// One entry of rigidCheckers().
struct RigidChecker {
  const char* name;         ///< as --checkers, the logs and the reports spell it
  const char* description;  ///< one line, for --help and the docs
  InstalledChecker (*install)(const RigidCheckerContext& context);
};

/// The table, in the order the benchmark runs them (mdd, fcl, fcl-continuous, then
/// the registered ones: hull-cast when registerHullCastCheckers() was called).
const std::vector<RigidChecker>& rigidCheckers();
/// The names of rigidCheckers(), in order.
std::vector<std::string> rigidCheckerNames();
/// The entry called `name`; throws InvalidInputError "unknown checker 'NAME'
/// (known: mdd, fcl, fcl-continuous)".
const RigidChecker& findRigidChecker(const std::string& name);
/// A comma-separated list of checker names ("mdd,fcl"), in order; throws
/// InvalidInputError for an unknown or repeated name or an empty list.
std::vector<std::string> parseCheckerList(const std::string& list);
/// Appends `checker` to rigidCheckers() (after the built-in ones, in call
/// order). A second call with the same entry does nothing. Throws
/// InvalidInputError for an unset field, an empty name or one with a comma,
/// or a name the table has for another checker. Not thread-safe: call it at
/// start-up, before the tables are read (it may move the table's entries).
void addRigidChecker(const RigidChecker& checker);

// ---- Arms (MotionBenchMaker problems) -------------------------------------------

/// fcl-fine's default longest valid segment (joint-space distance, radians):
/// the 1/32 per unit of joint-space distance VAMP samples its edges at.
inline constexpr double kDefaultFineResolution = 1.0 / 32.0;

/// What an arm checker is installed on.
struct ArmCheckerContext {
  ompl::base::SpaceInformationPtr si;     ///< the checkers go here
  ArmSpacePtr space;                      ///< the space of si
  std::shared_ptr<const ArmScene> scene;  ///< the problem's links, world and checked pairs
  /// FCL objects of the same pieces and pairs (built once per problem; the
  /// bench's verification uses it too).
  std::shared_ptr<const FclArmScene> fcl;
  /// fcl-fine's longest valid segment (joint-space distance, radians).
  double fine_resolution = kDefaultFineResolution;
};

/// One entry of armCheckers().
struct ArmChecker {
  const char* name;
  const char* description;
  InstalledChecker (*install)(const ArmCheckerContext& context);
};

/// The table, in the order the arm benchmark runs them (mdd, fcl, fcl-fine,
/// then the registered ones).
const std::vector<ArmChecker>& armCheckers();
std::vector<std::string> armCheckerNames();
/// Throws InvalidInputError "unknown arm checker 'NAME' (known: ...)".
const ArmChecker& findArmChecker(const std::string& name);
/// As parseCheckerList, for arm checker names.
std::vector<std::string> parseArmCheckerList(const std::string& list);
/// As addRigidChecker, for armCheckers().
void addArmChecker(const ArmChecker& checker);

}  // namespace mddual::planning
