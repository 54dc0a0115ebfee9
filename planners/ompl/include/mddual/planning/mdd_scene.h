// MddScene: the collision queries of the planning layer on MDD-DUAL, at the
// level of poses (no OMPL types): a robot (scene::RigidBody, frame R) against a
// static world (scene::World, frame W). The OMPL checkers and the directed
// clearance queries are thin layers over it.
//
// Contract (touching counts as collision everywhere, like FCL):
//  - collides(X_WR) and sweep(X_WR, v_W) (a translation) are exact up to the
//    core's touching tolerance, 1e-10 of the pair's size.
//  - checkEdge(motion), an edge under OMPL's interpolation: translation edges
//    are exact; rotating edges are sound, never "free" when the motion
//    collides (a free edge within the enlargement of an obstacle may be called
//    colliding). A first contact is never later than the true one.
//  - Verdicts and first-contact distances do not depend on the history of
//    world updates (addWorldPiece, removeWorldPiece, moveWorldPiece).
// Why these hold (the hierarchies, the search over robot node, world node and
// time interval, the chord sweep, slerp round-off, worlds that change):
// docs/design/rotating-edges.md.
//
// Thread safety: const methods may be called from any number of threads. Warm
// starts are kept per thread, per (robot piece, world piece, enlargement
// level) and per MddScene instance (PerThread, keyed by an instance id).
// The updates are not thread-safe: call them only while no query runs on
// this scene or on anything that uses it (the OMPL checkers over it, the
// clearance queries): between planning calls, never during one. A World given
// to the constructor must not be changed behind the scene's back (its trees
// would no longer match it): change the scene's world through the scene.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "mddual/bvh.h"
#include "mddual/planning/per_thread.h"
#include "mddual/planning/state_space.h"
#include "mddual/query.h"
#include "mddual/scene/scene.h"

namespace mddual::planning {

/// Largest MddSceneOptions::refinement_levels and last_valid_level.
inline constexpr int kMaxRefinementLevels = 8;

/// MddSceneOptions::last_valid_level's default: level 1 keeps more of an
/// invalid edge than level 0 for about 1.3x the time per check, and solved the
/// most KPIECE runs on twistycool, bugtrap and the apartment (`mddual bench
/// --planners kpiece`, 30 runs; docs/results/tuning.md).
inline constexpr int kDefaultLastValidLevel = 1;

/// Options of an MddScene.
struct MddSceneOptions {
  /// delta of the rotating-edge scheme (world units): the enlargement of the
  /// robot pieces at the coarsest leaf queries (see docs/design/rotating-edges.md); a pair
  /// of pieces is checked with the core once its time interval is short
  /// enough that no point of the robot piece moves more than delta from the
  /// interval's middle orientation. <= 0 selects the default,
  /// kDefaultRotationToleranceRel * RigidBody::radius(). Must be at least
  /// 1e-6 * radius (more sub-edges than that would be pointless) and at most
  /// 1e6 * radius (larger enlargements only waste queries).
  double rotation_tolerance = 0.0;
  /// Halvings of delta tried on a pair that fails on its interval before the
  /// edge is declared invalid (0 to 8); levels whose enlargement is not above
  /// twice the slerp round-off growth (2e-8 of the robot radius at most) are
  /// not tried.
  int refinement_levels = 3;
  /// lastValid on rotating edges (EdgeQuery::kLastValid): the coarsest
  /// enlargement level whose leaf contact may end the search as a bound of
  /// the first contact (0 to 8; a level above refinement_levels means the
  /// finest). A contact at a coarser level is refined first, as the
  /// first-contact search refines it. Level k's piece reaches up to 1.73
  /// delta / 2^k beyond the true one, so its contact can come that much
  /// motion before the true first contact: a coarser level answers sooner
  /// and keeps less of an invalid edge. kDefaultLastValidLevel says why the
  /// default is 1.
  int last_valid_level = kDefaultLastValidLevel;
};

/// Default delta relative to the robot radius: 2%. A piece at the robot's
/// radius is checked over intervals of 0.04 rad at the coarsest level; an
/// enlarged piece reaches at most 1.73 delta beyond the piece (the cube's
/// circumradius), 0.43% of the radius after the default 3 refinements. Relative to the robot, not to the space's
/// resolution: the enlargement is what costs completeness, and it should be small against the robot, whatever the size
/// of the world. On the test scenes' 2,000 rotating edges, 2% calls 0 to 6 free edges invalid against 5 to 26 at 5%, in
/// about the same time, where 1% takes 30% longer (docs/results/tuning.md).
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
  /// The robot already touches or overlaps the world at s = 0. Always right
  /// with first_contact; without it (any contact ends the sweep) a colliding
  /// start may go unseen when another contact was found first.
  bool start_collides = false;
  /// Distance along v_W (world units) to the first contact: 0 when the start
  /// collides, +infinity when no contact within |v_W|. When only any contact
  /// was asked for (first_contact = false), a contact distance, not
  /// necessarily the first.
  double distance = std::numeric_limits<double>::infinity();
  /// No contact before it (first_contact only; without it, only a copy of
  /// `distance`): `distance` itself, or at most the sweep's stop_within less
  /// (MddScene::sweepSet). +infinity when free.
  double lower_bound = std::numeric_limits<double>::infinity();
  PieceContact contact;  ///< the pair of that contact
  int pair_queries = 0;  ///< core queries (toi/intersect) run
};

/// What MddScene::checkEdge() computes.
enum class EdgeQuery : std::uint8_t {
  /// Whether the edge collides; EdgeContact::fraction is only the contact the
  /// search stopped at.
  kValidity,
  /// Whether it collides and its first contact: exact on translation edges;
  /// on rotating edges a lower bound from the finest enlargement (delta /
  /// 2^refinement_levels).
  kFirstContact,
  /// `collides` as kValidity decides it (computed first, so a free edge costs
  /// what kValidity costs), and for a colliding edge a lower bound of its
  /// first contact: on translation edges the exact one, or with a fraction
  /// tolerance at most that much earlier (the sweep stops once no pair left
  /// can touch earlier than the best contact less the tolerance); on rotating
  /// edges the earliest contact of the enlarged pieces at the level each
  /// (robot piece, world piece, interval) reached, not refined to the finest
  /// level: usually cheaper than kFirstContact's bound, and not ordered
  /// against it (each is no later than the true first contact). What OMPL's
  /// lastValid needs.
  kLastValid,
};

/// Result of MddScene::checkEdge(): the first contact on an edge.
struct EdgeContact {
  bool collides = false;        ///< some state of the edge (closed, both ends included) collides
  bool start_collides = false;  ///< the edge's start state collides (fraction 0)
  /// Fraction in [0, 1] of the first contact: every state before it is free.
  /// Exact for translation edges (with EdgeQuery::kLastValid and a tolerance,
  /// a lower bound at most the tolerance below it: see `exact`); for rotating
  /// edges a lower bound (the scheme above; with kLastValid another, usually
  /// coarser one).
  /// +infinity when the edge is free. With EdgeQuery::kValidity only
  /// `collides` is meaningful.
  double fraction = std::numeric_limits<double>::infinity();
  /// fraction is exact (a translation edge's contact), not a bound (rotating
  /// edges; translation edges with kLastValid and a tolerance when the bound
  /// the sweep stopped at is below the contact it found)
  bool exact = true;
  /// For rotating edges: the contact of the enlarged robot piece. With
  /// kLastValid (either kind of edge) empty (pieces -1) when the fraction is
  /// a bound of the search rather than a contact found.
  PieceContact contact;
  int pair_queries = 0;  ///< core queries run
  /// Rotating edges: (robot node, world node, time interval) triples tested
  /// (refinement included).
  int sub_edges = 0;
};

/// See the file comment and docs/design/rotating-edges.md.
class MddScene {
 public:
  /// Throws InvalidInputError for a null robot or world, a robot without
  /// pieces or bad options.
  MddScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
           const MddSceneOptions& options = MddSceneOptions());

  const scene::RigidBody& robot() const { return *robot_; }
  const scene::World& world() const { return *world_; }
  const std::shared_ptr<const scene::RigidBody>& robotPtr() const { return robot_; }
  const std::shared_ptr<const scene::World>& worldPtr() const { return world_; }
  /// delta (world units).
  double rotationTolerance() const { return delta_; }
  int refinementLevels() const { return static_cast<int>(enlarged_.size()) - 1; }
  /// Robot piece i enlarged by delta / 2^level (frame R), level in [0,
  /// refinementLevels()]. Built on first use (one small hull per piece and
  /// level, two for a piece of more than three vertices: on a robot of 3,000
  /// triangles building all of them up front took most of a scene's set-up,
  /// 1.7 s for the apartment's), thread-safe; the reference stays valid for
  /// the scene's lifetime. A failure to build one (a hull error; not seen on
  /// any scene, a piece grown by a ball is full-dimensional) therefore comes
  /// from the query that first needs it, not from the constructor.
  const scene::Piece& enlargedPiece(int level, int i) const;
  /// Number of equal time intervals of a rotating edge that would keep every
  /// robot point within delta of its interval's middle orientation (the
  /// intervals the coarsest leaf queries use for a piece at the robot radius).
  int subEdgeCount(double angle) const;
  /// The hierarchies: the robot's pieces (frame R) and the world's static
  /// tree (frame W; after updates, its pieces are the world's at the last
  /// rebuild: see "Worlds that change" above).
  const Bvh& robotTree() const { return robot_tree_; }
  const Bvh& worldTree() const { return world_tree_; }
  /// World tree t (0: static, 1: overflow: the pieces added or moved since
  /// the static tree's last rebuild; either may be empty). Every current world
  /// piece is a live leaf of exactly one of them.
  const Bvh& worldTreeAt(int t) const { return t == 0 ? world_tree_ : overflow_tree_; }
  /// The world index (into world().pieces()) of piece k of world tree t, or
  /// -1 when that leaf is skipped (its piece removed, or moved into the
  /// overflow).
  int worldIndex(int t, int k) const;

  // ---- Worlds that change (see docs/design/rotating-edges.md; not thread-safe). The
  // first update copies the world: the World given to the constructor is
  // never modified, and world() / worldPtr() return the copy from then on.
  // Ids are scene::World's (a constructed world's pieces have ids 0 .. n-1).
  /// Adds a world piece (frame W); returns its id.
  int addWorldPiece(scene::Piece piece);
  /// Removes world piece `id` (scene::World::removePiece: the last piece
  /// takes its index). Throws InvalidInputError for an unknown id.
  void removeWorldPiece(int id);
  /// Poses world piece `id` at X_WP relative to its geometry as added
  /// (scene::World::movePiece). Throws as it does.
  void moveWorldPiece(int id, const Eigen::Isometry3d& X_WP);
  /// Rebuilds of the world's static tree so far (statistics and tests).
  int worldTreeRebuilds() const { return world_rebuilds_; }

  /// Whether the robot at X_WR touches or overlaps a world piece. `which`
  /// receives the first colliding pair found (p_WC, n_W NaN).
  bool collides(const Eigen::Isometry3d& X_WR, int* pair_queries = nullptr, PieceContact* which = nullptr) const;

  /// The robot translating by s v_W from X_WR, s in [0, 1]. first_contact:
  /// find the first contact (all candidate pairs); otherwise stop at any.
  SweepResult sweep(const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, bool first_contact = true) const;

  /// The robot's motion along an edge (see EdgeQuery and docs/design/rotating-edges.md).
  /// kValidity, and kLastValid on rotating edges, first test a few states
  /// with the true pieces (probeStatesCollide: the end and the middle, on
  /// rotating edges also the quarters; a collision there settles
  /// the verdict); kValidity then stops at any contact. The three queries agree on `collides`.
  /// fraction_tolerance (kLastValid only, in [0, 1]): the search for the
  /// bound stops once it is within this much (a fraction of the edge) of the
  /// best contact found so far, so the bound may be up to that much earlier
  /// than the full search's (on translation edges: than the exact contact). The motion validator passes
  /// one step of OMPL's discrete check of the edge (its lastValid is no
  /// finer; an edge of one step gets tolerance 1 and the first contact found
  /// ends the search, as OMPL's own validator then returns 0). Throws
  /// InvalidInputError for a tolerance outside [0, 1].
  EdgeContact checkEdge(const EdgeMotion& motion, EdgeQuery query, double fraction_tolerance = 0.0) const;
  /// checkEdge(motion, kFirstContact) or (first_contact = false) kValidity.
  EdgeContact checkEdge(const EdgeMotion& motion, bool first_contact = true) const {
    return checkEdge(motion, first_contact ? EdgeQuery::kFirstContact : EdgeQuery::kValidity);
  }

  // ---- Building blocks on a chosen piece set (0: the robot's pieces; k >= 1:
  // the pieces enlarged at level k - 1); for the clearance queries and tests.
  /// Piece i of set `set` (every set has robot().pieces().size() pieces).
  const scene::Piece& pieceInSet(int set, int i) const;
  bool collidesSet(int set, const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const;
  /// stop_within (>= 0; first_contact only): castFirst's CastOptions::stop_within,
  /// SweepResult::lower_bound its CastHit::lower_bound.
  SweepResult sweepSet(int set, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, double max_distance,
                       bool first_contact, double stop_within = 0.0) const;
  /// Appends the candidate world pieces of robot piece `piece` of set `set`
  /// moving from X_WR by s v_W, s in [0, max_distance / |v_W|] (v_W may be
  /// zero; max_distance may be +infinity).
  void sweptCandidates(int set, int piece, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                       double max_distance, std::vector<int>* out) const;
  /// This thread's warm start for a pair of piece set `set`.
  WarmStart* warmStart(int set, int robot_piece, int world_piece) const;

 private:
  /// Warm starts by pair, direct-mapped: a pair's slot is a hash of its key,
  /// and a pair that lands on another pair's slot takes it over with a fresh
  /// warm start. No allocation per pair and a fixed size per thread and
  /// scene (the unordered map it replaces grew to 2^17 pairs, then was
  /// cleared); a lost warm start costs speed only, never an answer.
  struct WarmTable {
    struct Slot {
      std::uint64_t key = ~std::uint64_t{0};  ///< no pair has this key
      WarmStart warm;
    };
    std::vector<Slot> slots;  ///< 2^kWarmSlotBits entries, allocated on first use
  };
  /// The robot's pieces enlarged by one delta, each built on first use.
  struct EnlargedLevel {
    double delta = 0.0;
    std::unique_ptr<std::once_flag[]> once;
    std::unique_ptr<std::optional<scene::Piece>[]> pieces;
  };
  /// Rotating edges (docs/design/rotating-edges.md); mdd_scene_rotation.cpp. With
  /// kLastValid, only the contact bound of checkEdge's kLastValid (its verdict
  /// is computed before): out->collides is false when no enlarged piece at
  /// the level its triple reached touches.
  void checkRotating(const EdgeMotion& motion, EdgeQuery query, double fraction_tolerance, EdgeContact* out) const;
  /// Whether the true robot collides at one of the edge's probe states: the
  /// end and the middle; on a rotating edge also the quarters.
  bool probeStatesCollide(const EdgeMotion& motion, EdgeContact* out) const;
  /// Throws InvalidInputError naming `who` unless `set` is a piece set
  /// (0 to refinementLevels() + 1).
  void requireSet(int set, const char* who) const;
  /// Margin that grows the robot's node volumes to hold piece set `set`.
  double marginOfSet(int set) const;
  std::shared_ptr<WarmTable> warmTable() const;
  /// The warm start of (robot piece, world piece id) of set `set`.
  static WarmStart* warmIn(WarmTable& table, int set, int robot_piece, int world_id);
  /// The world, copied on the first update.
  scene::World& mutableWorld();
  /// After an update: the overflow tree, or both trees past the limit.
  void refreshWorldTrees();
  void buildWorldTrees();

  std::shared_ptr<const scene::RigidBody> robot_;
  std::shared_ptr<const scene::World> world_;
  double delta_ = 0.0;
  int last_valid_level_ = kDefaultLastValidLevel;
  std::vector<EnlargedLevel> enlarged_;
  Bvh robot_tree_;                 ///< over robot_->pieces(), frame R
  Bvh world_tree_;                 ///< static: over the world's pieces at the last build, frame W
  Bvh overflow_tree_;              ///< over the pieces added or moved since, frame W
  std::vector<int> static_ids_;    ///< piece k of world_tree_ -> world piece id
  std::vector<int> overflow_ids_;  ///< piece k of overflow_tree_ -> world piece id
  std::vector<char> in_static_;    ///< id -> world_tree_ holds the piece's current geometry
  int stale_ = 0;                  ///< skipped leaves of world_tree_
  int world_rebuilds_ = 0;
  std::shared_ptr<scene::World> own_world_;  ///< the copy the updates modify (null before the first)
  PerThread<WarmTable> warm_;
};

/// `piece` enlarged to contain every point within `delta` of it: the
/// Minkowski sum with a cube of inradius delta (axes of the piece's frame),
/// or for a piece of more than three vertices with an icosahedron of that
/// inradius when its hull has no more vertices than the cube's; for a flat
/// piece of more than 16 vertices, the prism over its polygon grown by delta
/// in its plane, delta thick on either side (ConvexPolytope::prism: no 3D
/// hull, whose merging of the sum's two large coplanar faces is quadratic).
/// A kConvex piece within sqrt(3) delta of `piece`.
scene::Piece enlargePiece(const scene::Piece& piece, double delta);

/// The oriented box box_R (body frame R) seen at X_WR, grown to hold every
/// point of it displaced perpendicular to the unit axis axis_R by at most
/// `across` (>= 0; a rotation about the axis that moves no point of the box
/// by more, or the chord sweep's residual, see partSweep), and then by `any`
/// (>= 0) in every direction: each half extent k grows by across sqrt(1 -
/// (axis_R . b_k)^2) + any, b_k the box's axis (the support of a disk of
/// radius `across` perpendicular to the axis). The rotating scheme's robot
/// volume over a time interval (see above).
Obb rotationSweptBox(const Obb& box_R, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& axis_R, double across,
                     double any);

/// How a part of the robot moves over a time interval of a rotating edge, as
/// a straight sweep plus a growth (docs/design/rotating-edges.md, "The chord sweep"): the
/// part's points at time ta + s (tb - ta), s in [0, 1], lie within `across`
/// (a displacement perpendicular to the axis) plus `any` (any direction) of
/// the part with the body frame R at X_WR_start, translated by s v_W.
struct PartSweep {
  /// The body frame's pose at the sweep's start: orientation R(tm),
  /// position p(ta) (the arc) or p(ta) - sin(h) R(tm) k (the chord).
  Eigen::Isometry3d X_WR_start = Eigen::Isometry3d::Identity();
  /// The sweep over the interval (world units).
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();
  /// Growth perpendicular to the rotation axis (world units).
  double across = 0.0;
  /// Growth in every direction: the slerp round-off part (world units).
  double any = 0.0;
  double total() const { return across + any; }
};

/// The PartSweep of the points within `radius` of centre_R (body frame) over
/// an interval [ta, tb] whose pose X_WI has the middle orientation R(tm) and
/// the start position p(ta), whose translation is v_W = p(tb) - p(ta) and
/// whose rotation about the unit axis_R turns by half_angle (>= 0) either
/// way of R(tm); `rho` (>= 0) bounds the points' distance from the body
/// origin (it gives the slerp round-off part and caps the arc's growth). Of
/// the two sweeps of docs/design/rotating-edges.md (the arc as a disk growth,
/// the chord as a sweep), the one with less growth.
PartSweep partSweep(const Eigen::Vector3d& centre_R, double radius, double rho, const Eigen::Vector3d& axis_R,
                    double half_angle, const Eigen::Isometry3d& X_WI, const Eigen::Vector3d& v_W);

}  // namespace mddual::planning
