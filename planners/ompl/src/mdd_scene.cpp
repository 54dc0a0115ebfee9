#include "mddual/planning/mdd_scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mddual/error.h"

namespace mddual::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Warm-start tables are cleared past this many pairs (per thread and scene):
/// bounds the memory of long runs over large worlds.
constexpr std::size_t kMaxWarmPairs = std::size_t{1} << 17;
/// Relative slack of the bounding-sphere culls (round-off of the transforms).
constexpr double kSphereSlack = 1e-9;
/// Sub-edge count safety factor (see the header: OMPL's slerp round-off).
constexpr double kSubEdgeSafety = 1e-6;
/// Smallest delta relative to the robot radius.
constexpr double kMinRotationToleranceRel = 1e-6;
constexpr int kMaxRefinementLevels = 8;

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

/// Whether the spheres (c1, r1) and (c2, r2) are certainly apart.
bool spheresApart(const Eigen::Vector3d& c1, double r1, const Eigen::Vector3d& c2, double r2) {
  const double r = (r1 + r2) * (1.0 + kSphereSlack);
  return (c1 - c2).squaredNorm() > r * r;
}

/// Whether the sphere (c, r) certainly misses the capsule swept by the sphere
/// (c0, r0) moving from c0 along unit u by [0, length] (length may be +inf).
bool sweptSphereApart(const Eigen::Vector3d& c0, double r0, const Eigen::Vector3d& u, double length,
                      const Eigen::Vector3d& c, double r) {
  const double s = std::clamp((c - c0).dot(u), 0.0, length);
  return spheresApart(c0 + s * u, r0, c, r);
}

/// Whether the box `moving` translated by s u, s in [0, length] (length may
/// be +inf), certainly misses the box `fixed`: the segment {s u} against the
/// box fixed - moving (a slab test).
bool sweptBoxApart(const Eigen::AlignedBox3d& moving, const Eigen::Vector3d& u, double length,
                   const Eigen::AlignedBox3d& fixed) {
  double lo = 0.0, hi = length;
  for (int k = 0; k < 3; ++k) {
    // Slack for the round-off of the boxes (relative to their coordinates).
    const double slack = kSphereSlack * (1.0 + std::abs(fixed.max()[k]) + std::abs(moving.max()[k]));
    const double a = fixed.min()[k] - moving.max()[k] - slack;  // s u_k must lie in [a, b]
    const double b = fixed.max()[k] - moving.min()[k] + slack;
    if (u[k] == 0.0) {
      if (a > 0.0 || b < 0.0) return true;
      continue;
    }
    double s0 = a / u[k], s1 = b / u[k];
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0);
    hi = std::min(hi, s1);
    if (lo > hi) return true;
  }
  return false;
}

/// Appends lo..hi in bisection order: middle first, then the middles of the
/// halves, breadth first.
void bisectionOrder(int lo, int hi, std::vector<int>* out) {
  std::vector<std::pair<int, int>> queue{{lo, hi}};
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const auto [a, b] = queue[q];
    if (a > b) continue;
    const int mid = a + (b - a) / 2;
    out->push_back(mid);
    queue.emplace_back(a, mid - 1);
    queue.emplace_back(mid + 1, b);
  }
}

std::uint64_t pairKey(int set, int robot_piece, int world_piece) {
  return (static_cast<std::uint64_t>(set) << 58) ^ (static_cast<std::uint64_t>(robot_piece) << 29) ^
         static_cast<std::uint64_t>(world_piece);
}

}  // namespace

std::vector<scene::Piece> enlargePieces(const std::vector<scene::Piece>& pieces, double delta) {
  // Two polytopes that contain the ball of radius delta: the icosahedron and
  // the cube of inradius delta (the 1e-9 margin absorbs the round-off of the
  // scale). The icosahedron adds less (circumradius 1.26 delta against 1.73),
  // the cube usually gives fewer vertices (a box aligned with the body frame
  // stays a box), which makes the queries cheaper: keep the hull with fewer
  // vertices.
  const double ico_scale = delta / icosahedronInradius() * (1.0 + 1e-9);
  const double cube_scale = delta * (1.0 + 1e-9);
  std::vector<scene::Piece> out;
  out.reserve(pieces.size());
  std::vector<Eigen::Vector3d> points;
  for (const scene::Piece& piece : pieces) {
    points.clear();
    for (const Eigen::Vector3d& v : piece.polytope.vertices()) {
      for (const Eigen::Vector3d& q : icosahedron()) points.push_back(v + ico_scale * q);
    }
    ConvexPolytope ico = ConvexPolytope::fromPoints(points);
    points.clear();
    for (const Eigen::Vector3d& v : piece.polytope.vertices()) {
      for (int c = 0; c < 8; ++c) {
        points.push_back(v + cube_scale *
                                 Eigen::Vector3d((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0));
      }
    }
    ConvexPolytope cube = ConvexPolytope::fromPoints(points);
    const bool use_cube = cube.numVertices() < ico.numVertices();
    out.push_back(scene::Piece::make(use_cube ? std::move(cube) : std::move(ico), scene::PieceKind::kConvex,
                                     piece.origin + " (enlarged by " + std::to_string(delta) + ")"));
  }
  return out;
}

MddScene::MddScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world,
                   const MddSceneOptions& options)
    : robot_(std::move(robot)), world_(std::move(world)) {
  if (!robot_) throw InvalidInputError("MddScene: the robot is null");
  if (!world_) throw InvalidInputError("MddScene: the world is null");
  const double r = robot_->radius();
  if (!std::isfinite(options.rotation_tolerance)) {
    throw InvalidInputError("MddScene: rotation_tolerance is not finite");
  }
  delta_ = options.rotation_tolerance > 0.0 ? options.rotation_tolerance : kDefaultRotationToleranceRel * r;
  if (delta_ < kMinRotationToleranceRel * r) {
    throw InvalidInputError("MddScene: rotation_tolerance " + std::to_string(delta_) +
                            " is below 1e-6 of the robot radius " + std::to_string(r));
  }
  if (options.refinement_levels < 0 || options.refinement_levels > kMaxRefinementLevels) {
    throw InvalidInputError("MddScene: refinement_levels " + std::to_string(options.refinement_levels) +
                            " is outside [0, 8]");
  }
  for (int level = 0; level <= options.refinement_levels; ++level) {
    enlarged_.push_back(enlargePieces(robot_->pieces(), delta_ / std::ldexp(1.0, level)));
  }
}

int MddScene::subEdgeCount(double angle) const {
  const double n = std::ceil(angle * robot_->radius() / (2.0 * delta_) * (1.0 + kSubEdgeSafety));
  return std::max(1, static_cast<int>(n));
}

const std::vector<scene::Piece>& MddScene::pieceSet(int set) const {
  return set == 0 ? robot_->pieces() : enlarged_.at(static_cast<std::size_t>(set - 1));
}

std::shared_ptr<MddScene::WarmTable> MddScene::warmTable() const {
  return warm_.local([] { return std::make_shared<WarmTable>(); });
}

WarmStart* MddScene::warmStart(int set, int robot_piece, int world_piece) const {
  // The table outlives this call: PerThread keeps it until this thread uses
  // kSlots other scenes; callers use the pointer within one query.
  return warmIn(*warmTable(), set, robot_piece, world_piece);
}

WarmStart* MddScene::warmIn(WarmTable& table, int set, int robot_piece, int world_piece) {
  if (table.map.size() > kMaxWarmPairs) table.map.clear();
  return &table.map[pairKey(set, robot_piece, world_piece)];
}

bool MddScene::collides(const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const {
  return collidesSet(0, X_WR, pair_queries, which);
}

bool MddScene::collidesSet(int set, const Eigen::Isometry3d& X_WR, int* pair_queries, PieceContact* which) const {
  const std::vector<scene::Piece>& pieces = pieceSet(set);
  const std::vector<scene::Piece>& world = world_->pieces();
  const std::shared_ptr<WarmTable> table = warmTable();  // held for the whole query
  thread_local std::vector<int> candidates;              // this function only: no reentrancy
  int queries = 0;
  bool hit = false;
  for (int i = 0; i < static_cast<int>(pieces.size()) && !hit; ++i) {
    const scene::Piece& piece = pieces[static_cast<std::size_t>(i)];
    candidates.clear();
    world_->candidates(scene::transformedBox(piece.box, X_WR), &candidates);
    const Eigen::Vector3d c_W = X_WR * piece.centre;
    for (int j : candidates) {
      const scene::Piece& obstacle = world[static_cast<std::size_t>(j)];
      if (spheresApart(c_W, piece.radius, obstacle.centre, obstacle.radius)) continue;
      IntersectInput in;
      in.a = &obstacle.polytope;
      in.b = &piece.polytope;
      in.X_WB = X_WR;
      ++queries;
      if (intersect(in, warmIn(*table, set, i, j)).intersecting) {
        if (which) {
          *which = PieceContact();
          which->robot_piece = i;
          which->world_piece = j;
        }
        hit = true;
        break;
      }
    }
  }
  if (pair_queries) *pair_queries += queries;
  return hit;
}

void MddScene::sweptCandidates(int set, int piece, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& v_W,
                               double max_distance, std::vector<int>* out) const {
  const scene::Piece& p = pieceSet(set)[static_cast<std::size_t>(piece)];
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
                               bool first_contact) const {
  SweepResult result;
  const double n = v_W.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw InvalidInputError("MddScene::sweep: the direction is zero or not finite");
  }
  if (!(max_distance >= 0.0)) throw InvalidInputError("MddScene::sweep: max_distance is negative or NaN");
  const Eigen::Vector3d u = v_W / n;
  const std::vector<scene::Piece>& pieces = pieceSet(set);
  const std::vector<scene::Piece>& world = world_->pieces();
  const std::shared_ptr<WarmTable> table = warmTable();
  double limit = max_distance;
  thread_local std::vector<int> candidates;  // this function only: no reentrancy
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    const scene::Piece& piece = pieces[static_cast<std::size_t>(i)];
    candidates.clear();
    sweptCandidates(set, i, X_WR, u, max_distance, &candidates);
    const Eigen::Vector3d c_W = X_WR * piece.centre;
    const Eigen::AlignedBox3d box_W = scene::transformedBox(piece.box, X_WR);
    for (int j : candidates) {
      const scene::Piece& obstacle = world[static_cast<std::size_t>(j)];
      if (sweptSphereApart(c_W, piece.radius, u, limit, obstacle.centre, obstacle.radius)) continue;
      if (sweptBoxApart(box_W, u, limit, obstacle.box)) continue;
      DirectionalInput in;
      in.a = &obstacle.polytope;
      in.b = &piece.polytope;
      in.X_WB = X_WR;
      in.s_W = u;
      in.max_distance = limit;
      in.exact_toi = first_contact;  // a yes/no sweep may stop at the first proof of a hit
      ++result.pair_queries;
      const ToiResult r = toi(in, warmIn(*table, set, i, j));
      if (r.status == ToiStatus::kNever || !(r.toi <= limit)) continue;
      result.contact = PieceContact();
      result.contact.robot_piece = i;
      result.contact.world_piece = j;
      if (r.status == ToiStatus::kInContact) {
        result.start_collides = true;
        result.distance = 0.0;
        return result;  // nothing comes before t = 0
      }
      result.distance = r.toi;
      result.contact.p_WC = r.contact.point_W;
      result.contact.n_W = r.contact.normal_W;
      if (!first_contact) return result;
      limit = r.toi;
    }
  }
  return result;
}

EdgeContact MddScene::checkEdge(const EdgeMotion& motion, bool first_contact) const {
  EdgeContact out;
  if (!motion.rotates()) {
    const Eigen::Isometry3d X = motion.pose(0.0);
    const Eigen::Vector3d v = motion.p_end - motion.p_start;
    const double length = v.norm();
    const SweepResult s = sweep(X, v, first_contact);
    out.pair_queries += s.pair_queries;
    if (s.start_collides || s.distance <= length) {
      out.collides = true;
      out.start_collides = s.start_collides;
      out.fraction = s.start_collides ? 0.0 : std::min(1.0, s.distance / length);
      out.contact = s.contact;
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
  const int n = subEdgeCount(motion.angle);
  // First contact: in order from the start. Validity only: in bisection order
  // (middle first, as OMPL's discrete validator), which meets a colliding
  // stretch sooner; a valid edge costs the same either way.
  thread_local std::vector<int> order;  // this function only: no reentrancy
  order.clear();
  if (first_contact) {
    for (int k = 0; k < n; ++k) order.push_back(k);
  } else {
    bisectionOrder(0, n - 1, &order);
  }
  for (int k : order) {
    const double ta = static_cast<double>(k) / n;
    const double tb = k + 1 == n ? 1.0 : static_cast<double>(k + 1) / n;
    const SubEdge sub = checkSubEdge(motion, ta, tb, 0, first_contact, &out);
    if (sub.free) continue;
    out.collides = true;
    out.fraction = sub.fraction;
    out.contact = sub.contact;
    if (sub.fraction == 0.0) out.start_collides = collidesSet(0, motion.pose(0.0), &out.pair_queries, nullptr);
    return out;
  }
  return out;
}

MddScene::SubEdge MddScene::checkSubEdge(const EdgeMotion& motion, double ta, double tb, int level, bool first_contact,
                                         EdgeContact* stats) const {
  const int set = level + 1;
  const bool finest = level == refinementLevels();
  const double tm = 0.5 * (ta + tb);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = motion.orientation(tm).toRotationMatrix();
  X.translation() = motion.position(ta);
  const Eigen::Vector3d v = motion.position(tb) - X.translation();
  const double length = v.norm();
  ++stats->sub_edges;
  SubEdge fail;
  fail.free = false;
  if (length == 0.0) {
    if (!collidesSet(set, X, &stats->pair_queries, &fail.contact)) return SubEdge();
    fail.fraction = ta;
  } else {
    // Coarse levels only decide whether to refine: any contact will do.
    const SweepResult s = sweepSet(set, X, v, length, first_contact && finest);
    stats->pair_queries += s.pair_queries;
    if (!s.start_collides && !(s.distance <= length)) return SubEdge();
    fail.fraction = s.start_collides ? ta : ta + (tb - ta) * std::min(1.0, s.distance / length);
    fail.contact = s.contact;
  }
  if (finest) return fail;
  if (!first_contact) {
    // Validity only: a true state of this sub-edge that collides settles it
    // without refining (the enlarged robot usually fails for a real contact).
    for (double t : {tm, tb}) {
      if (collidesSet(0, motion.pose(t), &stats->pair_queries, &fail.contact)) {
        fail.fraction = ta;  // not a first contact: only `collides` is meaningful in this mode
        return fail;
      }
    }
  }
  const SubEdge first = checkSubEdge(motion, ta, tm, level + 1, first_contact, stats);
  if (!first.free) return first;
  return checkSubEdge(motion, tm, tb, level + 1, first_contact, stats);
}

}  // namespace mddual::planning
