// Bullet and FCL wrappers (see peers.h). Compiled with BT_USE_DOUBLE_PRECISION
// against the float64 build of Bullet; the third-party headers are included
// as SYSTEM headers by benchmarks/CMakeLists.txt.
#include "peers.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>

#include "mddual/fcl_interop.h"

static_assert(sizeof(btScalar) == sizeof(double),
              "Bullet must be the double-precision build (BT_USE_DOUBLE_PRECISION)");

namespace mddual::bench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

btTransform toBullet(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  const Eigen::Vector3d& p = X.translation();
  return btTransform(btMatrix3x3(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)),
                     btVector3(p.x(), p.y(), p.z()));
}

std::unique_ptr<btConvexHullShape> bulletHull(const ConvexPolytope& p) {
  auto shape = std::make_unique<btConvexHullShape>();
  for (const Eigen::Vector3d& v : p.vertices()) shape->addPoint(btVector3(v.x(), v.y(), v.z()), false);
  shape->recalcLocalAabb();
  // Bullet pads convex shapes by a 0.04 collision margin by default: remove it
  // so that the cast sees exactly the same hull.
  shape->setMargin(0.0);
  return shape;
}

/// btGjkConvexCast or btSubsimplexConvexCast from B's pose to B's pose
/// translated by cast_length * s; A does not move.
template <class Cast>
class BulletCast final : public ToiPeer {
 public:
  BulletCast(std::string name, const ConvexPolytope& a, const ConvexPolytope& b, double cast_length)
      : name_(std::move(name)), a_(bulletHull(a)), b_(bulletHull(b)), length_(cast_length) {}
  const std::string& name() const override { return name_; }
  double toi(const Query& q) override {
    const btTransform from_a = toBullet(q.X_WA);
    const btTransform from_b = toBullet(q.X_WB);
    btTransform to_b = from_b;
    const Eigen::Vector3d d = length_ * q.s_W;
    to_b.setOrigin(from_b.getOrigin() + btVector3(d.x(), d.y(), d.z()));
    Cast cast(a_.get(), b_.get(), &simplex_);
    btConvexCast::CastResult result;
    if (!cast.calcTimeOfImpact(from_a, from_a, from_b, to_b, result)) return kInf;
    const double fraction = result.m_fraction;
    if (!std::isfinite(fraction)) throw std::runtime_error(name_ + ": non-finite fraction");
    return fraction > 1.0 ? kInf : fraction * length_;
  }

 private:
  std::string name_;
  std::unique_ptr<btConvexHullShape> a_;
  std::unique_ptr<btConvexHullShape> b_;
  btVoronoiSimplexSolver simplex_;
  double length_;
};

class FclCcd final : public ToiPeer {
 public:
  FclCcd(std::string name, const ConvexPolytope& a, const ConvexPolytope& b, double cast_length,
         fcl::CCDSolverType solver, fcl::GJKSolverType gjk)
      : name_(std::move(name)), a_(toFclConvex(a)), b_(toFclConvex(b)), length_(cast_length) {
    request_.ccd_motion_type = fcl::CCDM_TRANS;
    request_.ccd_solver_type = solver;
    request_.gjk_solver_type = gjk;
  }
  const std::string& name() const override { return name_; }
  double toi(const Query& q) override {
    fcl::Transform3<double> to_b = q.X_WB;
    to_b.translation() += length_ * q.s_W;
    fcl::ContinuousCollisionResult<double> result;
    const double r = fcl::continuousCollide<double>(a_.get(), q.X_WA, q.X_WA, b_.get(), q.X_WB, to_b, request_, result);
    if (r < 0.0) throw std::runtime_error(name_ + ": continuousCollide returned " + std::to_string(r));
    if (!result.is_collide) return kInf;
    if (!std::isfinite(result.time_of_contact)) throw std::runtime_error(name_ + ": non-finite time of contact");
    return result.time_of_contact * length_;
  }

 private:
  std::string name_;
  std::shared_ptr<fcl::Convex<double>> a_;
  std::shared_ptr<fcl::Convex<double>> b_;
  double length_;
  fcl::ContinuousCollisionRequest<double> request_;
};

/// FCL penetration: collide with contact (MPR with libccd, EPA with indep) or
/// signed distance (libccd's EPA).
class FclPenetration final : public PdPeer {
 public:
  enum class Mode { kCollide, kSignedDistance };
  FclPenetration(std::string name, const ConvexPolytope& a, const ConvexPolytope& b, Mode mode, fcl::GJKSolverType gjk)
      : name_(std::move(name)), a_(toFclConvex(a)), b_(toFclConvex(b)), mode_(mode) {
    collide_.num_max_contacts = 1;
    collide_.enable_contact = true;
    collide_.gjk_solver_type = gjk;
    distance_.enable_signed_distance = true;
    distance_.enable_nearest_points = true;
    distance_.gjk_solver_type = gjk;
  }
  const std::string& name() const override { return name_; }
  PdAnswer penetration(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) override {
    PdAnswer out;
    if (mode_ == Mode::kCollide) {
      fcl::CollisionResult<double> result;
      fcl::collide<double>(a_.get(), X_WA, b_.get(), X_WB, collide_, result);
      out.collide = result.isCollision();
      if (out.collide) {
        if (result.numContacts() == 0) throw std::runtime_error(name_ + ": collision without contact");
        // GST_INDEP reports the depth with a negative sign (FCL 0.7's EPA
        // path negates epa.depth); the magnitude is what is compared.
        out.depth = std::abs(result.getContact(0).penetration_depth);
      }
    } else {
      fcl::DistanceResult<double> result;
      const double d = fcl::distance<double>(a_.get(), X_WA, b_.get(), X_WB, distance_, result);
      out.collide = d < 0.0;
      out.depth = out.collide ? -d : 0.0;
    }
    if (!std::isfinite(out.depth)) throw std::runtime_error(name_ + ": non-finite depth");
    return out;
  }

 private:
  std::string name_;
  std::shared_ptr<fcl::Convex<double>> a_;
  std::shared_ptr<fcl::Convex<double>> b_;
  Mode mode_;
  fcl::CollisionRequest<double> collide_;
  fcl::DistanceRequest<double> distance_;
};

/// Bullet's GJK + EPA penetration (btGjkEpaSolver2::Penetration).
class BulletEpa final : public PdPeer {
 public:
  BulletEpa(std::string name, const ConvexPolytope& a, const ConvexPolytope& b)
      : name_(std::move(name)), a_(bulletHull(a)), b_(bulletHull(b)) {}
  const std::string& name() const override { return name_; }
  PdAnswer penetration(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) override {
    btGjkEpaSolver2::sResults result;
    const btTransform ta = toBullet(X_WA);
    const btTransform tb = toBullet(X_WB);
    const btVector3 guess = tb.getOrigin() - ta.getOrigin();
    PdAnswer out;
    out.collide = btGjkEpaSolver2::Penetration(a_.get(), ta, b_.get(), tb, guess, result);
    if (out.collide) {
      if (result.status != btGjkEpaSolver2::sResults::Penetrating) {
        throw std::runtime_error(name_ + ": status " + std::to_string(static_cast<int>(result.status)));
      }
      out.depth = -result.distance;
    } else if (result.status == btGjkEpaSolver2::sResults::EPA_Failed) {
      throw std::runtime_error(name_ + ": EPA failed");
    }
    if (!std::isfinite(out.depth)) throw std::runtime_error(name_ + ": non-finite depth");
    return out;
  }

 private:
  std::string name_;
  std::unique_ptr<btConvexHullShape> a_;
  std::unique_ptr<btConvexHullShape> b_;
};

}  // namespace

std::vector<std::string> pdPeerNames() {
  return {"fcl_mpr_libccd", "fcl_epa_indep", "fcl_epa_libccd", "bullet_epa"};
}

std::string pdPeerSettings(const std::string& name) {
  if (name == "fcl_mpr_libccd") {
    return "fcl::collide, num_max_contacts=1, enable_contact, GST_LIBCCD (FCL 0.7: libccd MPR penetration)";
  }
  if (name == "fcl_epa_indep") return "fcl::collide, num_max_contacts=1, enable_contact, GST_INDEP (GJK + EPA)";
  if (name == "fcl_epa_libccd") {
    return "fcl::distance, enable_signed_distance, GST_LIBCCD (libccd GJK + EPA); depth = -distance";
  }
  if (name == "bullet_epa") return "btGjkEpaSolver2::Penetration, btConvexHullShape margin 0 (double)";
  return "";
}

std::vector<std::unique_ptr<PdPeer>> makePdPeers(const ConvexPolytope& a, const ConvexPolytope& b,
                                                 const std::vector<std::string>& names) {
  std::vector<std::unique_ptr<PdPeer>> out;
  for (const std::string& n : pdPeerNames()) {
    if (!names.empty() && std::find(names.begin(), names.end(), n) == names.end()) continue;
    if (n == "fcl_mpr_libccd") {
      out.push_back(std::make_unique<FclPenetration>(n, a, b, FclPenetration::Mode::kCollide, fcl::GST_LIBCCD));
    }
    if (n == "fcl_epa_indep") {
      out.push_back(std::make_unique<FclPenetration>(n, a, b, FclPenetration::Mode::kCollide, fcl::GST_INDEP));
    }
    if (n == "fcl_epa_libccd") {
      out.push_back(std::make_unique<FclPenetration>(n, a, b, FclPenetration::Mode::kSignedDistance, fcl::GST_LIBCCD));
    }
    if (n == "bullet_epa") out.push_back(std::make_unique<BulletEpa>(n, a, b));
  }
  return out;
}

std::vector<std::string> peerNames() {
  return {"bullet_gjk", "bullet_subsimplex", "fcl_naive", "fcl_ca_libccd", "fcl_ca_indep"};
}

std::string peerSettings(const std::string& name) {
  if (name == "bullet_gjk") return "btGjkConvexCast, btConvexHullShape margin 0, btVoronoiSimplexSolver (double)";
  if (name == "bullet_subsimplex") {
    return "btSubsimplexConvexCast, btConvexHullShape margin 0, btVoronoiSimplexSolver (double)";
  }
  if (name == "fcl_naive") {
    return "fcl::continuousCollide CCDC_NAIVE, CCDM_TRANS, default num_max_iterations=10 toc_err=1e-4";
  }
  if (name == "fcl_ca_libccd") return "fcl::continuousCollide CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS, GST_LIBCCD";
  if (name == "fcl_ca_indep") return "fcl::continuousCollide CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS, GST_INDEP";
  return "";
}

std::vector<std::unique_ptr<ToiPeer>> makePeers(const ConvexPolytope& a, const ConvexPolytope& b, double cast_length,
                                                const std::vector<std::string>& names) {
  std::vector<std::unique_ptr<ToiPeer>> out;
  for (const std::string& n : peerNames()) {
    if (!names.empty() && std::find(names.begin(), names.end(), n) == names.end()) continue;
    if (n == "bullet_gjk") out.push_back(std::make_unique<BulletCast<btGjkConvexCast>>(n, a, b, cast_length));
    if (n == "bullet_subsimplex") {
      out.push_back(std::make_unique<BulletCast<btSubsimplexConvexCast>>(n, a, b, cast_length));
    }
    if (n == "fcl_naive") {
      out.push_back(std::make_unique<FclCcd>(n, a, b, cast_length, fcl::CCDC_NAIVE, fcl::GST_LIBCCD));
    }
    if (n == "fcl_ca_libccd") {
      out.push_back(
          std::make_unique<FclCcd>(n, a, b, cast_length, fcl::CCDC_CONSERVATIVE_ADVANCEMENT, fcl::GST_LIBCCD));
    }
    if (n == "fcl_ca_indep") {
      out.push_back(std::make_unique<FclCcd>(n, a, b, cast_length, fcl::CCDC_CONSERVATIVE_ADVANCEMENT, fcl::GST_INDEP));
    }
  }
  return out;
}

}  // namespace mddual::bench
