// MddScene::checkRotating: rotating edges by a branch and bound over
// (robot node, world node, time interval) triples of the two hierarchies. The
// soundness argument and the first-contact bound are in mdd_scene.h.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mddual/planning/mdd_scene.h"

namespace mddual::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// e(N, I) is computed times (1 + kGrowthSafety), plus kSlerpRoundoffRel *
/// rho(N): OMPL's slerp between states whose quaternion norms are within 1e-9
/// of 1 differs from EdgeMotion's rotation by about that much (see the header).
constexpr double kGrowthSafety = 1e-6;
constexpr double kSlerpRoundoffRel = 1e-8;
/// Sphere rejects need a gap above this fraction of the coordinates'
/// magnitude (round-off; the same slack as the hierarchy's own tests).
constexpr double kSphereSlackRel = 1e-9;

/// A time interval [ta, tb] of the edge and the pose the triples on it use.
struct Interval {
  double ta = 0.0, tb = 1.0;
  Eigen::Isometry3d X_WM;   ///< orientation R(tm) (tm the middle), position p(ta)
  Eigen::Vector3d u_W;      ///< unit direction of v = p(tb) - p(ta) (zero when v = 0)
  double length = 0.0;      ///< |v|
  double half_angle = 0.0;  ///< (tb - ta) / 2 * angle
};

struct Triple {
  double bound;  ///< lower bound of the first contact fraction of any pair in it
  int robot, world, interval;
};

struct Scratch {
  std::vector<Interval> intervals;
  std::vector<Triple> heap;
};

bool later(const Triple& a, const Triple& b) {
  return a.bound > b.bound;
}

}  // namespace

void MddScene::checkRotating(const EdgeMotion& motion, bool first_contact, EdgeContact* out) const {
  if (world_tree_.empty()) return;
  const std::vector<scene::Piece>& world = world_->pieces();
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
    I.X_WM = Eigen::Isometry3d::Identity();
    I.X_WM.linear() = motion.orientation(0.5 * (ta + tb)).toRotationMatrix();
    I.X_WM.translation() = motion.position(ta);
    const Eigen::Vector3d v = motion.position(tb) - I.X_WM.translation();
    I.length = v.norm();
    I.u_W = I.length > 0.0 ? Eigen::Vector3d(v / I.length) : Eigen::Vector3d::Zero();
    I.half_angle = 0.5 * (tb - ta) * motion.angle;
    intervals.push_back(I);
    return static_cast<int>(intervals.size()) - 1;
  };
  // e(N, I): how far a point of N moves from its place at the middle
  // orientation within I (rotation part only).
  const auto growth = [&](const Bvh::Node& n, const Interval& I) {
    const double to_axis = (n.centre - n.centre.dot(axis_R) * axis_R).norm();
    const double rho = std::min(n.max_norm, to_axis + n.radius);
    return I.half_angle * rho * (1.0 + kGrowthSafety) + kSlerpRoundoffRel * rho;
  };
  // Lower bound of the first contact in the triple, +inf when it is cleared.
  const auto bound = [&](int rn, int wn, const Interval& I) {
    ++out->sub_edges;
    const Bvh::Node& N = robot_tree_.node(rn);
    const Bvh::Node& M = world_tree_.node(wn);
    const double e = growth(N, I);
    const Eigen::Vector3d c_W = I.X_WM * N.centre;
    const double r = N.radius + e;
    const double s = I.length > 0.0 ? std::clamp((M.centre - c_W).dot(I.u_W), 0.0, I.length) : 0.0;
    const double slack =
        kSphereSlackRel * (c_W.cwiseAbs().maxCoeff() + M.centre.cwiseAbs().maxCoeff() + I.length + r + M.radius);
    if ((c_W + s * I.u_W - M.centre).norm() > r + M.radius + slack) return kInf;
    const Obb box_W = N.obb.transformed(I.X_WM, e);
    if (I.length == 0.0) return obbsDisjoint(M.obb, box_W) ? kInf : I.ta;
    double lo = 0.0, hi = 0.0;
    if (!obbCastInterval(M.obb, box_W, I.u_W, I.length, &lo, &hi)) return kInf;
    return I.ta + (I.tb - I.ta) * (lo / I.length);
  };
  double best = kInf;  // smallest finest-level contact fraction found
  PieceContact best_contact;
  const auto push = [&](int rn, int wn, int iv) {
    const double b = bound(rn, wn, intervals[static_cast<std::size_t>(iv)]);
    if (b < best) {
      heap.push_back(Triple{b, rn, wn, iv});
      std::push_heap(heap.begin(), heap.end(), later);
    }
  };
  const auto splitTime = [&](const Triple& t, const Interval& I) {
    const double tm = 0.5 * (I.ta + I.tb);
    const int first = makeInterval(I.ta, tm);
    const int second = makeInterval(tm, I.tb);
    push(t.robot, t.world, first);
    push(t.robot, t.world, second);
  };

  push(robot_tree_.root(), world_tree_.root(), makeInterval(0.0, 1.0));
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Triple t = heap.back();
    heap.pop_back();
    if (t.bound >= best) break;  // every triple left starts no earlier
    const Bvh::Node& N = robot_tree_.node(t.robot);
    const Bvh::Node& M = world_tree_.node(t.world);
    const Interval I = intervals[static_cast<std::size_t>(t.interval)];  // a copy: intervals may grow
    const double e = growth(N, I);
    if (!N.isLeaf() || !M.isLeaf()) {
      // Split the largest of the interval (by e) and the nodes that have children.
      const double rn = N.isLeaf() ? -1.0 : N.radius;
      const double rm = M.isLeaf() ? -1.0 : M.radius;
      if (e > rn && e > rm) {
        splitTime(t, I);
      } else if (rn >= rm) {
        push(N.left, t.world, t.interval);
        push(N.right, t.world, t.interval);
      } else {
        push(t.robot, M.left, t.interval);
        push(t.robot, M.right, t.interval);
      }
      continue;
    }
    if (e > delta_) {
      splitTime(t, I);
      continue;
    }
    // A pair of pieces on a short enough interval: the core on the piece
    // enlarged at the finest level whose enlargement still covers e.
    int level = 0;
    while (level < finest && delta_ / std::ldexp(1.0, level + 1) >= e) ++level;
    const int i = robot_tree_.leafPiece(t.robot);
    const int j = world_tree_.leafPiece(t.world);
    const ConvexPolytope& enlarged = enlarged_[static_cast<std::size_t>(level)][static_cast<std::size_t>(i)].polytope;
    const ConvexPolytope& obstacle = world[static_cast<std::size_t>(j)].polytope;
    WarmStart* warm = warmIn(*table, level + 1, i, j);
    const bool at_finest = level == finest;
    double fraction = I.ta;
    PieceContact contact;
    contact.robot_piece = i;
    contact.world_piece = j;
    ++out->pair_queries;
    if (I.length > 0.0) {
      DirectionalInput in;
      in.a = &obstacle;
      in.b = &enlarged;
      in.X_WB = I.X_WM;
      in.s_W = I.u_W;
      in.max_distance = I.length;
      in.exact_toi = first_contact && at_finest;  // coarse levels only decide whether to refine
      const ToiResult r = toi(in, warm);
      if (r.status == ToiStatus::kNever || !(r.toi <= I.length)) continue;
      if (r.status == ToiStatus::kHit) {
        fraction = I.ta + (I.tb - I.ta) * std::min(1.0, r.toi / I.length);
        contact.p_WC = r.contact.point_W;
        contact.n_W = r.contact.normal_W;
      }
    } else {
      IntersectInput in;
      in.a = &obstacle;
      in.b = &enlarged;
      in.X_WB = I.X_WM;
      if (!intersect(in, warm).intersecting) continue;
    }
    if (at_finest) {
      out->collides = true;
      if (fraction < best) {
        best = fraction;
        best_contact = contact;
      }
      if (!first_contact) break;
      continue;
    }
    if (!first_contact) {
      // Validity only: the true pieces at the middle of the interval settle
      // the edge without refining when they intersect.
      IntersectInput in;
      in.a = &obstacle;
      in.b = &robot_->pieces()[static_cast<std::size_t>(i)].polytope;
      in.X_WB = motion.pose(0.5 * (I.ta + I.tb));
      ++out->pair_queries;
      if (intersect(in, warmIn(*table, 0, i, j)).intersecting) {
        out->collides = true;
        best = I.ta;  // not a first contact: only `collides` is meaningful in this mode
        best_contact = contact;
        break;
      }
    }
    splitTime(t, I);
  }
  if (out->collides) {
    out->fraction = best;
    out->contact = best_contact;
  }
}

}  // namespace mddual::planning
