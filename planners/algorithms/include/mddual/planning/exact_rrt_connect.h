// ExactRRTConnect, the planner mdd_rrtconnect (its one name, kExactRRTConnectName):
// RRT-Connect (Kuffner and LaValle, 2000) whose EXTEND step
// first tries the whole straight edge to the target and, when that edge is
// blocked, falls back to RRT-Connect's step toward it (blocked_range long),
// kept up to its first contact (the motion validator's lastValid) instead
// of dropped.
//
// Why: with MDD-DUAL's motion validator an edge of any length costs one exact
// query per nearby pair of pieces, so a free edge to a far target is one
// check instead of the many steps of RRT-Connect's "step by range"; and a
// blocked step keeps what is free of it. CONNECT repeats its extension
// toward the new node while the other tree advances (the whole edge, or a
// step kept whole or up to lastValid, at least min_progress validity-checking
// steps long) and stops when it reaches the node or adds nothing; with a
// range set (and blocked_range no shorter), that is the CONNECT loop of
// OMPL's RRT-Connect. It works with any motion validator that fills
// lastValid (OMPL's DiscreteMotionValidator does, at its resolution), which
// is how it runs in the benchmark beside OMPL's planners with every checker.
//
// Why a step when blocked, not the whole edge up to its contact: a lastValid
// check costs MDD-DUAL several times a validity check (it must prove the edge
// free up to the contact, not find one contact), and most blocked edges are
// short ones near the trees' obstacles (CONNECT's, and extensions toward near
// samples), whose lastValid gains little. Against the whole edge, a step of
// 0.2 of the maximum extent (OMPL's default range) cut the median 1.8x to 2.7x
// on bugtrap and 1.2x to 1.6x on the maze, while the whole edge stays the
// faster through narrow slots, hence whole_edge_last_valid (`mddual bench
// --planners mdd_rrtconnect` on the mesh configs; docs/results/tuning.md).
//
// Rotate, then translate (SE(2) and SE(3)): on OMPL's
// SE2StateSpace and SE3StateSpace an extension from q to a target t is two
// edges: a rotation in place (q's position, t's orientation) and then a pure
// translation to t. Under OMPL's interpolation (position linear, orientation
// slerp) the first edge keeps the position and the second the orientation, so
// the path OMPL executes is exactly the one checked; the translation edge is
// one exact sweep with MDD-DUAL (first contact = lastValid), and the rotation
// in place sweeps less volume than a rotation combined with a long
// translation. A blocked rotation (its step kept as any blocked edge's) ends
// the extension there. A rotation in place is short in the space's distance
// (at most pi/2 in SE(3), pi/2 in SE(2) with OMPL's weights), mostly no
// longer than the default blocked_range, so a blocked one mostly adds
// nothing: with rotate_first, a smaller blocked_range or
// whole_edge_last_valid keeps those. Other spaces extend along the straight edge as before.
//
// Parameters (ompl::base::ParamSet): "range" (0 = unlimited, the default:
// extensions are only limited by contact), "blocked_range" (the step a
// blocked edge falls back to, a distance; 0, the default, is OMPL's default
// planner range, 0.2 of the space's maximum extent, set by setup() as OMPL's
// RRT-Connect sets its range; a value at least the length of every edge
// makes every blocked edge add nothing), "whole_edge_last_valid" (1: every
// edge is one lastValid check of the whole edge, kept up to lastValid when
// blocked, with no validity check first and no step: this planner before
// blocked_range, the faster in narrow passages, below; 0, the default),
// "min_progress" (in validity-
// checking steps of the edge: its length over the space's validSegmentCount,
// the step of OMPL's discrete check of that edge; 1 by default: a blocked
// extension gaining less than that adds nothing, nor one gaining less than
// 1e-9 steps whatever the value, 0 included; with MDD-DUAL's validator a
// rotating edge blocked within its first step returns lastValid 0, so a
// value below 1 keeps no more of those edges than 1 does), "probe_steps"
// (in the same steps; 4 by default, 0: no probe: before the motion check of
// an edge longer than that many steps, the state that many steps into it is
// tested, and when it collides the edge adds nothing and the extension ends;
// a rotation in place already kept stays), "rotate_first"
// (1: the two-edge extension where the space allows it; 0, the default:
// straight edges everywhere). Rotating first was the default for a while; it made the
// planner about 10x slower on the SE(2) maze and the SE(3) cubicles (docs/planning.md,
// "The benchmark"), so it is off.
//
// Why one step for min_progress: on a translation edge MDD-DUAL's validator
// returns as lastValid a state at most one step of the edge before the first
// contact (on a rotating edge, at most one step before a lower bound of it,
// which may be earlier). Extending again toward the same target from that
// state follows the same path (OMPL's interpolation of a part of an edge is
// that part of the edge, in R^n, SE(2) and SE(3)), so it meets the same
// contact, and on a translation edge gains less than a step of the first
// edge; with a threshold of 1e-6 of the maximum extent, as before, CONNECT
// repeated that creep, one lastValid check each time. (OMPL's discrete
// validator creeps little: its lastValid is a step before its first colliding
// sample, near which the next extension samples.) A threshold of one step of
// the edge made the median 1.3x to 4.5x lower than that 1e-6 in all 10
// (config, seed) groups of `mddual bench` on the mesh configs; the space's
// longest valid segment, tried first as the step, discards real progress of
// turning edges (docs/results/tuning.md).
//
// Why a probe four steps in: an edge blocked within its first few steps
// gains little (at most the steps before its contact), and with MDD-DUAL's
// validator its lastValid search is the dearest check the planner makes.
// In a recorded bugtrap run, most blocked rotating edges that were free one step
// in still returned less than a step, after a large share of the run's
// rotating searches. One state test is meant to end many of those first (not
// those free again four steps in); it also drops the edges blocked between
// the first and the fourth step that the search would have kept. The probe is
// the planner's, so it runs with every motion validator; with OMPL's discrete
// validator, which samples from the start, it saves at most a few state tests
// of a blocked edge and repeats one of every other. Four steps gave lower
// medians than no probe in 13 of 15 (config, seed) groups (`mddual bench`
// with the MDD checkers on the mesh configs; docs/results/tuning.md).
#pragma once

#include <memory>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/datastructures/NearestNeighbors.h>

namespace mddual::planning {

/// The planner's one name: in a cfg's [planner] section, --planners,
/// makePlanner, the benchmark logs and Planner::getName().
inline constexpr const char* kExactRRTConnectName = "mdd_rrtconnect";

OMPL_CLASS_FORWARD(ExactRRTConnect);

class ExactRRTConnect : public ompl::base::Planner {
 public:
  explicit ExactRRTConnect(const ompl::base::SpaceInformationPtr& si);
  ~ExactRRTConnect() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  /// Throws InvalidInputError for a negative or NaN range (0: unlimited).
  void setRange(double range);
  double getRange() const { return range_; }
  /// Throws InvalidInputError for a negative, infinite or NaN value (0:
  /// OMPL's default range, set by setup()).
  void setBlockedRange(double range);
  double getBlockedRange() const { return blocked_range_; }
  /// Throws InvalidInputError for a negative, infinite or NaN value.
  void setMinProgress(double steps);
  double getMinProgress() const { return min_progress_; }
  /// Throws InvalidInputError for a negative, infinite or NaN value.
  void setProbeSteps(double steps);
  double getProbeSteps() const { return probe_steps_; }
  void setWholeEdgeLastValid(bool whole_edge) { whole_edge_last_valid_ = whole_edge; }
  bool getWholeEdgeLastValid() const { return whole_edge_last_valid_; }
  void setRotateFirst(bool rotate_first) { rotate_first_ = rotate_first; }
  bool getRotateFirst() const { return rotate_first_; }

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
  /// One edge from `from` toward `to` (one validity check; when blocked and
  /// longer than blocked_range, the step of blocked_range toward `to`, up to
  /// lastValid if that is progress; with whole_edge_last_valid, one lastValid
  /// check of the whole edge): the motion added, or nullptr.
  Motion* edge(const Tree& tree, Motion* from, const ompl::base::State* to, bool* reached);
  /// One lastValid check of from -> to: the motion to `to` when it is free
  /// (*free), else to the last valid state when that is progress, else
  /// nullptr.
  Motion* upToLastValid(const Tree& tree, Motion* from, const ompl::base::State* to, bool* free);
  /// Whether keeping `fraction` of the edge from -> to gains at least
  /// min_progress of its validity-checking steps (and kMinGainSteps).
  bool isProgress(double fraction, const ompl::base::State* from, const ompl::base::State* to) const;
  /// The step a blocked edge falls back to: blocked_range, or OMPL's default
  /// range when it is 0 (set to 0 after setup()).
  double blockedStep() const;
  /// Writes `from`'s position with `to`'s orientation to `out`; false when
  /// the space is not SE(2) or SE(3) (or rotate_first is off).
  bool rotationInPlace(const ompl::base::State* from, const ompl::base::State* to, ompl::base::State* out) const;
  Motion* addMotion(const Tree& tree, Motion* parent, const ompl::base::State* state);
  void freeTree(const Tree& tree);
  double distance(const Motion* a, const Motion* b) const;

  Tree start_tree_;
  Tree goal_tree_;
  ompl::base::StateSamplerPtr sampler_;
  double range_ = 0.0;
  double blocked_range_ = 0.0;  ///< distance (see the header; 0 until setup(): OMPL's default range)
  double min_progress_ = 1.0;   ///< validity-checking steps (see the header)
  double probe_steps_ = 4.0;    ///< validity-checking steps (see the header; 0: no probe)
  bool rotate_first_ = false;
  bool whole_edge_last_valid_ = false;
  std::pair<ompl::base::State*, ompl::base::State*> connection_{nullptr, nullptr};
};

}  // namespace mddual::planning
