#include "mddual/planning/edges.h"

#include <cmath>
#include <string>

#include "mddual/error.h"

namespace mddual::planning {
namespace {

std::string num(double x) {
  return std::to_string(x);
}

bool isRotation(const Eigen::Matrix3d& R) {
  return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).isZero(kEdgeRotationTolerance) &&
         R.determinant() > 0.0;
}

}  // namespace

EdgeMotion translationEdge(const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& direction_W, double length) {
  if (!X_WR.matrix().allFinite()) throw InvalidInputError("translationEdge: the start pose X_WR is not finite");
  if (!isRotation(X_WR.linear())) {
    throw InvalidInputError("translationEdge: the linear part of X_WR is not a rotation (within " +
                            num(kEdgeRotationTolerance) + ")");
  }
  const double n = direction_W.norm();
  if (!std::isfinite(n) || !(n > 0.0)) {
    throw InvalidInputError("translationEdge: the direction is zero or not finite");
  }
  if (!std::isfinite(length) || length < 0.0) {
    throw InvalidInputError("translationEdge: the length " + num(length) + " is negative or not finite");
  }
  EdgeMotion m;
  m.R_start = X_WR.linear();
  m.q_start = Eigen::Quaterniond(m.R_start).normalized();
  m.p_start = X_WR.translation();
  m.p_end = m.p_start + (length / n) * direction_W;
  m.X_end.linear() = m.R_start;
  m.X_end.translation() = m.p_end;
  return m;
}

EdgeMotion extendedEdge(const EdgeMotion& edge, double factor) {
  if (!std::isfinite(factor) || !(factor > 0.0)) {
    throw InvalidInputError("extendedEdge: the factor " + num(factor) + " is not finite and positive");
  }
  if (!edge.p_start.allFinite() || !edge.p_end.allFinite() || !edge.q_start.coeffs().allFinite() ||
      !edge.axis_R.allFinite() || !std::isfinite(edge.angle)) {
    throw InvalidInputError("extendedEdge: the edge has non-finite fields");
  }
  if (edge.angle < 0.0) throw InvalidInputError("extendedEdge: the edge's angle " + num(edge.angle) + " is negative");
  if (edge.angle > 0.0 && std::abs(edge.axis_R.norm() - 1.0) > kEdgeRotationTolerance) {
    throw InvalidInputError("extendedEdge: the edge's rotation axis is not a unit vector (norm " +
                            num(edge.axis_R.norm()) + ")");
  }
  if (!isRotation(edge.R_start)) throw InvalidInputError("extendedEdge: the edge's R_start is not a rotation");
  EdgeMotion m = edge;
  m.p_end = edge.p_start + factor * (edge.p_end - edge.p_start);
  m.angle = factor * edge.angle;
  // Exactly what EdgeMotion::endDiffers() compares, so the end is not checked twice.
  m.X_end = Eigen::Isometry3d::Identity();
  m.X_end.translation() = m.p_end;
  m.X_end.linear() = m.angle == 0.0 ? m.R_start : m.orientation(1.0).toRotationMatrix();
  return m;
}

}  // namespace mddual::planning
