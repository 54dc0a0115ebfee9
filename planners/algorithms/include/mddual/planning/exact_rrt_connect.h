// ExactRRTConnect: RRT-Connect (Kuffner and LaValle, 2000) whose EXTEND step
// goes along the straight edge to the target and, when the edge is blocked,
// keeps the part up to the first contact (the motion validator's lastValid)
// instead of advancing by a fixed step.
//
// Why: with MDD-DUAL's motion validator an edge of any length costs one exact
// time-of-impact query per nearby pair of pieces, so the classic "step by
// range" of RRT-Connect only adds checks; going straight to the first contact
// makes every extension as long as the free space allows, and CONNECT
// finishes in a single call (it either reaches the other tree or stops at the
// obstacle). It works with any motion validator that fills lastValid (OMPL's
// DiscreteMotionValidator does, at its resolution), which is how it runs in
// the benchmark beside OMPL's planners with every checker.
//
// Parameters (ompl::base::ParamSet): "range" (0 = unlimited, the default:
// extensions are only limited by contact), "min_progress" (fraction of the
// space's maximum extent below which a blocked extension adds nothing).
#pragma once

#include <memory>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/datastructures/NearestNeighbors.h>

namespace mddual::planning {

OMPL_CLASS_FORWARD(ExactRRTConnect);

class ExactRRTConnect : public ompl::base::Planner {
 public:
  explicit ExactRRTConnect(const ompl::base::SpaceInformationPtr& si);
  ~ExactRRTConnect() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  void setRange(double range) { range_ = range; }
  double getRange() const { return range_; }
  void setMinProgress(double fraction) { min_progress_ = fraction; }
  double getMinProgress() const { return min_progress_; }

 private:
  struct Motion {
    ompl::base::State* state = nullptr;
    Motion* parent = nullptr;
    const ompl::base::State* root = nullptr;  ///< the start or goal state this tree grew from
  };
  using Tree = std::shared_ptr<ompl::NearestNeighbors<Motion*>>;
  enum class Extend { kTrapped, kAdvanced, kReached };

  /// Grows `tree` from its nearest motion toward `target`; the new motion, if
  /// any, is stored in *added.
  Extend extend(const Tree& tree, const ompl::base::State* target, Motion** added);
  Motion* addMotion(const Tree& tree, Motion* parent, const ompl::base::State* state);
  void freeTree(const Tree& tree);
  double distance(const Motion* a, const Motion* b) const;

  Tree start_tree_;
  Tree goal_tree_;
  ompl::base::StateSamplerPtr sampler_;
  double range_ = 0.0;
  double min_progress_ = 1e-6;
  std::pair<ompl::base::State*, ompl::base::State*> connection_{nullptr, nullptr};
};

}  // namespace mddual::planning
