#include "planar.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mddual::detail {
namespace {

double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// Barycentric weights down to -kFanWeightSlack count as inside a triangle
/// (round-off of a point on a side); dimensionless, so the point moves by at
/// most this fraction of the triangle's size when they are clamped to 0.
constexpr double kFanWeightSlack = 1e-12;

/// A fan triangle whose sine (twice its area over the product of its two
/// sides at the fan's apex) is at most this is skipped: its barycentric
/// weights are round-off noise. Dimensionless. The hull keeps points that
/// round-off moves 1e-33 off a straight edge of M's face, and such a flat
/// triangle took a point on that edge to the apex (QueryRegressions.
/// ContactPointOnBothBodiesForBoxesTouchingAlongAnEdge: the contact point
/// came out at a corner of A, 0.5 outside B). A point inside a skipped
/// triangle lies within this fraction of the polygon's size of its edges,
/// where the nearest-edge decomposition below takes it.
constexpr double kFanMinSin = 1e-12;

}  // namespace

PlanarDifference::PlanarDifference(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                                   const Eigen::Vector3d& normal)
    : pa_(pa) {
  const Eigen::Vector3d t = std::abs(normal.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1_ = normal.cross(t).normalized();
  e2_ = normal.cross(e1_);
  std::vector<Vertex> points;
  points.reserve(pa.size() * pb.size());
  for (size_t i = 0; i < pa.size(); ++i) {
    for (size_t j = 0; j < pb.size(); ++j) {
      points.push_back({toPlane(pa[i] - pb[j]), static_cast<int>(i), static_cast<int>(j)});
    }
  }
  // Andrew's monotone chain on a handful of points (the supporting features
  // of A and B); collinear points are dropped, duplicates collapse.
  std::sort(points.begin(), points.end(), [](const Vertex& a, const Vertex& b) {
    return a.q.x() < b.q.x() || (a.q.x() == b.q.x() && a.q.y() < b.q.y());
  });
  std::vector<Vertex> hull(2 * points.size() + 1);
  size_t k = 0;
  for (const Vertex& p : points) {  // lower chain
    while (k >= 2 && cross2(hull[k - 2].q, hull[k - 1].q, p.q) <= 0.0) --k;
    hull[k++] = p;
  }
  const size_t lower = k + 1;
  for (auto it = points.rbegin() + 1; it != points.rend(); ++it) {  // upper chain
    while (k >= lower && cross2(hull[k - 2].q, hull[k - 1].q, it->q) <= 0.0) --k;
    hull[k++] = *it;
  }
  hull.resize(k > 1 ? k - 1 : k);
  if (hull.size() == 2 && hull[0].q == hull[1].q) hull.resize(1);
  hull_ = std::move(hull);
}

Eigen::Vector2d PlanarDifference::edgeNormal(int k) const {
  const int n = static_cast<int>(hull_.size());
  const Eigen::Vector2d e = hull_[(k + 1) % n].q - hull_[k].q;
  return Eigen::Vector2d(e.y(), -e.x()).normalized();  // right of a counter-clockwise edge
}

PlanarSlice PlanarDifference::slice(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tol) const {
  PlanarSlice out;
  const Eigen::Vector2d o2 = toPlane(o);
  const Eigen::Vector2d d2 = toPlane(d).normalized();
  const Eigen::Vector2d across(-d2.y(), d2.x());
  const int n = static_cast<int>(hull_.size());
  out.s_lo = std::numeric_limits<double>::infinity();
  out.s_hi = -std::numeric_limits<double>::infinity();
  // A candidate end: position s along the line, at parameter lambda on edge k.
  auto consider = [&](double s, int k, double lambda) {
    const Vertex& p = hull_[k];
    const Vertex& q = hull_[(k + 1) % n];
    const Eigen::Vector3d a = (1.0 - lambda) * pa_[p.i] + lambda * pa_[q.i];
    // Outward normal at this end: the polygon edge's, or along the line when
    // the polygon is degenerate (a point or a segment).
    const bool polygon = n >= 3;
    if (s < out.s_lo) {
      out.s_lo = s;
      out.a_lo = a;
      out.normal_lo = fromPlane(polygon ? edgeNormal(k) : Eigen::Vector2d(-d2));
    }
    if (s > out.s_hi) {
      out.s_hi = s;
      out.a_hi = a;
      out.normal_hi = fromPlane(polygon ? edgeNormal(k) : d2);
    }
  };
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d p = hull_[k].q - o2;
    const Eigen::Vector2d q = hull_[(k + 1) % n].q - o2;
    const double yp = p.dot(across);
    const double yq = q.dot(across);
    const double sp = p.dot(d2);
    const double sq = q.dot(d2);
    if (std::abs(yp) <= tol) consider(sp, k, 0.0);
    if (n >= 2 && std::abs(yq) <= tol) consider(sq, k, 1.0);
    if ((yp < -tol && yq > tol) || (yp > tol && yq < -tol)) {
      const double lambda = yp / (yp - yq);
      consider(sp + lambda * (sq - sp), k, lambda);
    }
  }
  out.hit = out.s_lo <= out.s_hi;
  return out;
}

double PlanarDifference::outsideDistance(const Eigen::Vector3d& x, Eigen::Vector3d* edge_normal) const {
  const Eigen::Vector2d x2 = toPlane(x);
  const int n = static_cast<int>(hull_.size());
  if (n == 1) {
    const Eigen::Vector2d v = x2 - hull_[0].q;
    const double dist = v.norm();
    *edge_normal = dist > 0.0 ? fromPlane(v / dist) : Eigen::Vector3d(e1_);
    return dist;
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d m = edgeNormal(k);
    const double dist = m.dot(x2 - hull_[k].q);
    if (dist > best) {
      best = dist;
      *edge_normal = fromPlane(m);
    }
  }
  if (n == 2) {  // a segment: also its extent along its own line
    const Eigen::Vector2d axis = (hull_[1].q - hull_[0].q).normalized();
    const double beyond_end = std::max(axis.dot(x2 - hull_[1].q), -axis.dot(x2 - hull_[0].q));
    if (beyond_end > best) {
      best = beyond_end;
      *edge_normal = fromPlane(axis.dot(x2 - hull_[1].q) >= -axis.dot(x2 - hull_[0].q) ? axis : Eigen::Vector2d(-axis));
    }
  }
  return best;
}

Eigen::Vector3d PlanarDifference::pointOfA(const Eigen::Vector3d& x, double* outside) const {
  const Eigen::Vector2d x2 = toPlane(x);
  const int n = static_cast<int>(hull_.size());
  // Inside a polygon: barycentric weights in the triangle of the fan from
  // hull vertex 0 that holds x (the same weights combine the points of A).
  // The triangle whose smallest weight is largest: a point on a diagonal may
  // get a weight of -1e-17 in both triangles beside it.
  double best_min = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d w_best = Eigen::Vector3d::Zero();
  int k_best = -1;
  for (int k = 1; k + 1 < n; ++k) {
    const Eigen::Vector2d& p0 = hull_[0].q;
    const Eigen::Vector2d& p1 = hull_[k].q;
    const Eigen::Vector2d& p2 = hull_[k + 1].q;
    const double area = cross2(p0, p1, p2);
    if (!(area > kFanMinSin * (p1 - p0).norm() * (p2 - p0).norm())) continue;
    const double w1 = cross2(p0, x2, p2) / area;
    const double w2 = cross2(p0, p1, x2) / area;
    const Eigen::Vector3d w(1.0 - w1 - w2, w1, w2);
    if (w.minCoeff() > best_min) {
      best_min = w.minCoeff();
      w_best = w;
      k_best = k;
    }
  }
  if (k_best >= 0 && best_min >= -kFanWeightSlack) {
    const Eigen::Vector3d w = w_best.cwiseMax(0.0) / w_best.cwiseMax(0.0).sum();
    *outside = 0.0;
    return w[0] * pa_[hull_[0].i] + w[1] * pa_[hull_[k_best].i] + w[2] * pa_[hull_[k_best + 1].i];
  }
  // Outside (or a point, a segment, or on the boundary up to round-off): the
  // nearest point of the polygon lies on one of its edges (or is its only
  // vertex); interpolate the points of A along that edge.
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d a = pa_[hull_[0].i];
  for (int k = 0; k < n; ++k) {
    const Vertex& p = hull_[k];
    const Vertex& q = hull_[(k + 1) % n];
    const Eigen::Vector2d e = q.q - p.q;
    const double len2 = e.squaredNorm();
    const double lambda = len2 > 0.0 ? std::clamp(e.dot(x2 - p.q) / len2, 0.0, 1.0) : 0.0;
    const double dist = (p.q + lambda * e - x2).norm();
    if (dist < best) {
      best = dist;
      a = (1.0 - lambda) * pa_[p.i] + lambda * pa_[q.i];
    }
  }
  *outside = best;
  return a;
}

}  // namespace mddual::detail
