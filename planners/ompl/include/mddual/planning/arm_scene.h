// ArmScene: collision queries for an articulated robot (scene::RobotModel)
// in a static world, at the level of joint configurations (no OMPL types):
// exact state checks, clearance, and certified motion checks of joint-space
// edges. The OMPL layer (arm_space.h) is a thin layer over it.
//
// Frames: W is the world frame; the robot's root link frame B sits at X_WB;
// a link's pieces are in its own frame L, at X_WL = X_WB X_BL(q).
//
// Pairs checked (touching counts as collision, as everywhere in mddual):
// every link with collision pieces against the world (unless the
// AllowedCollisions lets it touch the world), and every pair of such links
// that the AllowedCollisions does not skip.
//
// Contract of checkEdge (the proof: docs/design/arms.md). The edge is
// q(t) = q0 + t (q1 - q0), t in [0, 1], in variable space (OMPL's
// interpolation of the joints, continuous joints unwrapped by the caller).
//   - Certified with a margin: `collides` is false only when every checked
//     pair keeps at least ArmSceneOptions::contact_distance apart at every
//     t in [0, 1] (so no pair touches).
//   - `fraction` is a lower bound of the first contact: every state at
//     t < fraction keeps that clearance (what OMPL's lastValid needs; a
//     lastValid state is never within the contact distance either).
//   - A state closer than the contact distance, or an interval still
//     unresolved at max_depth halvings, counts as a contact: a false alarm
//     at worst, never a miss. `state_collides` says whether the contact
//     found is a true collision of a state.
//
// Thread safety: const methods may run from any number of threads at once.
#pragma once

#include <Eigen/Geometry>
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mddual/bvh.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/scene.h"
#include "mddual/scene/srdf.h"

namespace mddual::planning {

/// Options of an ArmScene.
struct ArmSceneOptions {
  /// Clearance (world units) that every state of an edge called free keeps;
  /// a state closer counts as a contact. A path the checker accepts thus
  /// passes a check with a smaller contact distance (the benchmark's
  /// verification uses a tenth). Smaller values refine grazing edges deeper
  /// (about log2(motion / contact_distance) halvings) and refuse fewer of
  /// them. 1e-5: far below any planning resolution, above round-off at the
  /// sizes of robot arms (metres).
  double contact_distance = 1e-5;
  /// Halvings of the edge after which an unresolved interval counts as a
  /// contact (a false alarm bound, never a miss).
  int max_depth = 40;
  /// Remember, per thread, the configurations found free (state checks and
  /// the ends of edges certified free), and skip checkEdge's end-state check
  /// for them: OMPL's bidirectional planners check many edges that end at a
  /// tree state. The search still covers the whole edge, so this changes
  /// the work, never the answer. Off to time cold motion checks.
  bool remember_free_states = true;
};

/// The pair of a contact: a link and either a world piece or another link.
struct ArmContact {
  int link = -1;
  int world_piece = -1;  ///< index into World::pieces(), or -1
  int other_link = -1;   ///< self-collision: the other link, or -1
};

/// Result of ArmScene::checkEdge().
struct ArmEdgeResult {
  bool collides = false;
  /// Lower bound of the first contact (see the file comment); +infinity when
  /// free. With EdgeQuery::kValidity only `collides` is meaningful.
  double fraction = std::numeric_limits<double>::infinity();
  /// The contact is a state of the edge that collides (else a state within
  /// contact_distance, or an interval left unresolved at max_depth).
  bool state_collides = false;
  ArmContact contact;
  /// The end state was checked on its own first (kValidity and kLastValid,
  /// unless ArmSceneOptions::remember_free_states knew it free).
  bool end_state_checked = false;
  int distance_queries = 0;  ///< pair bound queries (one link or link pair at one time)
  int intervals = 0;         ///< time intervals visited
};

/// See the file comment.
class ArmScene {
 public:
  /// Throws InvalidInputError for a null model or world, a filter of another
  /// size than the model, a non-finite X_WB or bad options.
  ArmScene(std::shared_ptr<const scene::RobotModel> model, std::shared_ptr<const scene::World> world,
           scene::AllowedCollisions filter, const Eigen::Isometry3d& X_WB = Eigen::Isometry3d::Identity(),
           const ArmSceneOptions& options = ArmSceneOptions());

  const scene::RobotModel& model() const { return *model_; }
  const scene::World& world() const { return *world_; }
  const std::shared_ptr<const scene::World>& worldPtr() const { return world_; }
  const scene::AllowedCollisions& filter() const { return filter_; }
  const Eigen::Isometry3d& baseInWorld() const { return X_WB_; }
  const ArmSceneOptions& options() const { return options_; }
  /// The link pairs the self check tests (k < l).
  const std::vector<std::pair<int, int>>& selfPairs() const { return self_pairs_; }

  /// Whether configuration q (model().numVariables() values) collides:
  /// exact up to the core's touching tolerance. `which` receives the pair.
  bool collides(const double* q, ArmContact* which = nullptr) const;
  /// Smallest signed distance over the checked pairs at q (negative: the
  /// deepest penetration depth among overlapping pairs found), +infinity
  /// when no pair exists.
  double clearance(const double* q, ArmContact* which = nullptr) const;
  /// The certified motion check of the edge from q0 to q1 (see the file
  /// comment); `query` as MddScene's: kValidity first tests the state at
  /// t = 1 and stops at any contact; kFirstContact returns the lower bound
  /// of the first one; kLastValid decides as kValidity (a free edge costs
  /// what kValidity costs) and, on a colliding edge, returns a lower bound
  /// of the first contact at most `fraction_tolerance` (in [0, 1]) below it
  /// (the motion validator passes one of OMPL's discrete steps).
  ArmEdgeResult checkEdge(const double* q0, const double* q1, EdgeQuery query, double fraction_tolerance = 0.0) const;

  /// Link poses X_WL at q.
  void linkPoses(const double* q, std::vector<Eigen::Isometry3d>* X_WL) const;
  /// Bound of how fast (world units per unit of t) the distance of pair p
  /// (pairs(): world pairs first, then self pairs) can change on an edge
  /// with variable changes dq (see docs/design/arms.md).
  double pairRate(int p, const double* dq) const;
  /// Number of pairs: links with pieces against the world (when the world
  /// has pieces), then selfPairs().
  int numPairs() const { return static_cast<int>(pairs_.size()); }

 private:
  /// A joint that moves one side of a pair relative to the other, with the
  /// farthest a point of that side gets from its origin (prismatic: 1).
  struct Mover {
    int joint = -1;
    int variable = -1;
    double multiplier = 1.0;  ///< |multiplier| of a mimic joint, else 1
    bool prismatic = false;
    double reach = 0.0;
  };
  /// One checked pair: link `link` against the world (other = -1) or link `other`.
  struct Pair {
    int link = -1;
    int other = -1;
    /// Per variable v: how far (world units per unit change of v) a point of
    /// the pair moves relative to the other side, at most.
    std::vector<double> reach;
    /// The joints that move `link` and `other` relative to the other side
    /// (below their common ancestor), root first.
    std::vector<Mover> link_movers;
    std::vector<Mover> other_movers;
  };
  /// The two sides of a pair at link poses X_WL: side A (the world, or link
  /// `link`) and side B (link `link`, or `other`) posed at X_AB in A's frame.
  struct PairView {
    const std::vector<scene::Piece>* a;
    const std::vector<scene::Piece>* b;
    const Bvh* a_tree;
    const Bvh* b_tree;
    Eigen::Isometry3d X_AB;
  };
  PairView view(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL) const;
  /// Lower bound of pair p's distance at link poses X_WL, searched below
  /// `upper`: +infinity when every piece pair is at least `upper` apart.
  double pairBound(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, double upper) const;
  /// One side of a pair: the world (link < 0) or a link, at a level of
  /// detail: its cluster hulls of that level (where it has them) or, at
  /// kPieceLevel, its pieces.
  struct Side {
    const Bvh* tree;
    const std::vector<const ConvexPolytope*>* polytopes;
  };
  /// Levels of detail, coarse to fine: cluster hulls (kClusterSizes in
  /// arm_scene.cpp), then the pieces at kPieceLevel.
  static constexpr int kPieceLevel = 2;
  Side side(int link, int level) const;
  /// Whether a side of p is finer at `level` than at level - 1.
  bool refines(const Pair& p, int level) const;
  bool pairCollides(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, ArmContact* which) const;
  double pairDistance(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, ArmContact* which) const;
  /// checkEdge's search for the first contact of pair p on [a, b], every
  /// state before a being free; true when it found one (recorded in w).
  struct EdgeWork;
  /// The time window around the probe of `w` (at most tau) in which pair p
  /// keeps the contact distance, from each node pair's own motion bound
  /// (docs/design/arms.md), on the two sides at `level`; a negative value
  /// when a leaf pair of that level is already within the contact distance
  /// at the probe.
  double pairWindow(EdgeWork& w, const Pair& p, double tau, int level) const;
  /// Whether the bounding balls of a self pair's two links keep the contact
  /// distance for |t - probe| <= tau (the probe of w).
  bool rootBallsClear(const EdgeWork& w, const Pair& p, double tau) const;
  bool certify(EdgeWork& w, int p, double a, double b, int depth) const;

  std::shared_ptr<const scene::RobotModel> model_;
  std::shared_ptr<const scene::World> world_;
  scene::AllowedCollisions filter_;
  Eigen::Isometry3d X_WB_;
  bool base_is_identity_ = false;  ///< X_WB_ is exactly the identity (linkPoses skips it)
  ArmSceneOptions options_;
  Bvh world_tree_;
  std::vector<const ConvexPolytope*> world_polytopes_;
  std::vector<Bvh> link_trees_;  ///< per link, frame L (empty for links without pieces)
  std::vector<std::vector<const ConvexPolytope*>> link_polytopes_;
  /// Per level below kPieceLevel and link of many pieces, the hulls of
  /// clusters of its pieces (frame L) and their tree. Empty for other links.
  struct Clusters {
    std::vector<ConvexPolytope> hulls;
    std::vector<const ConvexPolytope*> polytopes;
    Bvh tree;
  };
  std::vector<Clusters> clusters_[kPieceLevel];
  std::vector<std::pair<int, int>> self_pairs_;
  std::vector<Pair> pairs_;
  double scale_ = 1.0;  ///< size of the robot and world (round-off slack)
  /// The clearance the search proves: the contact distance plus the
  /// round-off slack of the motion bounds.
  double search_distance_ = 0.0;
  /// Unique per scene constructed: keys the per-thread memo of free
  /// configurations (arm_scene.cpp).
  std::uint64_t serial_ = 0;
  /// The pair of the last contact a validity check found: checked first
  /// next time (a hint only; any thread may overwrite it).
  mutable std::atomic<int> last_contact_{-1};
};

}  // namespace mddual::planning
