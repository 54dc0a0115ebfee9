// Test oracle for the penetration-depth module: runs every method on one
// posed pair against the brute force (M built explicitly), checks the depth,
// the status, that the translation separates the interiors and that the
// reported facet's features lie on its plane, and prints any failing pair
// as a JSON line of the CLI's input format (paste it into a test or into
// `mddual pd`).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "mddual/brute_force.h"
#include "mddual/penetration.h"
#include "pair.h"
#include "query_oracle.h"

namespace mddual::testing {

/// What a family's sample contained (non-degeneracy guards).
struct PdTally {
  int scenes = 0;
  int separated = 0;
  int touching = 0;
  int penetrating = 0;
  int flat_m = 0;
  int ee_closest = 0;  ///< penetrating scenes whose closest facet (exact) is an EE facet
  int approx_checks = 0;
  int approx_exact_hits = 0;  ///< approximate answers equal to PD
  /// Exact answers taken from the explicit M (stats.brute_fallbacks): these
  /// compare the brute force with itself, so a family bounds their number.
  int brute_fallbacks = 0;
  double fraction(int n) const { return scenes > 0 ? static_cast<double>(n) / scenes : 0.0; }
};

class PdOracle {
 public:
  /// rel_tol: agreement required of the exact methods, relative to the pair's length scale.
  explicit PdOracle(std::vector<double> approx_deltas, double rel_tol = 1e-9)
      : deltas_(std::move(approx_deltas)), rel_tol_(rel_tol) {}

  /// Checks all methods on the pair; returns the number of failures (each
  /// also reported through gtest with the pair printed).
  int check(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
            const Eigen::Isometry3d& X_WB, PdTally* tally) {
    const detail::PairGeometry pair(&a, X_WA, &b, X_WB, "test");
    const double tol = rel_tol_ * pair.scale();
    const double world_tol = tol + worldRoundoff(a, X_WA, b, X_WB);  // query_oracle.h
    ++tally->scenes;
    if (pair.flatM()) ++tally->flat_m;
    PenetrationInput in{&a, X_WA, &b, X_WB};
    in.method = PenetrationMethod::kBruteForce;
    const PenetrationResult ref = penetrationDepth(in);
    if (ref.status == PenetrationStatus::kSeparated) ++tally->separated;
    if (ref.status == PenetrationStatus::kTouching) ++tally->touching;
    if (ref.status == PenetrationStatus::kPenetrating) ++tally->penetrating;
    int failures = 0;
    auto report = [&](const std::string& what, const PenetrationResult& r) {
      ++failures;
      std::ostringstream o;
      o.precision(17);
      o << what << "\n  got (delta " << r.delta << "): " << toString(r.status) << " depth " << r.depth << " normal ["
        << r.normal_W.transpose() << "]\n  brute: " << toString(ref.status) << " depth " << ref.depth << " normal ["
        << ref.normal_W.transpose()
        << "]\n  pair: " << toJsonLine(DirectionalInput{&a, X_WA, &b, X_WB, Eigen::Vector3d::UnitX()});
      ADD_FAILURE() << o.str();
    };
    auto run = [&](PenetrationMethod method, double delta, const char* name) {
      in.method = method;
      in.delta = delta;
      const PenetrationResult r = penetrationDepth(in);
      std::ostringstream why;
      if (!statusAgrees(r, ref, tol)) {
        why << name << ": status differs";
      } else if (method == PenetrationMethod::kApprox) {
        ++tally->approx_checks;
        if (std::abs(r.depth - ref.depth) <= tol) ++tally->approx_exact_hits;
        if (r.depth < ref.depth - tol || r.depth > (1.0 + r.delta) * ref.depth + tol)
          why << name << ": depth outside [PD, (1 + delta) PD]";
      } else if (std::abs(r.depth - ref.depth) > tol) {
        why << name << ": depth differs by " << r.depth - ref.depth;
      }
      if (why.str().empty()) validResult(a, X_WA, b, X_WB, r, world_tol, &why);
      if (!why.str().empty()) report(why.str(), r);
      return r;
    };
    const PenetrationResult exact = run(PenetrationMethod::kExact, 0.0, "exact");
    if (exact.facet.kind == FaceOfM::Kind::kEE) ++tally->ee_closest;
    if (exact.stats.brute_fallbacks > 0) ++tally->brute_fallbacks;
    if (exact.stats.walk_fallbacks > 0) {
      std::ostringstream why;
      why << "exact: " << exact.stats.walk_fallbacks << " Gaussian-map walk fallbacks";
      report(why.str(), exact);
    }
    run(PenetrationMethod::kShallow, 0.0, "shallow (default delta)");
    run(PenetrationMethod::kShallow, shallow_delta_, "shallow");
    for (double d : deltas_) run(PenetrationMethod::kApprox, d, "approx");
    return failures;
  }

  void setShallowDelta(double d) { shallow_delta_ = d; }

 private:
  static bool statusAgrees(const PenetrationResult& r, const PenetrationResult& ref, double tol) {
    if (r.status == ref.status) return true;
    // Across the touching boundary, both depths within tol of zero.
    const bool touching_side = r.status == PenetrationStatus::kTouching || ref.status == PenetrationStatus::kTouching;
    return touching_side && r.depth <= tol && ref.depth <= tol;
  }

  /// Fields as penetration.h promises them: zero translation when not
  /// penetrating; otherwise a unit normal, translation = depth * normal, the
  /// normal separating A from B translated (interiors disjoint), and the
  /// named features on the two supporting planes.
  static void validResult(const ConvexPolytope& a, const Eigen::Isometry3d& X_WA, const ConvexPolytope& b,
                          const Eigen::Isometry3d& X_WB, const PenetrationResult& r, double tol,
                          std::ostringstream* why) {
    if (r.status != PenetrationStatus::kPenetrating) {
      if (r.depth != 0.0 || r.translation_W != Eigen::Vector3d::Zero()) *why << "nonzero depth or translation";
      return;
    }
    const Eigen::Vector3d& n = r.normal_W;
    if (!n.allFinite() || std::abs(n.norm() - 1.0) > 1e-9 || (r.translation_W - r.depth * n).norm() > 1e-12 * r.depth) {
      *why << "normal not unit or translation != depth * normal";
      return;
    }
    double max_a = -std::numeric_limits<double>::infinity();
    double min_b = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : a.vertices()) max_a = std::max(max_a, n.dot(X_WA * v));
    for (const Eigen::Vector3d& v : b.vertices()) min_b = std::min(min_b, n.dot(X_WB * v + r.translation_W));
    if (max_a > min_b + tol) {
      *why << "translated B still overlaps A along the normal by " << max_a - min_b;
      return;
    }
    auto on = [&](const ConvexPolytope& p, const Eigen::Isometry3d& X, const Feature& f, double level,
                  const Eigen::Vector3d& shift) {
      std::vector<int> vs;
      if (f.type == FeatureType::kVertex) vs = {f.index};
      if (f.type == FeatureType::kEdge) vs = {p.edge(f.index).v0, p.edge(f.index).v1};
      if (f.type == FeatureType::kFace) vs.assign(p.faceVertices(f.index).begin(), p.faceVertices(f.index).end());
      for (int v : vs)
        if (std::abs(n.dot(X * p.vertex(v) + shift) - level) > tol) return false;
      return !vs.empty();
    };
    if (r.facet.kind != FaceOfM::Kind::kNone && (!on(a, X_WA, r.feature_a, max_a, Eigen::Vector3d::Zero()) ||
                                                 !on(b, X_WB, r.feature_b, min_b, r.translation_W))) {
      *why << "features " << toString(r.feature_a.type) << " " << r.feature_a.index << " / "
           << toString(r.feature_b.type) << " " << r.feature_b.index << " are not on the contact plane";
    }
  }

  std::vector<double> deltas_;
  double rel_tol_;
  double shallow_delta_ = 0.1;
};

}  // namespace mddual::testing
