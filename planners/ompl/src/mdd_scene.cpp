#include "mddual/planning/mdd_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "constants.h"
#include "mddual/error.h"

namespace mddual::planning {
namespace {

using detail::kInf;
/// Slots of a warm-start table (per thread and scene): 2^15 slots of 88
/// bytes, 2.9 MB. Against the unordered map it replaced, the mesh configs'
/// checks (mddual_bench_planning --mdd-only) ran at the same speed within 7%
/// (docs/results/tuning.md).
constexpr int kWarmSlotBits = 15;
/// Sub-edge count safety factor (docs/design/rotating-edges.md: OMPL's slerp round-off).
constexpr double kSubEdgeSafety = 1e-6;
/// An enlarged piece (enlargePiece at delta) lies within this many delta of
/// the piece: the cube's circumradius sqrt(3) (the icosahedron's is 1.26),
/// with room for the 1e-9 scale margin and round-off. The robot's node
/// volumes grown by it hold the enlarged pieces.
constexpr double kEnlargedReach = 1.7320508075688772 * (1.0 + 1e-6);
/// A flat piece of more vertices than this is enlarged as a prism over its
/// polygon grown in its plane (grownPolygon), not as its sum with the cube:
/// qhull's merging makes that sum's hull quadratic in the size of its two
/// large coplanar faces (a 5,000-gon: 7.9 s per enlargement level, 77 s for a
/// one-run benchmark), while below this the sum's hull takes under a
/// millisecond and keeps fewer corners (an axis-aligned square stays a box).
constexpr int kPrismEnlargeMinVertices = 16;
/// grownPolygon turns at most this angle per corner (60 degrees): its
/// corners lie within delta / cos(30 degrees) = 1.155 delta of the polygon in
/// the plane, so the prism's corners lie within sqrt(1.155^2 + 1) = 1.53
/// delta of the piece, inside kEnlargedReach.
constexpr double kGrownPolygonMaxTurn = kPi / 3.0;
/// Smallest delta relative to the robot radius.
constexpr double kMinRotationToleranceRel = 1e-6;
/// Largest delta relative to the robot radius: beyond, the enlarged pieces
/// only waste queries (and at 1e60 left the supported coordinate range).
constexpr double kMaxRotationToleranceRel = 1e6;

/// Vertices of an icosahedron with edge length 2 and its inradius.
const std::vector<Eigen::Vector3d>& icosahedron() {
  static const std::vector<Eigen::Vector3d> v = [] {
    const double phi = 0.5 * (1.0 + std::sqrt(5.0));
    std::vector<Eigen::Vector3d> out;
    for (double a : {-1.0, 1.0}) {
      for (double b : {-phi, phi}) {
        out.emplace_back(0.0, a, b);
        out.emplace_back(a, b, 0.0);
        out.emplace_back(b, 0.0, a);
      }
    }
    return out;
  }();
  return v;
}
double icosahedronInradius() {
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  return phi * phi / std::sqrt(3.0);
}

std::uint64_t pairKey(int set, int robot_piece, int world_piece) {
  return (static_cast<std::uint64_t>(set) << 58) ^ (static_cast<std::uint64_t>(robot_piece) << 29) ^
         static_cast<std::uint64_t>(world_piece);
}

/// Corners of a polygon in the flat polytope's plane that holds the polygon
/// grown by a disc of radius r. At corner v, where the outward edge normals
/// turn by phi from u_in to u_out, the disc's arc is covered by k = ceil(phi /
/// kGrownPolygonMaxTurn) tangent segments: their meeting points are v + r u /
/// cos(phi / 2k), u the unit normals at (i + 1/2) phi / k, i < k. Each
/// tangent line bounds the grown polygon (its support in direction u is the
/// polygon's plus r, u in v's normal cone), so the polygon they enclose holds
/// it.
std::vector<Eigen::Vector3d> grownPolygon(const ConvexPolytope& flat, double r) {
  const Eigen::Vector3d& n = flat.faceNormal(0);
  const IndexRange loop = flat.faceVertices(0);  // counter-clockwise about n
  const int m = loop.size();
  auto edgeNormal = [&](int j) {  // outward unit normal of edge j -> j + 1
    return (flat.vertex(loop[(j + 1) % m]) - flat.vertex(loop[j])).cross(n).normalized();
  };
  std::vector<Eigen::Vector3d> corners;
  for (int j = 0; j < m; ++j) {
    const Eigen::Vector3d u_in = edgeNormal((j + m - 1) % m);
    const Eigen::Vector3d u_out = edgeNormal(j);
    const double phi = std::max(0.0, std::atan2(u_in.cross(u_out).dot(n), u_in.dot(u_out)));
    const int k = std::max(1, static_cast<int>(std::ceil(phi / kGrownPolygonMaxTurn)));
    const double step = phi / k;
    const double reach = r / std::cos(0.5 * step);
    for (int i = 0; i < k; ++i) {
      const double a = (i + 0.5) * step;
      const Eigen::Vector3d u = std::cos(a) * u_in + std::sin(a) * n.cross(u_in);
      corners.push_back(flat.vertex(loop[j]) + reach * u);
    }
  }
  return corners;
}

/// A hand-built EdgeMotion that PlanningSpace::motion would never make: a
/// negative angle read as no rotation at all (the edge's collisions were
/// missed), a scaled axis or start rotation failed deep in the core.
void checkMotionArgument(const EdgeMotion& motion) {
  const auto fail = [](const std::string& what) {
    throw InvalidInputError("MddScene::checkEdge: the motion's " + what);
  };
  if (!(motion.angle >= 0.0) || !std::isfinite(motion.angle)) {
    fail("angle " + std::to_string(motion.angle) + " must be finite and >= 0 (turn the axis instead)");
  }
  if (!motion.p_start.allFinite() || !motion.p_end.allFinite()) fail("positions must be finite");
  if (!(std::abs(motion.q_start.norm() - 1.0) < 1e-9)) fail("q_start must be a unit quaternion");
  // 1e-6: a gross mismatch (a scaled matrix, another rotation), not the
  // round-off between a rotation accepted within 1e-9 and its quaternion.
  if (!((motion.R_start - motion.q_start.toRotationMatrix()).cwiseAbs().maxCoeff() < 1e-6)) {
    fail("R_start must be q_start as a matrix");
  }
  if (motion.rotates() && !(std::abs(motion.axis_R.norm() - 1.0) < 1e-9)) fail("axis_R must be a unit vector");
}

}  // namespace

scene::Piece enlargePiece(const scene::Piece& piece, double delta) {
  // Two polytopes that contain the ball of radius delta: the icosahedron and
  // the cube of inradius delta (the 1e-9 margin absorbs the round-off of the
  // scale). The icosahedron adds less (circumradius 1.26 delta against 1.73),
  // the cube usually gives fewer vertices (a box aligned with the body frame
  // stays a box), which makes the queries cheaper: keep the hull with fewer
  // vertices. A piece of at most three vertices (a triangle: every piece of
  // a mesh) takes the cube without trying the icosahedron: over the 11,264
  // enlarged triangles of the apartment's robot the cube's hull had 10 to
  // 16 vertices, the icosahedron's 21 or more, and each hull is most of the
  // build's cost (mddual_bench_planning's one-time set-up of the apartment:
  // 4.1 s with both, 1.7 s with the cube alone).
  const std::vector<Eigen::Vector3d>& vertices = piece.polytope.vertices();
  const std::string origin = piece.origin + " (enlarged by " + std::to_string(delta) + ")";
  const double cube_scale = delta * (1.0 + 1e-9);
  // A large flat piece: the prism over its grown polygon, made without a 3D
  // hull. It holds the piece grown by the ball of radius delta: a point within
  // delta of the piece is within delta of its plane and, seen along the
  // normal, within delta of its polygon.
  if (piece.polytope.isFlat() && piece.polytope.numVertices() > kPrismEnlargeMinVertices) {
    ConvexPolytope prism =
        ConvexPolytope::prism(grownPolygon(piece.polytope, cube_scale), piece.polytope.faceNormal(0), cube_scale);
    return scene::Piece::make(std::move(prism), scene::PieceKind::kConvex, origin);
  }
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& v : vertices) {
    for (int c = 0; c < 8; ++c) {
      points.push_back(v +
                       cube_scale * Eigen::Vector3d((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0));
    }
  }
  ConvexPolytope cube = ConvexPolytope::fromPoints(points);
  if (vertices.size() > 3) {
    const double ico_scale = delta / icosahedronInradius() * (1.0 + 1e-9);
    points.clear();
    for (const Eigen::Vector3d& v : vertices) {
      for (const Eigen::Vector3d& q : icosahedron()) points.push_back(v + ico_scale * q);
    }
    ConvexPolytope ico = ConvexPolytope::fromPoints(points);
    if (ico.numVertices() <= cube.numVertices()) {
      return scene::Piece::make(std::move(ico), scene::PieceKind::kConvex, origin);
    }
  }
  return scene::Piece::make(std::move(cube), scene::PieceKind::kConvex, origin);
}

MddScene::MddScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
                   const MddSceneOptions& options)
    : robot_(std::move(robot)), world_(std::move(world)) {
  if (!robot_) throw InvalidInputError("MddScene: the robot is null");
  if (robot_->pieces().empty()) throw InvalidInputError("MddScene: the robot '" + robot_->name() + "' has no pieces");
  if (!world_) throw InvalidInputError("MddScene: the world is null");
  const double r = robot_->radius();
  if (!std::isfinite(options.rotation_tolerance)) {
    throw InvalidInputError("MddScene: rotation_tolerance is not finite");
  }
  delta_ = options.rotation_tolerance > 0.0 ? options.rotation_tolerance : kDefaultRotationToleranceRel * r;
  const auto text = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.6g", x);  // std::to_string wrote 1e-300 as 0.000000
    return std::string(buffer);
  };
  if (delta_ < kMinRotationToleranceRel * r) {
    throw InvalidInputError("MddScene: rotation_tolerance " + text(delta_) + " is below 1e-6 of the robot radius " +
                            text(r));
  }
  if (delta_ > kMaxRotationToleranceRel * r) {
    throw InvalidInputError("MddScene: rotation_tolerance " + text(delta_) + " is above 1e6 times the robot radius " +
                            text(r) + " (every rotating edge would be refined from pieces grown beyond the scene)");
  }
  if (options.refinement_levels < 0 || options.refinement_levels > kMaxRefinementLevels) {
    throw InvalidInputError("MddScene: refinement_levels " + std::to_string(options.refinement_levels) +
                            " is outside [0, " + std::to_string(kMaxRefinementLevels) + "]");
  }
  if (options.last_valid_level < 0 || options.last_valid_level > kMaxRefinementLevels) {
    throw InvalidInputError("MddScene: last_valid_level " + std::to_string(options.last_valid_level) +
                            " is outside [0, " + std::to_string(kMaxRefinementLevels) + "]");
  }
  last_valid_level_ = std::min(options.last_valid_level, options.refinement_levels);
  const std::size_t n = robot_->pieces().size();
  for (int level = 0; level <= options.refinement_levels; ++level) {
    EnlargedLevel e;
    e.delta = delta_ / std::ldexp(1.0, level);
    e.once = std::make_unique<std::once_flag[]>(n);
    e.pieces = std::make_unique<std::optional<scene::Piece>[]>(n);
    enlarged_.push_back(std::move(e));
  }
  std::vector<const ConvexPolytope*> polytopes;
  for (const scene::Piece& p : robot_->pieces()) polytopes.push_back(&p.polytope);
  robot_tree_ = Bvh::fromPolytopes(polytopes);
  buildWorldTrees();
  world_rebuilds_ = 0;
}

void MddScene::buildWorldTrees() {
  // No node hulls: on the trap scene (benchmarks) their lower bounds did not
  // pay for their core queries in translation sweeps.
  const std::vector<scene::Piece>& pieces = world_->pieces();
  std::vector<const ConvexPolytope*> polytopes;
  polytopes.reserve(pieces.size());
  static_ids_.clear();
  in_static_.assign(static_cast<std::size_t>(world_->idLimit()), 0);
  for (std::size_t j = 0; j < pieces.size(); ++j) {
    polytopes.push_back(&pieces[j].polytope);
    const int id = world_->idOf(static_cast<int>(j));
    static_ids_.push_back(id);
    in_static_[static_cast<std::size_t>(id)] = 1;
  }
  world_tree_ = Bvh::fromPolytopes(polytopes);
  overflow_tree_ = Bvh();
  overflow_ids_.clear();
  stale_ = 0;
  ++world_rebuilds_;
}

void MddScene::refreshWorldTrees() {
  const int n = static_cast<int>(world_->pieces().size());
  if (static_cast<int>(overflow_ids_.size()) + stale_ > scene::World::overflowLimit(n)) {
    buildWorldTrees();
    return;
  }
  std::vector<const ConvexPolytope*> polytopes;
  polytopes.reserve(overflow_ids_.size());
  for (const int id : overflow_ids_)
    polytopes.push_back(&world_->pieces()[static_cast<std::size_t>(world_->indexOf(id))].polytope);
  overflow_tree_ = Bvh::fromPolytopes(polytopes);
}

scene::World& MddScene::mutableWorld() {
  if (!own_world_) {
    own_world_ = std::make_shared<scene::World>(*world_);
    world_ = own_world_;
  }
  return *own_world_;
}

int MddScene::addWorldPiece(scene::Piece piece) {
  const int id = mutableWorld().addPiece(std::move(piece));
  in_static_.resize(static_cast<std::size_t>(world_->idLimit()), 0);
  overflow_ids_.push_back(id);
  refreshWorldTrees();
  return id;
}

void MddScene::removeWorldPiece(int id) {
  mutableWorld().removePiece(id);  // throws for an unknown id, before any change here
  if (in_static_[static_cast<std::size_t>(id)]) {
    in_static_[static_cast<std::size_t>(id)] = 0;
    ++stale_;
  } else {
    overflow_ids_.erase(std::find(overflow_ids_.begin(), overflow_ids_.end(), id));
  }
  refreshWorldTrees();
}

void MddScene::moveWorldPiece(int id, const Eigen::Isometry3d& X_WP) {
  mutableWorld().movePiece(id, X_WP);
  if (in_static_[static_cast<std::size_t>(id)]) {
    in_static_[static_cast<std::size_t>(id)] = 0;
    ++stale_;
    overflow_ids_.push_back(id);
  }
  refreshWorldTrees();
}

int MddScene::worldIndex(int t, int k) const {
  if (t == 0) {
    const int id = static_ids_[static_cast<std::size_t>(k)];
    return in_static_[static_cast<std::size_t>(id)] ? world_->indexOf(id) : -1;
  }
  return world_->indexOf(overflow_ids_[static_cast<std::size_t>(k)]);
}

double MddScene::marginOfSet(int set) const {
  return set == 0 ? 0.0 : kEnlargedReach * delta_ / std::ldexp(1.0, set - 1);
}

int MddScene::subEdgeCount(double angle) const {
  if (!(angle >= 0.0) || !std::isfinite(angle)) {
    throw InvalidInputError("MddScene::subEdgeCount: the angle " + std::to_string(angle) + " must be finite and >= 0");
  }
  const double n = std::ceil(angle * robot_->radius() / (2.0 * delta_) * (1.0 + kSubEdgeSafety));
  // At most INT_MAX (an angle of 1e300 overflowed the cast).
  return n >= static_cast<double>(std::numeric_limits<int>::max()) ? std::numeric_limits<int>::max()
                                                                   : std::max(1, static_cast<int>(n));
}

const scene::Piece& MddScene::enlargedPiece(int level, int i) const {
  if (level < 0 || static_cast<std::size_t>(level) >= enlarged_.size()) {
    throw InvalidInputError("MddScene: enlargement level " + std::to_string(level) + " does not exist (0 to " +
                            std::to_string(enlarged_.size() - 1) + ")");
  }
  const EnlargedLevel& e = enlarged_[static_cast<std::size_t>(level)];
  const std::size_t k = static_cast<std::size_t>(i);
  if (i < 0 || k >= robot_->pieces().size()) {
    throw InvalidInputError("MddScene: robot piece " + std::to_string(i) + " does not exist");
  }
  // call_once: one thread builds the piece, the others wait for it; if the
  // build throws, the flag stays unset and the next caller tries again.
  std::call_once(e.once[k], [&] { e.pieces[k].emplace(enlargePiece(robot_->pieces()[k], e.delta)); });
  return *e.pieces[k];
}

void MddScene::requireSet(int set, const char* who) const {
  if (set < 0 || set > refinementLevels() + 1) {
    throw InvalidInputError(std::string(who) + ": piece set " + std::to_string(set) +
                            " does not exist (0: the robot's pieces, 1 to " + std::to_string(refinementLevels() + 1) +
                            ": its enlargement levels)");
  }
}

const scene::Piece& MddScene::pieceInSet(int set, int i) const {
  if (set != 0) return enlargedPiece(set - 1, i);  // says which level or piece does not exist
  if (i < 0 || static_cast<std::size_t>(i) >= robot_->pieces().size()) {
    throw InvalidInputError("MddScene: robot piece " + std::to_string(i) + " does not exist");
  }
  return robot_->pieces()[static_cast<std::size_t>(i)];
}

std::shared_ptr<MddScene::WarmTable> MddScene::warmTable() const {
  return warm_.local([] { return std::make_shared<WarmTable>(); });
}

WarmStart* MddScene::warmStart(int set, int robot_piece, int world_piece) const {
  // The table outlives this call: PerThread keeps it until this thread uses
  // kSlots other scenes; callers use the pointer within one query.
  return warmIn(*warmTable(), set, robot_piece, world_->idOf(world_piece));
}

WarmStart* MddScene::warmIn(WarmTable& table, int set, int robot_piece, int world_id) {
  if (table.slots.empty()) table.slots.resize(std::size_t{1} << kWarmSlotBits);
  const std::uint64_t key = pairKey(set, robot_piece, world_id);
  // Fibonacci hashing: the top bits of the key times 2^64 / golden ratio.
  WarmTable::Slot& slot = table.slots[(key * 0x9E3779B97F4A7C15ull) >> (64 - kWarmSlotBits)];
  if (slot.key != key) {
    slot.key = key;
    slot.warm = WarmStart();
  }
  return &slot.warm;
}

bool MddScene::collides(const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const {
  return collidesSet(0, X_WR, pair_queries, which);
}

bool MddScene::collidesSet(int set, const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const {
  // A NaN pose fails every volume test and would reach no pair: "free".
  requireFinitePose(X_WR, "the robot pose X_WR", "MddScene::collides");
  requireSet(set, "MddScene::collidesSet");
  const std::vector<scene::Piece>& world = world_->pieces();
  // Fetched at the first pair that reaches the core and held for the rest of
  // the query: most states of a sparse scene reach none.
  std::shared_ptr<WarmTable> table;
  int queries = 0;
  bool hit = false;
  for (int t = 0; t < 2 && !hit; ++t) {
    if (worldTreeAt(t).empty()) continue;
    forEachOverlappingPair(worldTreeAt(t), robot_tree_, X_WR, marginOfSet(set), [&](int k, int i) {
      const int j = worldIndex(t, k);
      if (j < 0) return true;  // a removed or moved piece's old leaf
      IntersectInput in;
      in.a = &world[static_cast<std::size_t>(j)].polytope;
      in.b = &pieceInSet(set, i).polytope;
      in.X_WB = X_WR;
      ++queries;
      if (!table) table = warmTable();
      if (!intersect(in, warmIn(*table, set, i, world_->idOf(j))).intersecting) return true;
      if (which) {
        *which = PieceContact();
        which->robot_piece = i;
        which->world_piece = j;
      }
      hit = true;
      return false;
    });
  }
  if (pair_queries) *pair_queries += queries;
  return hit;
}

void MddScene::sweptCandidates(int set, int piece, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                               double max_distance, std::vector<int>* out) const {
  const scene::Piece& p = pieceInSet(set, piece);
  Eigen::AlignedBox3d box = scene::transformedBox(p.box, X_WR);
  const double n = v_W.norm();
  if (n > 0.0 && max_distance > 0.0) {
    const Eigen::Vector3d u = v_W / n;
    for (int k = 0; k < 3; ++k) {
      if (u[k] == 0.0) continue;
      const double reach = std::isfinite(max_distance) ? u[k] * max_distance : (u[k] > 0.0 ? kInf : -kInf);
      if (reach > 0.0) box.max()[k] += reach;
      if (reach < 0.0) box.min()[k] += reach;
    }
  }
  world_->candidates(box, out);
}

SweepResult MddScene::sweep(const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, bool first_contact) const {
  const double length = v_W.norm();
  if (length == 0.0) {
    SweepResult r;
    r.start_collides = collidesSet(0, X_WR, &r.pair_queries, &r.contact);
    if (r.start_collides) r.distance = 0.0;
    return r;
  }
  return sweepSet(0, X_WR, v_W, length, first_contact);
}

SweepResult MddScene::sweepSet(int set, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W, double max_distance,
                               bool first_contact, double stop_within) const {
  // A NaN pose fails every volume test and would reach no pair: "free".
  requireFinitePose(X_WR, "the robot pose X_WR", "MddScene::sweep");
  requireSet(set, "MddScene::sweepSet");
  SweepResult result;
  // Divided by its largest coordinate first: |v| under- or overflows for
  // directions such as [1e-200, 0, 0] (the core's rule, pair.cpp).
  const double largest = v_W.cwiseAbs().maxCoeff();
  if (!(largest > 0.0) || !v_W.allFinite()) {
    throw InvalidInputError("MddScene::sweep: the direction is zero or not finite");
  }
  if (!(max_distance >= 0.0)) throw InvalidInputError("MddScene::sweep: max_distance is negative or NaN");
  const Eigen::Vector3d u = (v_W / largest).normalized();
  const std::vector<scene::Piece>& world = world_->pieces();
  const std::shared_ptr<WarmTable> table = warmTable();
  CastOptions options;
  options.margin_b = marginOfSet(set);
  options.first_contact = first_contact;
  options.stop_within = stop_within;
  // The cast keeps the smallest distance the leaf returns; the contact of
  // that pair is recorded here (same rule: strictly smaller than the best).
  int tree = 0;
  const auto leaf = [&](int k, int i, double limit) {
    const int j = worldIndex(tree, k);
    if (j < 0) return kInf;  // a removed or moved piece's old leaf
    DirectionalInput in;
    in.a = &world[static_cast<std::size_t>(j)].polytope;
    in.b = &pieceInSet(set, i).polytope;
    in.X_WB = X_WR;
    in.s_W = u;
    in.max_distance = limit;
    in.exact_toi = first_contact;  // a yes/no sweep may stop at the first proof of a hit
    ++result.pair_queries;
    const ToiResult r = toi(in, warmIn(*table, set, i, world_->idOf(j)));
    if (r.status == ToiStatus::kNever || !(r.toi <= limit) || !(r.toi < result.distance)) return kInf;
    result.contact = PieceContact();
    result.contact.robot_piece = i;
    result.contact.world_piece = j;
    result.distance = r.toi;
    if (r.status == ToiStatus::kInContact) {
      result.start_collides = true;
      result.distance = 0.0;
      return 0.0;  // nothing comes before s = 0: the cast stops
    }
    result.contact.p_WC = r.contact.point_W;
    result.contact.n_W = r.contact.normal_W;
    return r.toi;
  };
  // One cast per world tree; the second only looks for contacts before the
  // first's (the best so far), and none is needed after any contact when
  // first_contact is false or after a start in contact.
  // The lower bound: the smallest of the casts' (each bounds the contacts
  // of its tree below the limit it was given, which no later contact beats).
  double limit = max_distance;
  for (tree = 0; tree < 2; ++tree) {
    if (worldTreeAt(tree).empty()) continue;
    const CastHit hit = castFirst(worldTreeAt(tree), robot_tree_, X_WR, u, limit, leaf, options);
    result.lower_bound = std::min(result.lower_bound, hit.lower_bound);
    if (result.start_collides || (!first_contact && result.distance < kInf)) break;
    limit = std::min(limit, result.distance);
  }
  if (result.start_collides) result.lower_bound = 0.0;
  result.lower_bound = std::min(result.lower_bound, result.distance);
  return result;
}

bool MddScene::probeStatesCollide(const EdgeMotion& motion, EdgeContact* out) const {
  // The end, then interior states in OMPL's bisection order (the middle, the
  // quarters). A translation edge takes the first two only: its exact sweep
  // costs a few state tests. A rotating edge takes all four: its search
  // costs tens of them, and an invalid edge's colliding states are often
  // found by a few samples. On most scenes' rotating checkMotion
  // (mddual_bench_planning --mdd-only --cpu) four states take up to 16% less
  // time than eight (docs/results/tuning.md, with two and sixteen).
  static constexpr std::array<double, 4> kProbes = {1.0, 0.5, 0.25, 0.75};
  const std::size_t count = motion.rotates() ? kProbes.size() : 2;
  PieceContact which;
  for (std::size_t k = 0; k < count; ++k) {
    const double t = kProbes[k];
    if (collidesSet(0, t == 1.0 ? motion.X_end : motion.pose(t), &out->pair_queries, &which)) {
      out->collides = true;
      out->fraction = t;  // a state that collides, not the first contact
      out->contact = which;
      return true;
    }
  }
  return false;
}

EdgeContact MddScene::checkEdge(const EdgeMotion& motion, EdgeQuery query, double fraction_tolerance) const {
  if (!(fraction_tolerance >= 0.0 && fraction_tolerance <= 1.0)) {
    throw InvalidInputError("MddScene::checkEdge: fraction_tolerance must be in [0, 1] (got " +
                            std::to_string(fraction_tolerance) + ")");
  }
  checkMotionArgument(motion);
  if (query != EdgeQuery::kValidity && query != EdgeQuery::kFirstContact && query != EdgeQuery::kLastValid) {
    throw InvalidInputError("MddScene::checkEdge: unknown query " + std::to_string(static_cast<int>(query)));
  }
  const bool first_contact = query != EdgeQuery::kValidity;
  EdgeContact out;
  // Validity: a few states first (the end, the middle; on rotating edges
  // also the quarters). Invalid edges often collide there, and a
  // state test (intersect, early exit) is cheaper than the edge's search.
  if (query == EdgeQuery::kValidity && probeStatesCollide(motion, &out)) return out;
  if (!motion.rotates()) {
    const Eigen::Isometry3d X = motion.pose(0.0);
    const Eigen::Vector3d v = motion.p_end - motion.p_start;
    const double length = v.norm();
    // kLastValid: the sweep may stop within the tolerance of its best contact.
    const bool tolerant = query == EdgeQuery::kLastValid && fraction_tolerance > 0.0 && length > 0.0;
    const SweepResult s =
        tolerant ? sweepSet(0, X, v, length, true, fraction_tolerance * length) : sweep(X, v, first_contact);
    out.pair_queries += s.pair_queries;
    if (s.start_collides || s.distance <= length) {
      out.collides = true;
      out.start_collides = s.start_collides;
      out.fraction = s.start_collides ? 0.0 : std::min(1.0, s.distance / length);
      out.contact = s.contact;
      if (tolerant && s.lower_bound < s.distance) {
        out.fraction = std::min(1.0, s.lower_bound / length);
        out.exact = false;
        out.contact = PieceContact();  // a bound, not a contact found
        // A bound of 0 may stop the sweep before the pair in contact at the
        // start is visited: whether the start collides is asked directly.
        if (out.fraction == 0.0 && !out.start_collides) {
          out.start_collides = collidesSet(0, X, &out.pair_queries, nullptr);
        }
      }
    } else if (motion.endDiffers()) {
      PieceContact which;
      if (collidesSet(0, motion.X_end, &out.pair_queries, &which)) {
        out.collides = true;
        out.fraction = 1.0;
        out.contact = which;
      }
    }
    return out;
  }
  out.exact = false;
  if (query == EdgeQuery::kLastValid) {
    // 1. The verdict: the probe states (a collision there settles it),
    //    else the validity search.
    bool collides = probeStatesCollide(motion, &out);
    if (!collides) {
      checkRotating(motion, EdgeQuery::kValidity, 0.0, &out);
      collides = out.collides;
    }
    if (!collides) return out;
    // 2. The first-contact bound at enlargement level last_valid_level_ or
    //    finer; when no enlarged piece touched (the verdict was a contact
    //    within the finest enlargement on triples that this search cleared:
    //    a rare false alarm, and a second full search), the finest search.
    EdgeContact bound;
    checkRotating(motion, EdgeQuery::kLastValid, fraction_tolerance, &bound);
    if (!bound.collides) checkRotating(motion, EdgeQuery::kFirstContact, 0.0, &bound);
    bound.pair_queries += out.pair_queries;
    bound.sub_edges += out.sub_edges;
    out = bound;
    out.exact = false;
    out.collides = true;
    if (!(out.fraction < kInf)) out.fraction = 0.0;  // not seen; the start is a safe bound
  } else {
    checkRotating(motion, query, 0.0, &out);
  }
  if (out.collides && out.fraction == 0.0) {
    out.start_collides = collidesSet(0, motion.pose(0.0), &out.pair_queries, nullptr);
  }
  return out;
}

}  // namespace mddual::planning
