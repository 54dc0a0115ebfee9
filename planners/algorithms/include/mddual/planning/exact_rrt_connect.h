// ExactRRTConnect: RRT-Connect (Kuffner and LaValle, 2000) whose EXTEND step
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
// Why a step when blocked, not the whole edge up to its contact (what this
// planner did until this round): a lastValid check costs MDD-DUAL several
// times a validity check (it must prove the edge free up to the contact, not
// find one contact), and most blocked edges are short ones near the trees'
// obstacles (CONNECT's, and extensions toward near samples), whose lastValid
// gains little. Measured (mddual bench --checkers mdd --planners
// mdd_rrtconnect --runs 10 --time-limit 10, seeds 1 to 3, every run solved;
// medians, the whole edge up to lastValid -> the step of 0.2 of the maximum
// extent): bugtrap 0.423 / 0.236 / 0.304 s -> 0.236 / 0.123 / 0.111,
// cubicles_mesh 4.07 / 4.63 / 4.75 ms -> 3.35 / 4.01 / 2.53, maze_planar
// 0.0954 / 0.0920 / 0.0835 s -> 0.0616 / 0.0588 / 0.0672, the apartment
// 0.334 / 0.250 / 0.231 s -> 0.344 / 0.236 / 0.308, twistycool 0.164 /
// 0.493 / 0.922 s -> 1.09 / 0.590 / 0.686 (OMPL's RRT-Connect with the same
// checker: bugtrap 0.114 / 0.214 s, twistycool 3.63 / 3.45 s with seeds 1
// and 2). Asking lastValid of a blocked edge no longer than the step too
// gave back most of the gain (bugtrap 0.241 / 0.272 / 0.304 s, twistycool
// 0.507 / 0.642 / 0.717, the maze 0.107 / 0.108 / 0.108), and
// checking the step for validity only lost twistycool (seed 3: 5.52 s, 8 of
// 10 solved) while it gained bugtrap (0.0792 s). Other steps (the same
// runs): 0.1 of the extent made twistycool faster (0.461 / 0.208 / 0.499 s)
// and bugtrap slower (0.309 / 0.468 / 0.154 s), the cubicles 1.3x slower,
// the maze 1.1x, the apartment 0.91x to 1.41x; 0.4 made twistycool slower than
// the whole edge (3.02 / 2.46 / 2.26 s) and the maze 1.3x slower. 0.2, OMPL's
// own default range, lies between them. Where the way is a narrow slot the
// whole edge up to lastValid stays the faster (whole_edge_last_valid = 1):
// twistycool above, the narrow passage 0.796 / 0.565 s against 1.97 / 1.16
// (seeds 1 and 2); asking lastValid of short blocked edges only in CONNECT,
// or only in EXTEND, recovered neither (narrow passage 1.63 / 0.954 / 0.847
// and 2.33 / 0.880 / 1.18 s), the latter slowing bugtrap (0.389 / 0.871 /
// 0.290 s).
//
// Rotate, then translate (SE(2) and SE(3), issue 9 item 7): on OMPL's
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
// sample, near which the next extension samples.) Measured (docs/results/mesh-history.md,
// the mdd_rrtconnect paragraphs; five mesh configs, two seeds,
// 10 runs each): the median fell by 1.3x to 4.5x in all 10 (config, seed)
// groups. The space's longest valid segment (resolution x the sum of the
// extents) as the step, tried first, is 6% to 21% longer than a pure
// translation's step on the mesh configs and 6 to 19 of a pure rotation's
// (1 + translation extent / rotation extent): it discards real progress of
// turning edges. Against it the edge's step was faster in 7 of the 10 groups
// (1.08x to 2.3x), within 2% in 2, slower in 1 (twistycool with seed 1:
// 4.28 s, 8 of 10 solved, against 3.60 s, 9 of 10).
//
// Why a probe four steps in: an edge blocked within its first few steps
// gains little (at most the steps before its contact), and with MDD-DUAL's
// validator its lastValid search is the dearest check the planner makes.
// In a recorded bugtrap run (docs/results/planning-speed.md, "What mdd_rrtconnect's
// lastValid searches on bugtrap are spent on") 804 of the 1,240 searched blocked
// rotating edges, though free one step in, returned less than a step (and
// were dropped by min_progress) after 42% of the triples of all the run's
// rotating searches (valid edges' included). One state test is meant to end
// many of those first (not those free again four steps in); it also drops
// the edges blocked between the first and the fourth step that the search
// would have kept. The probe is the planner's, so it runs with every motion
// validator; with OMPL's discrete validator, which samples from the start,
// it saves at most a few state tests of a blocked edge and repeats one of
// every other. Measured with the MDD checkers on the
// five mesh configs (docs/results/planning-speed.md, "A probe before each
// extension's motion check"; 20 runs, seeds 1 to 3): 4 steps gave lower medians than no probe
// in 13 of 15 (config, seed) groups (bugtrap 0.35 -> 0.215 s with seed 1,
// the apartment 0.713 -> 0.251 s with seed 2; twistycool and the cubicles
// slower with seed 1, 0.589 -> 0.663 s and 3.56 -> 3.94 ms); 2 and 3 steps
// gained less, 6 about as much as 4.
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
