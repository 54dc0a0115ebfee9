// MddScene: the collision queries of the planning layer on MDD-DUAL, at the
// level of poses (no OMPL types): a robot (scene::RigidBody, frame R) against a
// static world (scene::World, frame W). The OMPL checkers and the directed
// clearance queries are thin layers over it.
//
// What it guarantees (touching counts as collision everywhere, like FCL):
//
//  - collides(X_WR): exact up to the core's touching tolerance (1e-10 of the
//    pair's size): every robot piece against the world pieces whose bounding
//    boxes meet its box at X_WR, with mddual::intersect (early escape).
//
//  - sweep(X_WR, v_W): the robot translating from X_WR by s v_W, s in [0, 1]
//    (orientation fixed). Exact: one mddual::toi per candidate pair (candidates:
//    world pieces whose boxes meet the union of the piece's boxes at both
//    ends, which holds the piece's whole sweep), max_distance = |v_W| (shrunk to
//    the best contact so far when the first contact is wanted).
//
//  - checkEdge(motion): an edge under OMPL's interpolation (EdgeMotion).
//    Translation edges: sweep() at the start orientation, exact; the first
//    contact fraction is exact. Rotating edges: SOUND, never "free" when the
//    motion collides, by this scheme:
//      Split [0, 1] into n equal sub-edges with angle / n * r <= 2 delta
//      (r = RigidBody::radius(), the largest distance of a robot point from
//      the body origin; the rotation is about that origin at constant angular
//      speed, so the angle is linear in t). On a sub-edge [ta, tb] with middle
//      tm, R(t) = R(tm) Rot(axis, a) with |a| <= (tb - ta) angle / 2, so every
//      body point x satisfies |R(t) x - R(tm) x| <= |a| |x| <= delta. Hence the
//      robot at time t lies inside the robot at orientation R(tm) enlarged by
//      the ball of radius delta, placed at p(t); p(t) runs along the segment
//      p(ta) -> p(tb). We replace the ball by a polytope Q that contains it,
//      an icosahedron or a cube of inradius delta (whichever gives the hull
//      fewer vertices): the enlarged piece is the hull of {v + q_k}, the
//      Minkowski sum of the piece and Q, which contains piece + ball. We
//      sweep that enlarged robot from p(ta) to p(tb): if it touches nothing,
//      neither does the true motion on [ta, tb]. If it first touches at
//      distance d along the sub-edge's translation, the true motion is free on
//      [ta, ta + (tb - ta) d / |p(tb) - p(ta)|): a lower bound of the first
//      contact. A pure rotation sub-edge (no translation) uses intersect().
//      Refinement: a sub-edge that fails is split in two and each half checked
//      with delta / 2 (the halves rotate half as much, so the bound above holds
//      with delta / 2), down to `refinement_levels` times; only the finest
//      level's failure makes the edge invalid. This keeps the scheme's false
//      alarms to clearances below delta / 2^levels while the common free
//      sub-edges are checked at the coarse delta.
//    A small safety factor (1e-6) in n absorbs the round-off of OMPL's
//    quaternion slerp (states stored with norms within 1e-9 of 1).
//
// Thread safety: const methods may be called from any number of threads. Warm
// starts are kept per thread, per (robot piece, world piece, enlargement
// level) and per MddScene instance (PerThread, keyed by an instance id).
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

#include "mddual/planning/per_thread.h"
#include "mddual/planning/state_space.h"
#include "mddual/query.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

/// Options of an MddScene.
struct MddSceneOptions {
  /// delta of the rotating-edge scheme (world units): the largest distance a
  /// robot point moves within a sub-edge's half. <= 0 selects the default,
  /// kDefaultRotationToleranceRel * RigidBody::radius(). Must be at least
  /// 1e-6 * radius (more sub-edges than that would be pointless).
  double rotation_tolerance = 0.0;
  /// Halvings of delta tried on a failing sub-edge before the edge is
  /// declared invalid (0 to 8).
  int refinement_levels = 3;
};

/// Default delta relative to the robot radius: 2%. Sub-edges every 0.04 rad
/// (25 per radian); an enlarged piece reaches at most 1.73 delta beyond the
/// piece (the cube's circumradius), 0.43% of the radius after the default 3
/// refinements. Relative to the robot, not to the space's resolution: the
/// enlargement is what costs completeness, and it should be small against the
/// robot, whatever the size of the world. Measured on the tests' scenes
/// (2,000 rotating edges each): 2% finds 0 to 6 free edges invalid, 5% 5 to
/// 26, for about the same time (fewer sub-edges, more refinement); 1% costs
/// 30% more time.
inline constexpr double kDefaultRotationToleranceRel = 0.02;

/// One contact between a robot piece and a world piece.
struct PieceContact {
  int robot_piece = -1;  ///< index into RigidBody::pieces()
  int world_piece = -1;  ///< index into World::pieces()
  /// Point of the world piece that the robot piece touches (world frame); NaN
  /// when the contact is an overlap found by a state test (no single point).
  Eigen::Vector3d p_WC = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Unit normal of the contact, pointing from the world piece toward the robot
  /// piece (world frame); NaN with p_WC.
  Eigen::Vector3d n_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// Result of MddScene::sweep().
struct SweepResult {
  bool start_collides = false;  ///< the robot already touches or overlaps the world at s = 0
  /// Distance along v_W (world units) to the first contact: 0 when the start
  /// collides, +infinity when no contact within |v_W|. When only any contact
  /// was asked for (first_contact = false), a contact distance, not
  /// necessarily the first.
  double distance = std::numeric_limits<double>::infinity();
  PieceContact contact;  ///< the pair of that contact
  int pair_queries = 0;  ///< core queries (toi/intersect) run
};

/// Result of MddScene::checkEdge(): the first contact on an edge.
struct EdgeContact {
  bool collides = false;        ///< some state of the edge (closed, both ends included) collides
  bool start_collides = false;  ///< the edge's start state collides (fraction 0)
  /// Fraction in [0, 1] of the first contact: every state before it is free.
  /// Exact for translation edges; for rotating edges a lower bound (the scheme
  /// above). +infinity when the edge is free. With first_contact = false, only
  /// `collides` is meaningful.
  double fraction = std::numeric_limits<double>::infinity();
  bool exact = true;     ///< fraction is exact (translation edge), not a bound
  PieceContact contact;  ///< for rotating edges: the contact of the enlarged robot
  int pair_queries = 0;  ///< core queries run
  int sub_edges = 0;     ///< sub-edges swept (rotating edges, refinement included)
};

/// See the file comment.
class MddScene {
 public:
  /// Throws InvalidInputError for a null robot or world or bad options.
  MddScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
           const MddSceneOptions& options = MddSceneOptions());

  const scene::RigidBody& robot() const { return *robot_; }
  const scene::World& world() const { return *world_; }
  const std::shared_ptr<const scene::RigidBody>& robotPtr() const { return robot_; }
  const std::shared_ptr<const scene::World>& worldPtr() const { return world_; }
  /// delta (world units).
  double rotationTolerance() const { return delta_; }
  int refinementLevels() const { return static_cast<int>(enlarged_.size()) - 1; }
  /// Robot pieces enlarged by delta / 2^level (frame R), level in [0, refinementLevels()].
  const std::vector<scene::Piece>& enlargedPieces(int level) const { return enlarged_.at(level); }
  /// Number of sub-edges of a rotating edge at the coarse level.
  int subEdgeCount(double angle) const;

  /// Whether the robot at X_WR touches or overlaps a world piece. `which`
  /// receives the first colliding pair found (p_WC, n_W NaN).
  bool collides(const Eigen::Isometry3d& X_WR, int* pair_queries = nullptr, PieceContact* which = nullptr) const;

  /// The robot translating by s v_W from X_WR, s in [0, 1]. first_contact:
  /// find the first contact (all candidate pairs); otherwise stop at any.
  SweepResult sweep(const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, bool first_contact = true) const;

  /// The robot's motion along an edge (see the file comment). first_contact:
  /// the first contact fraction (sub-edges in order from the start);
  /// otherwise validity only: sub-edges in bisection order, any contact stops
  /// a sweep, and a coarse sub-edge that fails is first tested at its middle
  /// and end states with the true pieces (a collision there settles the edge
  /// without refinement). Both modes agree on `collides`.
  EdgeContact checkEdge(const EdgeMotion& motion, bool first_contact = true) const;

  // ---- Building blocks on a chosen piece set (0: the robot's pieces; k >= 1:
  // enlargedPieces(k - 1)); for the clearance queries and tests.
  const std::vector<scene::Piece>& pieceSet(int set) const;
  bool collidesSet(int set, const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const;
  SweepResult sweepSet(int set, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, double max_distance,
                       bool first_contact) const;
  /// Appends the candidate world pieces of robot piece `piece` of set `set`
  /// moving from X_WR by s v_W, s in [0, max_distance / |v_W|] (v_W may be
  /// zero; max_distance may be +infinity).
  void sweptCandidates(int set, int piece, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                       double max_distance, std::vector<int>* out) const;
  /// This thread's warm start for a pair of piece set `set`.
  WarmStart* warmStart(int set, int robot_piece, int world_piece) const;

 private:
  struct WarmTable {
    std::unordered_map<std::uint64_t, WarmStart> map;
  };
  struct SubEdge {
    bool free = true;
    double fraction = std::numeric_limits<double>::infinity();
    PieceContact contact;
  };
  SubEdge checkSubEdge(const EdgeMotion& motion, double ta, double tb, int level, bool first_contact,
                       EdgeContact* stats) const;
  std::shared_ptr<WarmTable> warmTable() const;
  static WarmStart* warmIn(WarmTable& table, int set, int robot_piece, int world_piece);

  std::shared_ptr<const scene::RigidBody> robot_;
  std::shared_ptr<const scene::World> world_;
  double delta_ = 0.0;
  std::vector<std::vector<scene::Piece>> enlarged_;
  PerThread<WarmTable> warm_;
};

/// The pieces of `pieces` enlarged to contain every point within `delta` of
/// them: the Minkowski sum with an icosahedron or a cube of inradius delta
/// (the one whose hull has fewer vertices), as kConvex pieces.
std::vector<scene::Piece> enlargePieces(const std::vector<scene::Piece>& pieces, double delta);

}  // namespace mddual::planning
