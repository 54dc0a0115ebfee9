// The planning front end: a benchmark config's problem (mddual::scene's
// ProblemConfig and ProblemScene) set up in OMPL with one of the collision
// checkers, ready for planning or for ompl::tools::Benchmark.
//
//   auto problem = mp::loadProblem("configs/thin_walls/thin_walls.cfg");
//   mp::ProblemSetup setup(problem, "mdd");
//   auto planner = setup.makePlanner(problem.config.planners[0]);
//   setup.applyPlannerContext(problem.config.planners[0]);
//   setup.simpleSetup().setPlanner(planner);
//   setup.simpleSetup().solve(1.0);
//
// What a ProblemSetup holds, in the order it is built:
//   1. the state space: PlanningSpace of the cfg's kind (SE(2), SE(3), R^2,
//      R^3) with the scene's position bounds (planar kinds: x and y only);
//      the translation-only kinds keep the start's orientation (and z = 0 for
//      R^2); their default projection is the position with OMPL's default
//      cells (OMPL's own for R^3 is a random 2-D linear map drawn anew at
//      each set-up: projection-based planners such as KPIECE would depend on
//      it, differently for each checker; for R^2 it trips an Eigen assertion
//      in OMPL 1.5.2);
//   2. the checker: the entry of rigidCheckers() (checker_registry.h) that
//      the set-up is named by (mdd, fcl, fcl-continuous) installs its state
//      validity checker and motion validator, each then wrapped so that the
//      time spent checking is measured once (a motion
//      validator's own state checks are nested in its time, not added again)
//      and the checks are counted (stats());
//   3. the cfg's space parameters ([problem] keys that are not OMPL.app's own,
//      e.g. longest_valid_segment_fraction), set on the space information
//      (every key must be one of its parameters, or "sampler"), then the state
//      space is set up again so that they take effect;
//   4. the start and goal states, which the checker must find free (the
//      exact pair test of checkStartAndGoal may call free a state that a
//      checker, within its precision, calls touching), the goal threshold
//      (the cfg's, or OMPL.app's default kDefaultGoalThreshold = 1e-6) and the
//      optimization objective if the cfg names one (length,
//      max_min_clearance, mechanical_work; with its cost threshold).
// applyPlannerContext(spec) then sets a planner's own problem.KEY overrides
// on top of the space parameters, as OMPL.app's ompl_benchmark does in its
// planner-switch event (space parameters, then the planner's context); values
// another planner's context changed are reset first, so every planner runs
// with the space parameters plus its own context only.
//
// Errors: InvalidInputError (scene::SceneError for the cfg and its files) with
// a message that names the cfg, and its line where there is one.
#pragma once

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/checker_registry.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/problem_config.h"

namespace mddual::planning {

/// The planner names a cfg may use: OMPL.app's and ours (mdd_rrtconnect).
std::set<std::string> ourPlannerNames();

/// A cfg and its scene, loaded once and shared by every set-up of it.
struct Problem {
  scene::ProblemConfig config;
  std::shared_ptr<const scene::ProblemScene> scene;
  /// The experiment's name: the cfg's name (or its file's stem), with every
  /// character other than letters, digits, '_', '.' and '-' replaced by '_'.
  std::string name;

  std::shared_ptr<const scene::RigidBody> robot() const;
  std::shared_ptr<const scene::World> world() const;
  /// The cfg's file name as messages name it (name + ".cfg" when the
  /// problem was made in code).
  std::string cfgName() const;
};

/// Reads a cfg (readProblemConfig, with our planner names) and loads its
/// scene (loadProblemScene). Throws scene::SceneError naming the file (and
/// line) for anything wrong.
Problem loadProblem(const std::filesystem::path& cfg);
/// A Problem from a config and scene made in code.
Problem makeProblem(scene::ProblemConfig config, scene::ProblemScene scene);

// clipForMessage (a user's string in a message): mddual/error.h.

/// Colliding (robot piece, world piece) pairs named by checkStartAndGoal; the
/// rest are counted.
inline constexpr std::size_t kMaxCollisionsNamed = 3;

/// Checks that the start and the goal state of `problem` can be planned from
/// and to: each position within the position bounds (x and y for the planar
/// kinds) and the robot there free of the world by the exact check of the
/// core (intersect(); touching counts as collision, as in the mdd checker).
/// OMPL's planners only report such a problem as unsolved. Throws
/// InvalidInputError "<cfg>: the start state ...", naming the state, the
/// bound it violates (axis, value, range), or the colliding robot and world
/// pieces (their origins, e.g. "robot.urdf: link 'base', collision 0 (box)"),
/// then what tells which answer to trust: the largest penetration depth among
/// the overlapping pairs (exact) and whether FCL's collide() finds a contact
/// on the same pieces.
void checkStartAndGoal(const Problem& problem);
/// The same checks, but a state in collision is returned as the message
/// checkStartAndGoal would throw (start first, then goal; empty when both are
/// free) instead of thrown; a position outside the bounds still throws. For
/// `mddual bench --allow-invalid-endpoints`.
std::vector<std::string> endpointCollisions(const Problem& problem);

/// The planning space kind of a cfg's space kind.
SpaceKind toPlanningKind(scene::SpaceKind kind);

// SetupOptions (the checkers' options): checker_registry.h.

/// What the checkers of a ProblemSetup did since the last resetStats().
struct CheckStats {
  std::uint64_t state_checks = 0;   ///< isValid() calls (also those a motion validator makes)
  std::uint64_t motion_checks = 0;  ///< checkMotion() calls
  /// Narrow-phase queries on a (robot piece, world piece) pair: MDD-DUAL's
  /// intersect/toi, FCL's collide/continuousCollide.
  std::uint64_t pair_queries = 0;
  std::uint64_t sub_edges = 0;  ///< mdd: rotating-edge sub-edges swept
  /// Wall time inside the checkers' methods (outermost calls only; summed
  /// over threads).
  double seconds = 0.0;
};

class CheckTimer;

/// See the file comment. Not copyable; one OMPL problem per instance.
class ProblemSetup {
 public:
  /// Throws InvalidInputError for a space parameter that OMPL's space
  /// information does not have or rejects, a start or goal the checker finds
  /// in collision, or a bad objective, and for a checker name that
  /// rigidCheckers() does not have (findRigidChecker's message).
  ProblemSetup(const Problem& problem, const std::string& checker, const SetupOptions& options = SetupOptions());
  ~ProblemSetup();
  ProblemSetup(const ProblemSetup&) = delete;
  ProblemSetup& operator=(const ProblemSetup&) = delete;

  const Problem& problem() const { return problem_; }
  /// The checker's name (an entry of rigidCheckers()).
  const std::string& checker() const { return checker_; }
  ompl::geometric::SimpleSetup& simpleSetup() { return *ss_; }
  const ompl::geometric::SimpleSetup& simpleSetup() const { return *ss_; }
  const ompl::base::SpaceInformationPtr& spaceInformation() const { return ss_->getSpaceInformation(); }
  const PlanningSpacePtr& planningSpace() const { return space_; }
  /// The MDD checkers' scene (checker mdd), else null: e.g. to build its
  /// enlarged robot pieces before timing (MddScene::enlargedPiece).
  const MddScene* mddScene() const { return installed_.mdd_scene.get(); }

  /// The planner of a cfg's [planner] entry: makePlanner(spec.name, si,
  /// spec.params), named spec.name unless its params set "name". Throws
  /// InvalidInputError "<cfg>:<line>: ..." for a parameter it rejects.
  ompl::base::PlannerPtr makePlanner(const scene::PlannerSpec& spec) const;
  /// Where a [planner] entry is, for messages: "<cfg>:<line>: planner 'NAME': ".
  std::string plannerWhere(const scene::PlannerSpec& spec) const;

  /// Sets the space parameters and then spec.context on the space information
  /// (see the file comment) and sets the state space up again. Throws
  /// InvalidInputError "<cfg>:<line>: problem.KEY ..." for a key the space
  /// information does not have or a value it rejects.
  void applyPlannerContext(const scene::PlannerSpec& spec);

  /// The MDD motion validator's MddMotionValidator::setDiscardedLastValidFraction
  /// (checker mdd; nothing for checkers without the setting): the benchmark sets it per planner
  /// to discardedLastValidFraction(planner). Throws as that method does.
  void setDiscardedLastValidFraction(double fraction);

  /// The checkers' counts and time since the last resetStats().
  CheckStats stats() const;
  void resetStats();

 private:
  void applyParameters(const std::vector<std::pair<std::string, std::string>>& params, const std::string& where);
  void setSampler(const std::string& name, const std::string& where);

  Problem problem_;
  std::string checker_;
  PlanningSpacePtr space_;
  std::shared_ptr<ompl::geometric::SimpleSetup> ss_;
  std::shared_ptr<CheckTimer> timer_;
  /// What the checker's install function returned (its counts, its options).
  InstalledChecker installed_;
  /// Parameter values after the space parameters, for the keys any planner's
  /// context sets (restored before each context).
  std::map<std::string, std::string> baseline_;
  std::string baseline_sampler_;
};

}  // namespace mddual::planning
