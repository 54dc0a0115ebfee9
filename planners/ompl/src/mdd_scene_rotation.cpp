// MddScene::checkRotating: rotating edges by a branch and bound over
// (robot node, world node, time interval) triples of the two hierarchies. The
// soundness argument and the first-contact bound are in mdd_scene.h.
#include <algorithm>
#include <cmath>
#include <vector>

#include "constants.h"
#include "mddual/planning/mdd_scene.h"

namespace mddual::planning {
namespace {

using detail::kInf;
/// e(N, I) is computed times (1 + kGrowthSafety), plus kSlerpRoundoffRel
/// times N's largest distance from the body origin: OMPL's slerp between
/// states whose quaternion norms are within 1e-9 of 1 differs from
/// EdgeMotion's rotation by about that much (docs/design/rotating-edges.md).
constexpr double kGrowthSafety = 1e-6;
constexpr double kSlerpRoundoffRel = 1e-8;
/// Which part of a triple to split: its interval is halved when e exceeds
/// kTimeSplitAlways times the larger radius of its nodes that have children,
/// never when e is below kTimeSplitNever times it, and in between when the
/// nodes' volumes without the growth e clear the triple; otherwise the larger
/// node is split. On the trap's and the mesh scene's rotating edges
/// (mddual_bench_planning), splitting by the largest of e and the radii
/// alone needs 3x the triples and core queries of these values
/// (docs/results/tuning.md, with the other values tried).
constexpr double kTimeSplitAlways = 0.1;
constexpr double kTimeSplitNever = 0.01;
/// When neither node's radius exceeds the other's by more than this factor,
/// both are split at once (four child triples), not only the larger; with no
/// limit (both whenever both have children) the apartment is much slower. On
/// bugtrap's rotating edges (mddual_bench_planning --cpu) this takes 15% to
/// 25% less time than splitting the larger node only
/// (docs/results/tuning.md, with the other factors tried).
constexpr double kBothSplitRatio = 2.0;

/// A time interval [ta, tb] of the edge and the pose the triples on it use.
struct Interval {
  double ta = 0.0, tb = 1.0;
  Eigen::Isometry3d X_WI;   ///< orientation R(tm) (tm the middle), position p(ta)
  Eigen::Vector3d v_W;      ///< p(tb) - p(ta)
  double half_angle = 0.0;  ///< (tb - ta) / 2 * angle
  double sin_half = 0.0;    ///< sin(half_angle)
  Eigen::Vector3d u_W;      ///< unit direction of v_W (zero when v_W is zero)
  double length = 0.0;      ///< |v_W|
};

/// Whether a triple's volumes without the motion growth e would clear it
/// (the split heuristic's question), as bound() found it.
enum class Ungrown : signed char {
  kUnknown,  ///< not asked (a sweep of length 0: bound() tests the boxes at rest)
  kApart,    ///< N's box without e misses M's box on the 6 face axes (a triangle leaf: the triangle on its 13) over the
             ///< sweep
  kMeets,    ///< it does not: the nodes, not the growth, keep the triple
};

struct Triple {
  double bound;  ///< lower bound of the first contact fraction of any pair in it
  double until;  ///< no contact in it after this fraction (its volumes' overlap ends)
  int robot;     ///< robot node
  int world;     ///< world node, with its tree: 2 * node + tree (0: static, 1: overflow)
  int interval;
  Ungrown ungrown;  ///< the split heuristic's test, from bound()
};

struct Scratch {
  std::vector<Interval> intervals;
  std::vector<Triple> heap;
};

bool later(const Triple& a, const Triple& b) {
  return a.bound > b.bound;
}

/// Whether halving [ta, tb] gives two shorter intervals (false once the
/// interval is a few ulps long: its middle rounds to an end).
bool halvable(double ta, double tb) {
  const double tm = 0.5 * (ta + tb);
  return ta < tm && tm < tb;
}

/// v / length, or zero when length (|v|) is zero.
Eigen::Vector3d unitOrZero(const Eigen::Vector3d& v, double length) {
  return length > 0.0 ? Eigen::Vector3d(v / length) : Eigen::Vector3d::Zero();
}

/// partSweep with sin(half_angle) given (computed once per interval).
PartSweep partSweepWithSin(const Eigen::Vector3d& centre_R, double radius, double rho, const Eigen::Vector3d& axis_R,
                           double h, double sin_h, const Eigen::Isometry3d& X_WI, const Eigen::Vector3d& v_W) {
  // With c = centre_R, x = c + y (|y| <= radius) and k = axis x c (|k| =
  // dist(c, axis)), a point's displacement from its place at R(tm) is
  //   Rot(axis, a) x - x = sin(a) k - (1 - cos a) c_perp + (Rot(axis, a) y - y)
  // for |a| <= h, all of it perpendicular to the axis.
  // 1. Arc: its length is at most h dist(x, axis) <= h rho_arc: a disk of
  //    that radius, at the middle pose, swept along v.
  // 2. Chord: a = (2s - 1) h at s in [0, 1] (constant angular speed), and
  //    sin(a) = (2s - 1) sin(h) + r(a) with |r(a)| <= h - sin h <= h^3 / 6,
  //    1 - cos a <= h^2 / 2, |Rot(axis, a) y - y| <= h |y|: the centre's
  //    chord, from -sin(h) k to +sin(h) k, becomes part of the sweep and
  //    the disk's radius is h radius + (h^2 / 2 + h^3 / 6) |k|, of order h
  //    times the part's own size instead of its distance from the axis.
  const Eigen::Vector3d k_R = axis_R.cross(centre_R);
  const double to_axis = k_R.norm();
  const double any = kSlerpRoundoffRel * rho;
  const double arc = h * std::min(rho, to_axis + radius) * (1.0 + kGrowthSafety);
  const double chord = (h * radius + (0.5 * h * h + h * h * h / 6.0) * to_axis) * (1.0 + kGrowthSafety);
  PartSweep out;
  out.X_WR_start = X_WI;
  out.v_W = v_W;
  out.any = any;
  if (!(chord < arc)) {
    out.across = arc;
    return out;
  }
  const Eigen::Vector3d k_W = X_WI.linear() * k_R;
  out.X_WR_start.translation() -= sin_h * k_W;
  out.v_W += (2.0 * sin_h) * k_W;
  out.across = chord;
  return out;
}

}  // namespace

Obb rotationSweptBox(const Obb& box_R, const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& axis_R, double across,
                     double any) {
  // A point x moves by Rot(axis, a) x - x, perpendicular to the axis, of
  // length at most `across`: inside a disk of that radius perpendicular to
  // the axis, whose support along the box's axis b_k is across sqrt(1 -
  // (axis . b_k)^2) (none along b_k = axis). With the axis's coordinates
  // a_i in the box's orthonormal axes, 1 - a_k^2 is the sum of the other two
  // squares: no cancellation (sqrt(1 - a_k^2) gave 1e-8 for a_k = 1).
  Obb box = box_R.transformed(X_WR, any);
  const Eigen::Vector3d a = box_R.axes_F.transpose() * axis_R;
  for (int k = 0; k < 3; ++k) {
    const double i = a[(k + 1) % 3], j = a[(k + 2) % 3];
    box.half[k] += across * std::sqrt(i * i + j * j);
  }
  return box;
}

PartSweep partSweep(const Eigen::Vector3d& centre_R, double radius, double rho, const Eigen::Vector3d& axis_R,
                    double half_angle, const Eigen::Isometry3d& X_WI, const Eigen::Vector3d& v_W) {
  return partSweepWithSin(centre_R, radius, rho, axis_R, half_angle, std::sin(half_angle), X_WI, v_W);
}

void MddScene::checkRotating(const EdgeMotion& motion, EdgeQuery query, double fraction_tolerance,
                             EdgeContact* out) const {
  const bool first_contact = query != EdgeQuery::kValidity;
  // kLastValid: a leaf contact at any enlargement level is a lower bound of
  // its pair's first contact (the enlarged sweep holds the true motion), so
  // one at level last_valid_level_ or finer may end the search like a
  // finest-level one (the edge is known to collide: the verdict does not
  // rest on it); a coarser one is refined, as for kFirstContact.
  const bool last_valid = query == EdgeQuery::kLastValid;
  if (world_tree_.empty() && overflow_tree_.empty()) return;
  const std::vector<scene::Piece>& world = world_->pieces();
  // World nodes of both trees, encoded as in Triple::world.
  const auto worldNode = [this](int wn) -> const Bvh::Node& { return worldTreeAt(wn & 1).node(wn >> 1); };
  const auto worldChild = [](int wn, int child) { return 2 * child + (wn & 1); };
  // The world index of a world leaf, -1 for a removed or moved piece's old leaf.
  const auto worldLeaf = [this](int wn) { return worldIndex(wn & 1, worldTreeAt(wn & 1).leafPiece(wn >> 1)); };
  const std::shared_ptr<WarmTable> table = warmTable();  // held for the whole query
  thread_local Scratch scratch;                          // this function only: no reentrancy
  std::vector<Interval>& intervals = scratch.intervals;
  std::vector<Triple>& heap = scratch.heap;
  intervals.clear();
  heap.clear();
  const Eigen::Vector3d axis_R = motion.axis_R.normalized();
  const int finest = refinementLevels();

  const auto makeInterval = [&](double ta, double tb) {
    Interval I;
    I.ta = ta;
    I.tb = tb;
    I.X_WI = Eigen::Isometry3d::Identity();
    I.X_WI.linear() = motion.orientation(0.5 * (ta + tb)).toRotationMatrix();
    I.X_WI.translation() = motion.position(ta);
    I.v_W = motion.position(tb) - I.X_WI.translation();
    I.half_angle = 0.5 * (tb - ta) * motion.angle;
    I.sin_half = std::sin(I.half_angle);
    I.length = I.v_W.norm();
    I.u_W = unitOrZero(I.v_W, I.length);
    intervals.push_back(I);
    return static_cast<int>(intervals.size()) - 1;
  };
  // How node N moves over I: a sweep along a segment and a growth e(N, I)
  // (the arc or the chord of docs/design/rotating-edges.md, whichever grows less).
  const auto sweepOf = [&](const Bvh::Node& n, const Interval& I) {
    return partSweepWithSin(n.centre, n.radius, n.max_norm, axis_R, I.half_angle, I.sin_half, I.X_WI, I.v_W);
  };
  // The robot node of the last triple bounded, posed over its interval: the
  // triples of one split share it (a world node's two children, the four
  // child pairs of a split of both), so it is computed once for them.
  struct PosedRobot {
    int rn = -1, iv = -1;
    PartSweep sweep;       ///< how N moves over the interval (arc or chord)
    Eigen::Vector3d u_W;   ///< unit direction of sweep.v_W (zero when it is zero)
    double length = 0.0;   ///< |sweep.v_W|
    Eigen::Vector3d c_W;   ///< N's sphere centre at the start of the sweep
    bool has_box = false;  ///< box_W is computed after the sphere test passes
    Obb box_W;
  } posed;
  // Lower bound of the first contact in the triple, +inf when it is cleared;
  // *until as in Triple, and *ungrown (when the triple is kept) the split
  // heuristic's test on the same sweep, asked in the same pass over the
  // face axes (obbCastIntervalInner: N's box without the growth has the
  // grown box's centre and axes).
  const auto bound = [&](int rn, int wn, int iv, double* until, Ungrown* ungrown) {
    ++out->sub_edges;
    const Interval& I = intervals[static_cast<std::size_t>(iv)];
    const Bvh::Node& N = robot_tree_.node(rn);
    const Bvh::Node& M = worldNode(wn);
    *until = I.tb;
    *ungrown = Ungrown::kUnknown;
    if (posed.rn != rn || posed.iv != iv) {
      posed.rn = rn;
      posed.iv = iv;
      posed.sweep = sweepOf(N, I);
      posed.length = posed.sweep.v_W.norm();
      posed.u_W = unitOrZero(posed.sweep.v_W, posed.length);
      posed.c_W = posed.sweep.X_WR_start * N.centre;
      posed.has_box = false;
    }
    const double e = posed.sweep.total();
    const double r = N.radius + e;
    const double length = posed.length;
    const Eigen::Vector3d& u_W = posed.u_W;
    const double slack =
        kBvhSlackRel * (M.scale + posed.sweep.X_WR_start.translation().cwiseAbs().maxCoeff() + N.scale + e + length);
    // Whether a sphere of radius rs centred at c_W, swept by s u_W for s in
    // [0, len] (v_W = len u_W), misses M's sphere, then M's box (a node of
    // large flat triangles has a thin box in a wide sphere). The box test
    // comes before N's box is posed: on bugtrap's recorded RRT-Connect
    // checks (mddual_bench_replay --load, callgrind) it takes 6.1% off
    // checkEdge's instructions (docs/results/tuning.md).
    const auto sphereMisses = [&](const Eigen::Vector3d& c_W, double rs, const Eigen::Vector3d& dir_W, double len,
                                  const Eigen::Vector3d& v_W) {
      const double s = len > 0.0 ? std::clamp((M.centre - c_W).dot(dir_W), 0.0, len) : 0.0;
      const double reach = rs + M.radius + slack;
      return (c_W + s * dir_W - M.centre).squaredNorm() > reach * reach ||
             sweptSphereObbApart(M.obb, c_W, rs, v_W, slack);
    };
    // N's points lie within N.max_norm of the body origin at every
    // orientation (times 1 + kSlerpRoundoffRel: OMPL's slerp of quaternions
    // a little off unit norm): over I, within that distance of the segment
    // p(ta) -> p(tb), with no growth from the rotation. Asked only when its
    // radius is below N's grown radius r (max_norm(N) < N.radius + e: a
    // long turn's coarse triples). On the rotating edges of
    // mddual_bench_planning (--cpu) it takes 5% to 20% off the validity
    // checks of twistycool, bugtrap, cubicles_mesh and the mesh scene
    // (docs/results/tuning.md).
    const double r0 = N.max_norm * (1.0 + kSlerpRoundoffRel);
    if (r0 < r && sphereMisses(I.X_WI.translation(), r0, I.u_W, I.length, I.v_W)) return kInf;
    if (sphereMisses(posed.c_W, r, u_W, length, posed.sweep.v_W)) return kInf;
    if (!posed.has_box) {
      posed.box_W = rotationSweptBox(N.obb, posed.sweep.X_WR_start, axis_R, posed.sweep.across, posed.sweep.any);
      posed.has_box = true;
    }
    const Obb& box_W = posed.box_W;
    if (sweptAabbApart(M.box, box_W.centre_F, box_W.aabbHalf(), u_W, length, slack)) return kInf;
    // A world leaf that is a triangle: the triangle itself on its 13 axes in
    // place of its box (which a large triangle fills only half of), the
    // inner box's verdict on the same axes. On the mesh configs' rotating
    // checkMotion (mddual_bench_planning --mdd-only, callgrind) it takes
    // 2.5% to 9.8% fewer instructions (docs/results/tuning.md). Asked only
    // for triangles larger than N's grown sphere (the translating cast's
    // rule), it was no better anywhere.
    const std::array<Eigen::Vector3d, 3>* tri = M.triangle >= 0 ? &worldTreeAt(wn & 1).triangle(M.triangle) : nullptr;
    if (length == 0.0) {
      const bool apart = tri ? triangleObbApart(*tri, box_W, slack) : obbsDisjoint(M.obb, box_W, slack);
      return apart ? kInf : I.ta;
    }
    double lo = 0.0, hi = 0.0;
    bool apart = false;
    const bool meets = tri ? triangleObbCastInterval(*tri, box_W, u_W, length, slack, &lo, &hi, &N.obb.half, &apart)
                           : obbCastIntervalInner(M.obb, box_W, N.obb.half, u_W, length, slack, &lo, &hi, &apart);
    if (!meets) return kInf;
    *ungrown = apart ? Ungrown::kApart : Ungrown::kMeets;
    *until = I.ta + (I.tb - I.ta) * (hi / length);
    return I.ta + (I.tb - I.ta) * (lo / length);
  };
  double best = kInf;  // smallest finest-level contact fraction found (kLastValid: LeafResult::bounds)
  PieceContact best_contact;
  const auto push = [&](int rn, int wn, int iv) {
    if (worldNode(wn).isLeaf() && worldLeaf(wn) < 0) return;  // the piece is not in the world
    double until = 0.0;
    Ungrown ungrown = Ungrown::kUnknown;
    const double b = bound(rn, wn, iv, &until, &ungrown);
    if (b < best) {
      heap.push_back(Triple{b, until, rn, wn, iv, ungrown});
      if (first_contact) std::push_heap(heap.begin(), heap.end(), later);
    }
  };
  const auto splitTime = [&](const Triple& t, const Interval& I) {
    const double tm = 0.5 * (I.ta + I.tb);
    // A half outside [t.bound, t.until] holds no contact: the triple's
    // volumes, which hold its pieces over all of I, meet only then. Dropping
    // it saves 2.4% of bugtrap's checkEdge instructions (callgrind,
    // mddual_bench_planning --mdd-only; docs/results/tuning.md).
    if (t.bound <= tm) push(t.robot, t.world, makeInterval(I.ta, tm));
    if (t.until >= tm) push(t.robot, t.world, makeInterval(tm, I.tb));
  };
  // The core on a pair of pieces over an interval with e <= delta: robot
  // piece i enlarged at the finest level whose enlargement still covers e,
  // swept along its leaf's sweep (ps) against world piece j.
  struct LeafResult {
    bool hit = false;
    bool finest = false;
    bool bounds = false;    ///< a contact that may end a kLastValid search (its level is fine enough)
    double fraction = 0.0;  ///< lower bound of the pair's first contact on I (when hit)
    PieceContact contact;
  };
  const auto leafQuery = [&](int i, int j, const Interval& I, const PartSweep& ps) {
    const double e = ps.total();
    const double length = ps.v_W.norm();
    int level = 0;
    while (level < finest && delta_ / std::ldexp(1.0, level + 1) >= e) ++level;
    LeafResult out_leaf;
    // A finer level is out of reach when its enlargement is not above twice
    // the growth's round-off part (ps.any), which halving the interval does
    // not shrink (only `across` halves): a hit here is then as final as one
    // at the finest level, a conservative verdict. (Without this, a
    // rotation_tolerance near its minimum, 1e-6 of the robot radius, with 8
    // levels, whose finest enlargement is below 1e-8 of it, halved the
    // intervals of a pair closer than that without end: pinned in
    // test_mdd_scene_rotation.cpp.)
    out_leaf.finest = level == finest || delta_ / std::ldexp(1.0, level + 1) <= 2.0 * ps.any;
    out_leaf.bounds = out_leaf.finest || (last_valid && level >= last_valid_level_);
    out_leaf.fraction = I.ta;
    out_leaf.contact.robot_piece = i;
    out_leaf.contact.world_piece = j;
    const ConvexPolytope& enlarged = enlargedPiece(level, i).polytope;
    const ConvexPolytope& obstacle = world[static_cast<std::size_t>(j)].polytope;
    WarmStart* warm = warmIn(*table, level + 1, i, world_->idOf(j));
    ++out->pair_queries;
    if (length > 0.0) {
      DirectionalInput in;
      in.a = &obstacle;
      in.b = &enlarged;
      in.X_WB = ps.X_WR_start;
      in.s_W = ps.v_W / length;
      in.max_distance = length;
      // Otherwise only whether to refine is asked; an interval that no
      // longer halves cannot be refined, so its hit may become the bound.
      in.exact_toi = first_contact && (out_leaf.bounds || !halvable(I.ta, I.tb));
      const ToiResult r = toi(in, warm);
      if (r.status == ToiStatus::kNever || !(r.toi <= length)) return out_leaf;
      // An early (inexact) hit's toi is an upper bound of the contact, not a
      // lower one: a first-contact search keeps I.ta for it.
      if (r.status == ToiStatus::kHit && (r.toi_exact || !first_contact)) {
        out_leaf.fraction = I.ta + (I.tb - I.ta) * std::min(1.0, r.toi / length);
        out_leaf.contact.p_WC = r.contact.point_W;
        out_leaf.contact.n_W = r.contact.normal_W;
      }
    } else {
      IntersectInput in;
      in.a = &obstacle;
      in.b = &enlarged;
      in.X_WB = ps.X_WR_start;
      if (!intersect(in, warm).intersecting) return out_leaf;
    }
    out_leaf.hit = true;
    return out_leaf;
  };
  // Validity only: whether the true pieces i and j intersect at time t.
  const auto trueContact = [&](int i, int j, double t) {
    IntersectInput in;
    in.a = &world[static_cast<std::size_t>(j)].polytope;
    in.b = &robot_->pieces()[static_cast<std::size_t>(i)].polytope;
    in.X_WB = motion.pose(t);
    ++out->pair_queries;
    return intersect(in, warmIn(*table, 0, i, world_->idOf(j))).intersecting;
  };
  // Validity only: a pair refuted at a coarse level is refined depth first
  // (halving its interval) until it is free, a finest-level query refutes it,
  // or the true pieces intersect at a refuted interval's contact time.
  // Returns true when the edge collides.
  thread_local std::vector<int> stack;  // intervals still to check for this pair
  const auto refineDepthFirst = [&](int rn, int wn, int iv) {
    const int i = robot_tree_.leafPiece(rn);
    const int j = worldLeaf(wn);
    stack.clear();
    stack.push_back(iv);
    while (!stack.empty()) {
      const Interval I = intervals[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (!halvable(I.ta, I.tb)) {
        // Refuted at a coarse level on an interval that no longer halves
        // (not seen: leafQuery calls a level final before that): the edge is
        // declared colliding, conservatively.
        best = I.ta;
        best_contact = PieceContact();
        best_contact.robot_piece = i;
        best_contact.world_piece = j;
        return true;
      }
      const double tm = 0.5 * (I.ta + I.tb);
      for (const int half : {makeInterval(tm, I.tb), makeInterval(I.ta, tm)}) {
        const Interval& H = intervals[static_cast<std::size_t>(half)];
        double until = 0.0;
        Ungrown ungrown = Ungrown::kUnknown;
        if (!(bound(rn, wn, half, &until, &ungrown) < kInf)) continue;
        const LeafResult r = leafQuery(i, j, H, posed.sweep);  // bound() just posed (rn, half)
        if (!r.hit) continue;
        if (r.finest || trueContact(i, j, r.fraction)) {
          best = r.fraction;  // not a first contact: only `collides` is meaningful in this mode
          best_contact = r.contact;
          return true;
        }
        stack.push_back(half);
      }
    }
    return false;
  };

  const int whole = makeInterval(0.0, 1.0);
  for (int tree = 0; tree < 2; ++tree) {
    if (!worldTreeAt(tree).empty()) push(robot_tree_.root(), 2 * worldTreeAt(tree).root() + tree, whole);
  }
  // First contact: a queue by bound (see the header). Validity only: any
  // order is sound; a stack (depth first) is cheaper and reaches leaves soon.
  while (!heap.empty()) {
    if (last_valid && heap.front().bound >= best - fraction_tolerance) {
      // Every contact left in the queue is no earlier than the queue's
      // smallest bound, within the tolerance of the best one found.
      if (heap.front().bound < best) {
        best = heap.front().bound;
        best_contact = PieceContact();  // a bound, not a contact found
      }
      break;
    }
    if (first_contact) std::pop_heap(heap.begin(), heap.end(), later);
    const Triple t = heap.back();
    heap.pop_back();
    if (t.bound >= best) break;  // every triple left starts no earlier
    const Bvh::Node& N = robot_tree_.node(t.robot);
    const Bvh::Node& M = worldNode(t.world);
    const Interval I = intervals[static_cast<std::size_t>(t.interval)];  // a copy: intervals may grow
    // The sweep bound() computed when the triple was pushed, if still posed.
    const PartSweep ps = posed.rn == t.robot && posed.iv == t.interval ? posed.sweep : sweepOf(N, I);
    const double e = ps.total();
    const bool can_halve = halvable(I.ta, I.tb);
    if (!N.isLeaf() || !M.isLeaf()) {
      // Split the interval when its growth is not small against the nodes
      // that have children; otherwise the larger of them. The growth
      // compared is the part that halving the interval shrinks (ps.across,
      // not e: e's round-off part ps.any stays, and nodes under ten times
      // it, 1e-7 of their distance from the body origin, had their interval
      // halved without end; pinned in test_mdd_scene_rotation.cpp).
      const double rn = N.isLeaf() ? -1.0 : N.radius;
      const double rm = M.isLeaf() ? -1.0 : M.radius;
      // Split the interval when e is large against both nodes; keep it
      // when e is small; in between, when the volumes without growth would
      // clear the triple (the growth is to blame). That test is a heuristic
      // (any split is sound): the 6 face axes, not all 15 (fewer
      // instructions per check), asked by bound() in its own cast
      // (Triple::ungrown). Asked here in a second cast, it was 14% of
      // checkRotating's instructions on bugtrap's RRT-Connect checks
      // (callgrind, mddual_bench_replay; docs/results/tuning.md).
      const double r = std::max(rn, rm);
      const double growth = ps.across;
      // Not below the round-off part: halving would barely shrink e.
      const bool halving_helps = can_halve && growth > ps.any;
      const bool in_band = halving_helps && growth > kTimeSplitNever * r;
      bool split_time = halving_helps && growth > kTimeSplitAlways * r;
      if (!split_time && in_band && t.ungrown != Ungrown::kUnknown) {
        split_time = t.ungrown == Ungrown::kApart;
      } else if (!split_time && in_band) {
        const Obb box_W = N.obb.transformed(ps.X_WR_start, 0.0);
        const double length = ps.v_W.norm();
        const Eigen::Vector3d u_W = unitOrZero(ps.v_W, length);
        double lo = 0.0, hi = 0.0;
        split_time = !obbCastIntervalFaces(M.obb, box_W, u_W, length, 0.0, &lo, &hi);
      }
      if (split_time) {
        splitTime(t, I);
      } else if (rn > 0.0 && rm > 0.0 && rn <= kBothSplitRatio * rm && rm <= kBothSplitRatio * rn) {
        // Both nodes of similar size: their four child pairs at once (the
        // two intermediate pairs would rarely be cleared).
        for (const int nc : {N.left, N.right}) {
          push(nc, worldChild(t.world, M.left), t.interval);
          push(nc, worldChild(t.world, M.right), t.interval);
        }
      } else if (rn >= rm) {
        push(N.left, t.world, t.interval);
        push(N.right, t.world, t.interval);
      } else {
        push(t.robot, worldChild(t.world, M.left), t.interval);
        push(t.robot, worldChild(t.world, M.right), t.interval);
      }
      continue;
    }
    if (e > delta_ && can_halve) {
      splitTime(t, I);
      continue;
    }
    const int i = robot_tree_.leafPiece(t.robot);
    const int j = worldLeaf(t.world);
    if (j < 0) continue;  // the piece is not in the world
    // On an interval that no longer halves (not seen: the growth halves with
    // it down to its round-off part, below 1e-6 of delta), no enlarged piece
    // may hold the motion (e > delta) and no finer level is reachable: a
    // contact is assumed at its start, or any hit taken as final; both
    // conservative.
    LeafResult r;
    if (e > delta_) {
      r.hit = r.finest = r.bounds = true;
      r.fraction = I.ta;
      r.contact.robot_piece = i;
      r.contact.world_piece = j;
    } else {
      r = leafQuery(i, j, I, ps);
    }
    if (!r.hit) continue;
    if (r.bounds || !can_halve) {
      out->collides = true;
      if (r.fraction < best) {
        best = r.fraction;
        best_contact = r.contact;
      }
      if (!first_contact) break;
      continue;
    }
    if (first_contact) {
      splitTime(t, I);  // the halves wait in the queue by their bounds
      continue;
    }
    if (trueContact(i, j, r.fraction) || refineDepthFirst(t.robot, t.world, t.interval)) {
      out->collides = true;
      best_contact = r.contact;
      if (!(best < kInf)) best = r.fraction;
      break;
    }
  }
  if (out->collides) {
    out->fraction = best;
    out->contact = best_contact;
  }
}

}  // namespace mddual::planning
