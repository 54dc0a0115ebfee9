// Fuzz target: the polytope builder on raw point sets, then the queries.
//
// Input: text; every number strtod can read (including "nan", "1e400",
// hex floats) is taken in order, three per point, at most kMaxPoints points.
// A polytope that builds is queried against a box of its own size placed
// across its boundary (intersect, mdd and toi along two directions) and every
// answer is compared with the brute force (M built explicitly) where the
// brute force answers. A disagreement beyond 1e-9 of the pair's size (the
// touching side excepted), or an error from the fast query where the brute
// force answers, prints the query as a JSON line and aborts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mddual/brute_force.h"
#include "mddual/error.h"
#include "mddual/penetration.h"
#include "mddual/query.h"
#include "pair.h"

namespace {

constexpr std::size_t kMaxPoints = 64;
constexpr double kRelTol = 1e-9;
// The comparison covers bodies whose edges, and (for solids) whose width,
// are all at least this fraction of their radius. Sharper slivers (features
// within ~1e-12 of the size, which qhull merges or keeps depending on
// round-off) are built and queried, and must not crash, but the fast method
// and the brute force (both on qhull hulls) may then disagree beyond 1e-9:
// the findings (fuzz/findings) were a 1e10-long body with two corners 1e-2
// apart (answers 6% apart) and a 2e9-long tetrahedron 3e-3 thick (answers
// 1.7e-7 of the size apart; in fact flattened, see below).
constexpr double kMinFeatureRel = 1e-6;

bool wellConditioned(const mddual::ConvexPolytope& p) {
  for (int e = 0; e < p.numEdges(); ++e) {
    const mddual::ConvexPolytope::Edge& edge = p.edge(e);
    if ((p.localVertex(edge.v1) - p.localVertex(edge.v0)).norm() < kMinFeatureRel * p.radius()) return false;
  }
  if (p.isFlat()) {
    // Flat within kFlatToleranceRel but not exactly: the polytope's two faces
    // and its vertices disagree by up to that thickness, which a grazing
    // direction amplifies (third finding: 0.2 off-plane on a 2e9 body, mdd
    // 1e-7 of the size apart). Compared only when the corners are coplanar
    // to round-off.
    const Eigen::Vector3d& n = p.faceNormal(0);
    double off = 0.0;
    for (int v = 0; v < p.numVertices(); ++v) {
      off = std::max(off, std::abs(n.dot(p.localVertex(v) - p.localVertex(0))));
    }
    return off <= 1e-14 * p.radius();
  }
  try {
    return mddual::width(mddual::WidthInput{&p}).width >= kMinFeatureRel * p.radius();
  } catch (const mddual::Error&) {
    return false;
  }
}

std::vector<Eigen::Vector3d> parsePoints(const std::string& text) {
  std::vector<double> numbers;
  const char* p = text.c_str();
  const char* end = p + text.size();
  while (p < end && numbers.size() < 3 * kMaxPoints) {
    char* next = nullptr;
    const double x = std::strtod(p, &next);
    if (next == p) {
      ++p;
    } else {
      numbers.push_back(x);
      p = next;
    }
  }
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i + 2 < numbers.size(); i += 3)
    points.emplace_back(numbers[i], numbers[i + 1], numbers[i + 2]);
  return points;
}

[[noreturn]] void finding(const char* what, const mddual::DirectionalInput& in) {
  std::fprintf(stderr, "fuzz_polytope: %s\n  query: %s\n", what, mddual::toJsonLine(in).c_str());
  std::abort();
}

void compare(const mddual::DirectionalInput& in, double tol) {
  using mddual::ContactStatus;
  mddual::MddResult ref;
  mddual::ToiResult ref_toi;
  mddual::IntersectResult ref_x;
  try {
    mddual::BruteForce brute(in.a, in.X_WA, in.b, in.X_WB);
    ref = brute.mdd(in.s_W);
    ref_toi = brute.toi(in.s_W, in.max_distance);
    ref_x = brute.intersect();
  } catch (const mddual::Error&) {
    return;  // the reference has no answer: nothing to compare
  }
  mddual::MddResult fast;
  mddual::ToiResult fast_toi;
  mddual::IntersectResult fast_x;
  try {
    fast = mddual::mdd(in);
    fast_toi = mddual::toi(in);
    fast_x = mddual::intersect(mddual::IntersectInput{in.a, in.X_WA, in.b, in.X_WB});
  } catch (const mddual::Error& e) {
    finding(e.what(), in);
  }
  const bool touching_side = ref.status == ContactStatus::kTouching || fast.status == ContactStatus::kTouching ||
                             std::abs(ref.t_lo) <= tol || std::abs(ref.t_hi) <= tol || ref.t_hi - ref.t_lo <= tol;
  if (fast_x.intersecting != ref_x.intersecting && !touching_side &&
      fast_x.status != mddual::IntersectStatus::kTouching && ref_x.status != mddual::IntersectStatus::kTouching) {
    finding("intersect disagrees with the brute force", in);
  }
  if (touching_side) return;
  if (fast.status != ref.status) finding("mdd status disagrees with the brute force", in);
  if (ref.status != ContactStatus::kNoContact && !(std::abs(fast.distance - ref.distance) <= tol)) {
    finding("mdd disagrees with the brute force", in);
  }
  if (fast_toi.status != ref_toi.status) finding("toi status disagrees with the brute force", in);
  if (std::isfinite(ref_toi.toi) && !(std::abs(fast_toi.toi - ref_toi.toi) <= tol)) {
    finding("toi disagrees with the brute force", in);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<Eigen::Vector3d> points = parsePoints(std::string(reinterpret_cast<const char*>(data), size));
  mddual::ConvexPolytope a;
  try {
    a = mddual::ConvexPolytope::fromPoints(points);
  } catch (const mddual::Error&) {
    return 0;  // rejected with a message: an answer
  }
  // B: a box of A's size, centred on A's boundary region.
  const double r = a.radius();
  const Eigen::Vector3d c = a.centroid() + Eigen::Vector3d(0.7, 0.2, 0.1) * r;
  std::vector<Eigen::Vector3d> box;
  for (int k = 0; k < 8; ++k) {
    box.push_back(c + 0.5 * r * Eigen::Vector3d(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -0.8, k & 4 ? 1.0 : -0.6));
  }
  mddual::ConvexPolytope b;
  try {
    b = mddual::ConvexPolytope::fromPoints(box);
  } catch (const mddual::Error&) {
    return 0;  // A's size at the edge of the supported range
  }
  const bool check = wellConditioned(a);
  for (const Eigen::Vector3d& s : {Eigen::Vector3d(1.0, 0.3, 0.2), Eigen::Vector3d(-0.2, 1.0, 0.5)}) {
    mddual::DirectionalInput in{&a, Eigen::Isometry3d::Identity(), &b, Eigen::Isometry3d::Identity(), s};
    if (!check) {  // queried, compared with nothing
      try {
        (void)mddual::mdd(in);
        (void)mddual::toi(in);
      } catch (const mddual::Error&) {
      }
      continue;
    }
    const mddual::detail::PairGeometry pair(in.a, in.X_WA, in.b, in.X_WB, "fuzz");
    compare(in, kRelTol * pair.scale());
  }
  return 0;
}
