#include "pair.h"

#include <cmath>
#include <sstream>

#include "mddual/error.h"

namespace mddual::detail {
namespace {

/// PairGeometry's double path: both bodies' local origins within this many
/// of the larger body radius from the world origin (a round-off of about
/// 1e3 * 2^-53 = 1e-13 of the scale; see the constructor).
constexpr double kDoublePoseRange = 1024.0;

void checkPose(const Eigen::Isometry3d& X, const char* name, const char* query) {
  // A hierarchy's queries repeat poses: the identity for world pieces, one
  // robot pose for many pairs, two link poses for an arm's self pair. The
  // identity and the last two poses this thread validated are accepted on an
  // exact comparison (NaN never compares equal), which costs a twentieth of
  // the full check (callgrind on the apartment's state checks,
  // mddual_bench_planning --mdd-only; docs/results/tuning.md).
  using Pose34 = Eigen::Matrix<double, 3, 4>;
  static const Pose34 kIdentity = Pose34::Identity();
  thread_local Pose34 last_valid[2] = {Pose34::Identity(), Pose34::Identity()};
  thread_local int older = 0;
  const auto X34 = X.matrix().topRows<3>();
  if (X34 == kIdentity || X34 == last_valid[0] || X34 == last_valid[1]) return;
  const Eigen::Matrix3d& R = X.linear();
  const bool finite = R.allFinite() && X.translation().allFinite();
  if (finite && X.translation().cwiseAbs().maxCoeff() > defaults::kMaxCoordinate) {
    std::ostringstream msg;
    msg << query << ": pose " << name << " has a translation beyond " << defaults::kMaxCoordinate
        << " in magnitude (out of the supported range)";
    throw InvalidInputError(msg.str());
  }
  if (!finite) requireFinitePose(X, (std::string("pose ") + name).c_str(), query);  // throws, saying which part
  const bool rotation = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0.0;
  if (!rotation) {
    throw InvalidInputError(std::string(query) + ": pose " + name +
                            " is not a rigid transform (its rotation part must be orthonormal with determinant 1)");
  }
  last_valid[older] = X34;
  older = 1 - older;
}

}  // namespace

PairGeometry::PairGeometry(const ConvexPolytope* a, const Eigen::Isometry3d& X_WA, const ConvexPolytope* b,
                           const Eigen::Isometry3d& X_WB, const char* query)
    : a_(a != nullptr ? *a : throw InvalidInputError(std::string(query) + ": polytope A is null")),
      b_(b != nullptr ? *b : throw InvalidInputError(std::string(query) + ": polytope B is null")),
      X_WA_(X_WA) {
  checkPose(X_WA, "X_WA", query);
  checkPose(X_WB, "X_WB", query);
  // The pair is evaluated in A's local frame (polytope.h): "A's frame" below
  // and in every _A name of the core means that frame. X_WA_ = X_WA X_PL(A).
  // B's local frame relative to it:
  //   R_AB = R_WA^T R_WB,  p_AB = R_WA^T (t_WB + R_WB p_PL(B) - t_WA - R_WA p_PL(A)).
  // The translation subtracts nearly equal large numbers when both bodies are
  // far from the world origin; in long double (64-bit mantissa on x86-64) the
  // cancellation costs 2^11 times less than in double, so p_AB keeps the
  // bodies' relative position to about 1e-19 of their distance from the
  // origin. With identity poses (bodies given in world coordinates) it is
  // exact: the difference of the two local origins.
  //
  // Near the origin (both local origins within kDoublePoseRange body radii of
  // it) double arithmetic loses at most about 1e-13 of the pair's scale, far
  // below the touching tolerance (kTouchRel = 1e-10), and is several times
  // cheaper than the x87 long double path (an arm's motion check builds a
  // pair per GJK call: perf, mddual_bench_arm_edges).
  const Eigen::Vector3d p_WLa_d = X_WA.translation() + X_WA.linear() * a_.p_PL();
  const Eigen::Vector3d p_WLb_d = X_WB.translation() + X_WB.linear() * b_.p_PL();
  const double range = kDoublePoseRange * std::max(a_.radius(), b_.radius());
  if (p_WLa_d.cwiseAbs().maxCoeff() <= range && p_WLb_d.cwiseAbs().maxCoeff() <= range) {
    X_WA_.translation() = p_WLa_d;
    R_AB_ = X_WA.linear().transpose() * X_WB.linear();
    p_AB_ = X_WA.linear().transpose() * (p_WLb_d - p_WLa_d);
    finishSetUp();
    return;
  }
  using Vec3L = Eigen::Matrix<long double, 3, 1>;
  using Mat3L = Eigen::Matrix<long double, 3, 3>;
  const Mat3L R_WA = X_WA.linear().cast<long double>();
  const Mat3L R_WB = X_WB.linear().cast<long double>();
  const Vec3L p_WLa = X_WA.translation().cast<long double>() + R_WA * a_.p_PL().cast<long double>();
  const Vec3L p_WLb = X_WB.translation().cast<long double>() + R_WB * b_.p_PL().cast<long double>();
  X_WA_.translation() = p_WLa.cast<double>();
  R_AB_ = (R_WA.transpose() * R_WB).cast<double>();
  p_AB_ = (R_WA.transpose() * (p_WLb - p_WLa)).cast<double>();
  finishSetUp();
}

void PairGeometry::finishSetUp() {
  g_A_ = a_.localCentroid() - (R_AB_ * b_.localCentroid() + p_AB_);
  scale_ = std::max({a_.radius(), b_.radius(), g_A_.norm()});
  if (a_.isFlat() && b_.isFlat()) {
    const Eigen::Vector3d nb_A = R_AB_ * b_.faceNormal(0);
    if (a_.faceNormal(0).cross(nb_A).norm() <= defaults::kParallelSin) {
      flat_m_ = true;
      flat_normal_A_ = a_.faceNormal(0);
    }
  }
}

int PairGeometry::supportA(const Eigen::Vector3d& d_A, int hint, SearchStats* stats, double* gap) const {
  SupportStats s;
  const int v = a_.supportVertex(d_A, hint < a_.numVertices() ? hint : -1, &s, gap);
  if (stats != nullptr) stats->support_vertices += s.vertices_visited;
  return v;
}

int PairGeometry::supportMinusB(const Eigen::Vector3d& d_A, int hint, SearchStats* stats, double* gap) const {
  SupportStats s;
  const int v = b_.supportVertex(-aToB(d_A), hint < b_.numVertices() ? hint : -1, &s, gap);
  if (stats != nullptr) stats->support_vertices += s.vertices_visited;
  return v;
}

MPoint PairGeometry::supportM(const Eigen::Vector3d& d_A, int hint_a, int hint_b, SearchStats* stats) const {
  MPoint m;
  m.va = supportA(d_A, hint_a, stats);
  m.vb = supportMinusB(d_A, hint_b, stats);
  m.p_A = a_.localVertex(m.va) - bVertex(m.vb);
  return m;
}

void checkMaxDistance(double max_distance, const char* query) {
  if (!(max_distance >= 0.0)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << query << ": max_distance " << max_distance << " must be >= 0 (or +infinity)";
    throw InvalidInputError(msg.str());
  }
}

Eigen::Vector3d unitDirection(const Eigen::Vector3d& s, const char* query) {
  // Divide by the largest coordinate first: |s| itself may overflow or
  // underflow for valid directions such as [1e300, 0, 0] or [1e-200, 0, 0].
  const double largest = s.cwiseAbs().maxCoeff();
  if (!s.allFinite() || !(largest > 0.0)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << query << ": direction [" << s.x() << ", " << s.y() << ", " << s.z() << "] must be finite and nonzero";
    throw InvalidInputError(msg.str());
  }
  return (s / largest).normalized();
}

}  // namespace mddual::detail

namespace mddual {

std::string toJsonLine(const DirectionalInput& input, const std::string& id) {
  std::ostringstream out;
  out.precision(17);
  auto points = [&](const ConvexPolytope* p, const Eigen::Isometry3d& X) {
    out << "[";
    for (int v = 0; p != nullptr && v < p->numVertices(); ++v) {
      const Eigen::Vector3d w = X * p->vertex(v);
      out << (v > 0 ? ", " : "") << "[" << w.x() << ", " << w.y() << ", " << w.z() << "]";
    }
    out << "]";
  };
  out << R"({"id": ")" << id << R"(", "a": )";
  points(input.a, input.X_WA);
  out << R"(, "b": )";
  points(input.b, input.X_WB);
  const Eigen::Vector3d& s = input.s_W;
  out << R"(, "direction": [)" << s.x() << ", " << s.y() << ", " << s.z() << "]}";
  return out.str();
}

void requireFinitePose(const Eigen::Isometry3d& X, const char* what, const char* query) {
  if (X.matrix().topRows<3>().allFinite()) return;
  throw InvalidInputError(std::string(query) + ": " + what + " has a non-finite " +
                          (X.linear().allFinite() ? "translation" : "rotation") + " entry (NaN or infinity)");
}

}  // namespace mddual
