#include "fcl_bvh.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/continuous_collision.h>

#include <atomic>
#include <iostream>
#include <memory>
#include <streambuf>
#include <utility>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::soundness {
namespace {

namespace ob = ompl::base;

std::atomic<std::uint64_t> warnings{0};

/// Counts the lines written to it and drops them.
class LineCounter : public std::streambuf {
 public:
  std::uint64_t lines = 0;

 protected:
  int overflow(int ch) override {
    if (ch == '\n') ++lines;
    return ch == traits_type::eof() ? traits_type::not_eof(ch) : ch;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) lines += s[i] == '\n';
    return n;
  }
};

/// std::cerr into a LineCounter while it lives; the count goes to `warnings`.
class CerrCounted {
 public:
  CerrCounted() : old_(std::cerr.rdbuf(&counter_)) {}
  ~CerrCounted() {
    std::cerr.rdbuf(old_);
    warnings += counter_.lines;
  }
  CerrCounted(const CerrCounted&) = delete;
  CerrCounted& operator=(const CerrCounted&) = delete;

 private:
  LineCounter counter_;
  std::streambuf* old_;
};

/// The pieces as one triangle soup in a BVHModel<BV>: a flat piece's vertex
/// loop, a convex piece's every face, fanned into triangles.
template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> soup(const std::vector<scene::Piece>& pieces) {
  std::vector<fcl::Vector3<double>> points;
  std::vector<fcl::Triangle> triangles;
  for (const scene::Piece& piece : pieces) {
    const ConvexPolytope& p = piece.polytope;
    const auto base = points.size();
    for (int v = 0; v < p.numVertices(); ++v) points.push_back(p.vertex(v));
    const int faces = piece.kind == scene::PieceKind::kTriangle ? 1 : p.numFaces();
    for (int f = 0; f < faces; ++f) {
      const IndexRange loop = p.faceVertices(f);
      for (int k = 1; k + 1 < loop.size(); ++k) {
        triangles.emplace_back(base + static_cast<std::size_t>(loop[0]), base + static_cast<std::size_t>(loop[k]),
                               base + static_cast<std::size_t>(loop[k + 1]));
      }
    }
  }
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

template <class BV>
class BvhContinuousMotionValidator : public ob::MotionValidator {
 public:
  BvhContinuousMotionValidator(const ob::SpaceInformationPtr& si, const Scene& s)
      : ob::MotionValidator(si),
        space_(s.space),
        robot_(soup<BV>(s.robot->pieces())),
        world_(soup<BV>(s.world->pieces())) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool valid = si_->isValid(s2) && !(cast(s1, s2) <= 1.0);
    valid ? ++valid_ : ++invalid_;
    return valid;
  }

  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    double first_invalid = cast(s1, s2);
    if (first_invalid > 1.0 && !si_->isValid(s2)) first_invalid = 1.0;
    if (first_invalid > 1.0) {
      ++valid_;
      return true;
    }
    planning::setLastValid(*si_, s1, s2, first_invalid, lastValid);
    ++invalid_;
    return false;
  }

 private:
  /// FCL's time of contact, or 2 when it finds none.
  double cast(const ob::State* s1, const ob::State* s2) const {
    fcl::ContinuousCollisionRequest<double> request;
    request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    request.gjk_solver_type = fcl::GST_LIBCCD;
    const bool screw = space_->motion(s1, s2).rotates();
    request.ccd_motion_type = screw ? fcl::CCDM_SCREW : fcl::CCDM_TRANS;
    const Eigen::Isometry3d X_start = space_->pose(s1);
    Eigen::Isometry3d X_end = space_->pose(s2);
    if (!screw) X_end.linear() = X_start.linear();
    const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
    fcl::ContinuousCollisionResult<double> result;
    {
      const CerrCounted quiet;
      fcl::continuousCollide(robot_.get(), X_start, X_end, world_.get(), identity, identity, request, result);
    }
    return result.is_collide ? std::max(0.0, result.time_of_contact) : 2.0;
  }

  planning::PlanningSpacePtr space_;
  std::shared_ptr<fcl::BVHModel<BV>> robot_;
  std::shared_ptr<fcl::BVHModel<BV>> world_;
};

}  // namespace

ob::MotionValidatorPtr makeFclBvhContinuous(const ob::SpaceInformationPtr& si, const Scene& s, FclBvh bvh) {
  if (!s.space || !s.robot || !s.world) throw InvalidInputError("soundness: the FCL hierarchies need a rigid scene");
  if (bvh == FclBvh::kObb) return std::make_shared<BvhContinuousMotionValidator<fcl::OBB<double>>>(si, s);
  return std::make_shared<BvhContinuousMotionValidator<fcl::RSS<double>>>(si, s);
}

std::uint64_t fclBvhWarnings() {
  return warnings.load();
}

}  // namespace mddual::soundness
