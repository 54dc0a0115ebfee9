// Bvh: the volumes' containment invariant, every traversal against a brute
// force over all pieces or pairs on seeded random piece sets (identical
// candidate sets, identical first contacts), degenerate inputs (one piece,
// coincident pieces, flat triangles, points) and bad input. The volume tests
// (separating axes, casts, swept sphere, triangle against box) are in
// test_bvh_volumes.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "family_support.h"
#include "mddual/bvh.h"
#include "mddual/distance.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/query.h"

namespace mddual {
namespace {

using generators::Rng;
using testing::uniform;
using testing::uniformVector;
using Points = std::vector<Eigen::Vector3d>;
constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Isometry3d randomPose(Rng& rng, double spread) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = generators::randomRotation(rng);
  X.translation() = generators::drawVector(std::uniform_real_distribution<double>(-spread, spread), rng);
  return X;
}

/// A random set: small blobs and triangles (some large and thin) in a cube.
std::vector<Points> randomPieces(Rng& rng, int n, double spread) {
  std::vector<Points> out;
  for (int k = 0; k < n; ++k) {
    const Eigen::Isometry3d X = randomPose(rng, spread);
    Points p;
    // The last argument's draws first: the order GCC evaluated the arguments
    // (C++ leaves it unspecified), kept so the seeded pieces stay as they were.
    if (k % 3 == 0) {
      const double s = uniform(rng, 0.1, 2.0);
      const double y = s * uniform(rng, 0.05, 1.0);
      const double x = s * uniform(rng, 0.2, 3.0);
      p = generators::triangle({0, 0, 0}, {x, 0, 0}, {0, y, 0});
    } else {
      const Eigen::Vector3d semi_axes = uniformVector(rng, 0.1, 0.8);
      const int n_points = std::uniform_int_distribution<int>(6, 14)(rng);
      p = generators::blob(n_points, semi_axes, rng);
    }
    for (Eigen::Vector3d& v : p) v = X * v;
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<ConvexPolytope> polytopes(const std::vector<Points>& pieces) {
  std::vector<ConvexPolytope> out;
  for (const Points& p : pieces) out.push_back(ConvexPolytope::fromPoints(p));
  return out;
}

/// The brute force's pairs (i, j) whose pieces intersect, B's pieces posed at X_WB.
std::set<std::pair<int, int>> intersectingPairs(const std::vector<ConvexPolytope>& ca,
                                                const std::vector<ConvexPolytope>& cb, const Eigen::Isometry3d& X_WB) {
  std::set<std::pair<int, int>> out;
  for (std::size_t i = 0; i < ca.size(); ++i) {
    for (std::size_t j = 0; j < cb.size(); ++j) {
      IntersectInput in;
      in.a = &ca[i];
      in.b = &cb[j];
      in.X_WB = X_WB;
      if (intersect(in).intersecting) out.emplace(static_cast<int>(i), static_cast<int>(j));
    }
  }
  return out;
}

/// Checks that every node's volumes hold its pieces' points, that boxes hold
/// their children's boxes, and the tree's bookkeeping.
void expectInvariants(const Bvh& t, const std::vector<Points>& pieces) {
  ASSERT_EQ(t.numPieces(), static_cast<int>(pieces.size()));
  ASSERT_EQ(t.numNodes(), 2 * t.numPieces() - 1);
  std::vector<int> seen(pieces.size(), 0);
  for (int n = 0; n < t.numNodes(); ++n) {
    const Bvh::Node& node = t.node(n);
    for (int k = node.first; k < node.first + node.count; ++k) {
      for (const Eigen::Vector3d& p : pieces[static_cast<std::size_t>(t.pieceAt(k))]) {
        EXPECT_TRUE(node.box.contains(p));
        EXPECT_TRUE(node.obb.contains(p, 0.0)) << "node " << n;
        EXPECT_LE((p - node.centre).norm(), node.radius);
        EXPECT_LE(p.norm(), node.max_norm);
      }
    }
    if (node.isLeaf()) {
      ASSERT_EQ(node.count, 1);
      const int piece = t.leafPiece(n);
      ++seen[static_cast<std::size_t>(piece)];
      EXPECT_EQ(t.leafOf(piece), n);
      continue;
    }
    const Bvh::Node& l = t.node(node.left);
    const Bvh::Node& r = t.node(node.right);
    EXPECT_EQ(node.count, l.count + r.count);
    EXPECT_EQ(l.first, node.first);
    EXPECT_EQ(r.first, node.first + l.count);
    for (const Bvh::Node* c : {&l, &r}) {
      EXPECT_TRUE(node.box.contains(c->box));
      EXPECT_LE(c->max_norm, node.max_norm);
    }
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

TEST(Bvh, VolumesHoldTheirPieces) {
  Rng rng(1);
  for (int n : {1, 2, 3, 17, 200}) {
    const std::vector<Points> pieces = randomPieces(rng, n, 10.0);
    const Bvh t(pieces);
    SCOPED_TRACE(n);
    expectInvariants(t, pieces);
    // A median split keeps the tree balanced.
    EXPECT_LE(t.height(), static_cast<int>(std::ceil(std::log2(n))) + 1);
  }
}

TEST(Bvh, HullsContainTheirPiecesAndBoundEveryPairBelow) {
  Rng rng(2);
  const std::vector<Points> pieces = randomPieces(rng, 60, 5.0);
  BvhOptions options;
  options.hull_max_pieces = 8;
  const Bvh t(pieces, options);
  ASSERT_GT(t.numHulls(), 0);
  for (int n = 0; n < t.numNodes(); ++n) {
    const Bvh::Node& node = t.node(n);
    const ConvexPolytope* h = t.hull(n);
    if (node.isLeaf() || node.count > 8) {
      EXPECT_EQ(h, nullptr);
      continue;
    }
    ASSERT_NE(h, nullptr);
    for (int k = node.first; k < node.first + node.count; ++k) {
      for (const Eigen::Vector3d& p : pieces[static_cast<std::size_t>(t.pieceAt(k))]) {
        double worst = -kInf;
        for (int f = 0; f < h->numFaces(); ++f) worst = std::max(worst, h->faceNormal(f).dot(p) - h->faceOffset(f));
        EXPECT_LE(worst, 1e-9);
      }
    }
  }
  // The toi of two hulls is at most the toi of any pair of pieces below them.
  const std::vector<ConvexPolytope> pieces_c = polytopes(pieces);
  int checked = 0;
  int finite = 0;  // some pair of pieces below hits: where the bound says something
  const auto centre = [](const ConvexPolytope& p) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : p.vertices()) c += v;
    return Eigen::Vector3d(c / p.numVertices());
  };
  for (int q = 0; q < 40; ++q) {
    Eigen::Isometry3d X = randomPose(rng, 6.0);
    const Eigen::Vector3d jitter = generators::randomUnitVector(rng);
    const int na = std::uniform_int_distribution<int>(0, t.numNodes() - 1)(rng);
    const int nb = std::uniform_int_distribution<int>(0, t.numNodes() - 1)(rng);
    if (!t.hull(na) || !t.hull(nb)) continue;
    // B moves towards A (centre to centre, give or take a tenth), so that
    // pairs of pieces below them meet: else both sides are infinite.
    const Eigen::Vector3d u = centre(*t.hull(na)) - X * centre(*t.hull(nb)) + 0.1 * jitter;
    DirectionalInput in;
    in.a = t.hull(na);
    in.b = t.hull(nb);
    in.X_WB = X;
    in.s_W = u;
    const ToiResult hull = toi(in);
    double below = kInf;
    for (int i = t.node(na).first; i < t.node(na).first + t.node(na).count; ++i) {
      for (int j = t.node(nb).first; j < t.node(nb).first + t.node(nb).count; ++j) {
        in.a = &pieces_c[static_cast<std::size_t>(t.pieceAt(i))];
        in.b = &pieces_c[static_cast<std::size_t>(t.pieceAt(j))];
        const ToiResult r = toi(in);
        if (r.status != ToiStatus::kNever) below = std::min(below, r.toi);
      }
    }
    EXPECT_LE(hull.toi, below + 1e-9);
    ++checked;
    finite += std::isfinite(below) ? 1 : 0;
  }
  EXPECT_GT(checked, 5);
  EXPECT_GE(finite, 5);  // 7 of the 9 checked
}

TEST(Bvh, BoxAndObbQueriesAgainstABruteForce) {
  Rng rng(3);
  const std::vector<Points> pieces = randomPieces(rng, 150, 10.0);
  const std::vector<ConvexPolytope> pieces_c = polytopes(pieces);
  const Bvh t(pieces);
  int found = 0;
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3d c = generators::drawVector(std::uniform_real_distribution<double>(-11, 11), rng);
    const Eigen::Vector3d h = generators::drawVector(std::uniform_real_distribution<double>(0.01, 4), rng);
    const Eigen::AlignedBox3d box(c - h, c + h);
    std::set<int> tree, brute;
    EXPECT_TRUE(t.queryBox(box, [&](int p) { return tree.insert(p).second; }));
    for (int p = 0; p < t.numPieces(); ++p) {
      if (t.node(t.leafOf(p)).box.intersects(box)) brute.insert(p);
    }
    EXPECT_EQ(tree, brute);
    Obb obb;
    obb.centre_F = c;
    obb.axes_F = generators::randomRotation(rng);
    obb.half = h;
    tree.clear();
    brute.clear();
    EXPECT_TRUE(t.queryObb(obb, [&](int p) { return tree.insert(p).second; }));
    // Some of the pieces whose leaf boxes meet it; those left out are
    // disjoint from it (an ancestor's box, which holds them, is).
    const auto corners = obb.corners();
    const ConvexPolytope query = ConvexPolytope::fromPoints(Points(corners.begin(), corners.end()));
    for (int p = 0; p < t.numPieces(); ++p) {
      if (!obbsDisjoint(t.node(t.leafOf(p)).obb, obb)) brute.insert(p);
    }
    for (int p : tree) EXPECT_EQ(brute.count(p), 1u);
    for (int p : brute) {
      if (tree.count(p)) continue;
      IntersectInput in;
      in.a = &query;
      in.b = &pieces_c[static_cast<std::size_t>(p)];
      EXPECT_FALSE(intersect(in).intersecting) << "piece " << p << " left out but meets the box";
    }
    found += static_cast<int>(tree.size());
  }
  EXPECT_GT(found, 100);
}

/// Brute force of forEachOverlappingPair's candidate set.
std::set<std::pair<int, int>> bruteCandidates(const Bvh& a, const Bvh& b, const Eigen::Isometry3d& X_AB, double m) {
  std::set<std::pair<int, int>> out;
  for (int i = 0; i < a.numPieces(); ++i) {
    const Bvh::Node& A = a.node(a.leafOf(i));
    for (int j = 0; j < b.numPieces(); ++j) {
      const Bvh::Node& B = b.node(b.leafOf(j));
      const double r = A.radius + B.radius + m;
      if ((A.centre - X_AB * B.centre).norm() > r * (1 + 1e-9)) continue;
      if (obbsDisjoint(A.obb, B.obb.transformed(X_AB, m))) continue;
      out.emplace(i, j);
    }
  }
  return out;
}

TEST(Bvh, TreeAgainstTreeFindsEveryIntersectingPairAmongTheBruteForceCandidates) {
  Rng rng(4);
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<Points> pa = randomPieces(rng, 120, 6.0), pb = randomPieces(rng, 40, 2.0);
    const Bvh a(pa), b(pb);
    const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
    std::set<std::pair<int, int>> without_margin;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    for (int q = 0; q < 6; ++q) {
      // Pairs of queries at one pose, without and with a margin.
      if (q % 2 == 0) X = randomPose(rng, 4.0);
      const double margin = q % 2 == 0 ? 0.0 : 0.3;
      std::set<std::pair<int, int>> tree;
      BvhStats stats;
      EXPECT_TRUE(forEachOverlappingPair(
          a, b, X, margin, [&](int i, int j) { return tree.emplace(i, j).second; }, &stats));
      // Some of the pairs whose leaf volumes overlap (brute force); those
      // left out are pairs of disjoint pieces (an ancestor pair's volumes,
      // which hold the pieces, are disjoint). With a margin, every pair found
      // without it (grown volumes hold the others).
      const std::set<std::pair<int, int>> brute = bruteCandidates(a, b, X, margin);
      for (const auto& p : tree) EXPECT_EQ(brute.count(p), 1u);
      EXPECT_GT(tree.size(), 0u);
      if (margin == 0.0) {
        for (const auto& [i, j] : brute) {
          if (tree.count({i, j})) continue;
          IntersectInput in;
          in.a = &ca[static_cast<std::size_t>(i)];
          in.b = &cb[static_cast<std::size_t>(j)];
          in.X_WB = X;
          EXPECT_FALSE(intersect(in).intersecting) << "pair " << i << ", " << j << " left out but intersecting";
        }
        without_margin = tree;
      } else {
        for (const auto& p : without_margin) EXPECT_EQ(tree.count(p), 1u);
      }
      EXPECT_EQ(stats.leaf_pairs, static_cast<int>(tree.size()));
      // Fewer node tests than the brute force's pair tests.
      EXPECT_LT(stats.node_pairs, static_cast<int>(pa.size() * pb.size()));
      for (const auto& [i, j] : intersectingPairs(ca, cb, X)) {
        EXPECT_EQ(tree.count({i, j}), 1u) << "missed pair " << i << ", " << j;
      }
    }
  }
}

TEST(Bvh, TreeAgainstTreeStopsWhenTheCallbackSaysSo) {
  Rng rng(5);
  const std::vector<Points> pa = randomPieces(rng, 80, 3.0);
  const Bvh a(pa);
  int calls = 0;
  EXPECT_FALSE(forEachOverlappingPair(a, a, Eigen::Isometry3d::Identity(), 0.0, [&](int, int) { return ++calls < 3; }));
  EXPECT_EQ(calls, 3);
}

/// The toi of one pair, as the leaf of a cast (independent of the limit so
/// that the brute force compares exactly).
struct ToiLeaf {
  const std::vector<ConvexPolytope>* a;
  const std::vector<ConvexPolytope>* b;
  Eigen::Isometry3d X_AB;
  Eigen::Vector3d u;
  double max_distance;
  double operator()(int i, int j) const {
    DirectionalInput in;
    in.a = &(*a)[static_cast<std::size_t>(i)];
    in.b = &(*b)[static_cast<std::size_t>(j)];
    in.X_WB = X_AB;
    in.s_W = u;
    in.max_distance = max_distance;
    const ToiResult r = toi(in);
    return r.status == ToiStatus::kNever ? kInf : r.toi;
  }
};

TEST(Bvh, CastFindsTheBruteForceFirstContact) {
  Rng rng(6);
  int hits = 0, misses = 0, starts = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const std::vector<Points> pa = randomPieces(rng, 100, 6.0), pb = randomPieces(rng, 25, 1.5);
    const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
    for (int hull_cap : {0, 8}) {
      BvhOptions options;
      options.hull_max_pieces = hull_cap;
      const Bvh a(pa, options), b(pb, options);
      for (int q = 0; q < 6; ++q) {
        const Eigen::Isometry3d X = randomPose(rng, 9.0);
        // Toward the other set mostly, in any direction sometimes.
        const Eigen::Vector3d u = q % 2 == 0
                                      ? Eigen::Vector3d(-X.translation() + 3.0 * generators::randomUnitVector(rng))
                                      : generators::randomUnitVector(rng);
        const double max_distance = q % 3 == 0 ? kInf : uniform(rng, 2.0, 15.0);
        const ToiLeaf leaf{&ca, &cb, X, u, max_distance};
        double brute = kInf;
        for (int i = 0; i < a.numPieces(); ++i) {
          for (int j = 0; j < b.numPieces(); ++j) brute = std::min(brute, leaf(i, j));
        }
        if (!(brute <= max_distance)) brute = kInf;
        BvhStats stats;
        const CastHit hit = castFirst(
            a, b, X, u, max_distance, [&](int i, int j, double) { return leaf(i, j); }, CastOptions(), &stats);
        EXPECT_EQ(hit.distance, brute) << "trial " << trial << " query " << q << " hulls " << hull_cap;
        if (std::isfinite(brute)) {
          EXPECT_EQ(leaf(hit.piece_a, hit.piece_b), brute);
          ++(brute == 0.0 ? starts : hits);
        } else {
          ++misses;
          EXPECT_EQ(hit.piece_a, -1);
        }
        EXPECT_LT(stats.leaf_pairs, a.numPieces() * b.numPieces());
        if (hull_cap == 0) {
          EXPECT_EQ(stats.hull_queries, 0);
        }
        // Any contact: found exactly when there is one.
        CastOptions any;
        any.first_contact = false;
        const CastHit first = castFirst(
            a, b, X, u, max_distance, [&](int i, int j, double) { return leaf(i, j); }, any);
        EXPECT_EQ(std::isfinite(first.distance), std::isfinite(brute));
        if (std::isfinite(first.distance)) {
          EXPECT_GE(first.distance, brute);
          EXPECT_EQ(leaf(first.piece_a, first.piece_b), first.distance);
        }
      }
    }
  }
  // The draws cover all three outcomes.
  EXPECT_GT(hits, 10);
  EXPECT_GT(misses, 5);
  EXPECT_GT(starts, 0);
}

TEST(Bvh, CastStoppedWithinAToleranceBracketsTheBruteForceFirstContact) {
  // stop_within w: the first contact lies in [lower_bound, distance], no
  // longer than w, distance a pair's contact; w = 0 gives the exact one.
  // Flat contacts (many pairs touching at nearly the same distance) are
  // where the stop saves leaf calls: a slab of pieces against a slab.
  Rng rng(61);
  int stopped_early = 0, contacts = 0;
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<Points> pa = randomPieces(rng, 120, 6.0), pb = randomPieces(rng, 30, 1.5);
    for (Points& p : pa) {
      for (Eigen::Vector3d& v : p) v.z() *= 0.05;  // a thin slab in z = 0
    }
    const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
    const Bvh a(pa), b(pb);
    for (int q = 0; q < 6; ++q) {
      Eigen::Isometry3d X = randomPose(rng, 3.0);
      X.translation().z() = uniform(rng, 3.0, 6.0);
      const Eigen::Vector3d u = -Eigen::Vector3d::UnitZ() + 0.2 * generators::randomUnitVector(rng);
      const ToiLeaf leaf{&ca, &cb, X, u, kInf};
      double brute = kInf;
      for (int i = 0; i < a.numPieces(); ++i) {
        for (int j = 0; j < b.numPieces(); ++j) brute = std::min(brute, leaf(i, j));
      }
      for (const double w : {0.0, 0.05, 0.5}) {
        CastOptions options;
        options.stop_within = w;
        BvhStats stats, exact_stats;
        const auto fn = [&](int i, int j, double) { return leaf(i, j); };
        const CastHit hit = castFirst(a, b, X, u, kInf, fn, options, &stats);
        castFirst(a, b, X, u, kInf, fn, CastOptions(), &exact_stats);
        const std::string where = "trial " + std::to_string(trial) + " query " + std::to_string(q) + " w " +
                                  std::to_string(w) + " brute " + std::to_string(brute);
        if (!std::isfinite(brute)) {
          EXPECT_EQ(hit.distance, kInf) << where;
          EXPECT_EQ(hit.lower_bound, kInf) << where;
          continue;
        }
        ++contacts;
        EXPECT_EQ(leaf(hit.piece_a, hit.piece_b), hit.distance) << where;
        EXPECT_LE(hit.lower_bound, brute) << where;
        EXPECT_GE(hit.distance, brute) << where;
        EXPECT_LE(hit.distance - hit.lower_bound, w) << where;
        if (w == 0.0) {
          EXPECT_EQ(hit.distance, brute) << where;
          EXPECT_EQ(hit.lower_bound, brute) << where;
        }
        EXPECT_LE(stats.leaf_pairs, exact_stats.leaf_pairs) << where;
        stopped_early += stats.leaf_pairs < exact_stats.leaf_pairs;
      }
    }
  }
  // Not a degenerate sample: contacts, and stops that saved leaf calls.
  EXPECT_GT(contacts, 60);
  EXPECT_GT(stopped_early, 10);
}

TEST(Bvh, CastWithAMarginCallsEveryPairItWouldCallWithoutAndMore) {
  // A leaf that reports no contact sees every pair the cast cannot rule out:
  // with a margin, a superset of the pairs seen without one, which include
  // every pair that intersects at the start. Several poses, so that the guard
  // below holds whatever order a compiler draws a pose's numbers in.
  Rng rng(7);
  const std::vector<Points> pa = randomPieces(rng, 60, 4.0), pb = randomPieces(rng, 10, 1.0);
  const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
  const Bvh a(pa), b(pb);
  int intersecting = 0, margin_added = 0;
  for (int pose = 0; pose < 16; ++pose) {
    const Eigen::Isometry3d X = randomPose(rng, 2.0);
    const std::string where = "pose " + std::to_string(pose);
    const auto seenWith = [&](double margin) {
      CastOptions options;
      options.margin_b = margin;
      std::set<std::pair<int, int>> seen;
      const CastHit hit = castFirst(
          a, b, X, Eigen::Vector3d::UnitX(), 1.0,
          [&](int i, int j, double) {
            seen.emplace(i, j);
            return kInf;
          },
          options);
      EXPECT_EQ(hit.distance, kInf) << where;
      return seen;
    };
    const std::set<std::pair<int, int>> without = seenWith(0.0), with = seenWith(0.5);
    for (const auto& p : without) EXPECT_EQ(with.count(p), 1u) << where;
    margin_added += with.size() > without.size();
    for (const auto& [i, j] : intersectingPairs(ca, cb, X)) {
      ++intersecting;
      EXPECT_EQ(without.count({i, j}), 1u) << where << ", pair " << i << " " << j;
    }
  }
  // Not a degenerate sample: pairs that intersect at the start, and poses
  // where the margin brought in more pairs.
  EXPECT_GT(intersecting, 4);
  EXPECT_GT(margin_added, 8);
}

TEST(Bvh, NearestPairFindsTheBruteForceSmallestSignedDistance) {
  // nearestPair with the core's signed distance at the leaves against the
  // minimum over every pair: the same value (the same function on the
  // pair that attains it), apart and overlapping, with and without an upper
  // bound, and fewer leaf calls than pairs.
  Rng rng(61);
  int apart = 0, overlapping = 0;
  long long leaf_calls = 0, all_pairs = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const std::vector<Points> pa = randomPieces(rng, 80, 5.0), pb = randomPieces(rng, 20, 1.5);
    const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
    const Bvh a(pa), b(pb);
    for (int q = 0; q < 8; ++q) {
      // Inside set a's cube half the time (overlaps), anywhere near it else.
      const Eigen::Isometry3d X = randomPose(rng, q % 2 == 0 ? 3.0 : 12.0);
      const auto value = [&](int i, int j) {
        DistanceInput in;
        in.a = &cb[static_cast<std::size_t>(j)];
        in.X_WA = X;
        in.b = &ca[static_cast<std::size_t>(i)];
        return distance(in).distance;
      };
      double brute = kInf;
      for (int i = 0; i < a.numPieces(); ++i) {
        for (int j = 0; j < b.numPieces(); ++j) brute = std::min(brute, value(i, j));
      }
      int calls = 0;
      const NearestHit hit = nearestPair(a, b, X, [&](int i, int j, double) {
        ++calls;
        return value(i, j);
      });
      std::ostringstream where;
      where << "trial " << trial << " query " << q;
      EXPECT_EQ(hit.value, brute) << where.str();
      EXPECT_EQ(value(hit.piece_a, hit.piece_b), brute) << where.str();
      ++(brute < 0.0 ? overlapping : apart);
      leaf_calls += calls;
      all_pairs += static_cast<long long>(a.numPieces()) * b.numPieces();
      // An upper bound: pairs at or above it are not reported.
      EXPECT_EQ(nearestPair(
                    a, b, X, [&](int i, int j, double) { return value(i, j); }, brute)
                    .piece_a,
                -1)
          << where.str();
      EXPECT_EQ(nearestPair(
                    a, b, X, [&](int i, int j, double) { return value(i, j); }, brute + 1.0)
                    .value,
                brute)
          << where.str();
    }
  }
  // Both signs occur, and the bounds prune (most pairs never reach the core).
  EXPECT_GT(apart, 10);
  EXPECT_GT(overlapping, 10);
  EXPECT_LT(leaf_calls, all_pairs / 4);
  // A leaf callback that runs another nearestPair (on other trees): both
  // answer as they do alone.
  {
    const std::vector<Points> pa = randomPieces(rng, 40, 4.0), pb = randomPieces(rng, 10, 1.0);
    const std::vector<ConvexPolytope> ca = polytopes(pa), cb = polytopes(pb);
    const Bvh a(pa), b(pb);
    const Eigen::Isometry3d X = randomPose(rng, 3.0), Y = randomPose(rng, 3.0);
    const auto value = [&](const Eigen::Isometry3d& pose, int i, int j) {
      DistanceInput in;
      in.a = &cb[static_cast<std::size_t>(j)];
      in.X_WA = pose;
      in.b = &ca[static_cast<std::size_t>(i)];
      return distance(in).distance;
    };
    const double alone_x = nearestPair(a, b, X, [&](int i, int j, double) { return value(X, i, j); }).value;
    const double alone_y = nearestPair(b, a, Y.inverse(), [&](int j, int i, double) { return value(Y, i, j); }).value;
    int nested = 0;
    const NearestHit outer = nearestPair(a, b, X, [&](int i, int j, double) {
      const NearestHit inner = nearestPair(b, a, Y.inverse(), [&](int jj, int ii, double) { return value(Y, ii, jj); });
      EXPECT_EQ(inner.value, alone_y);
      ++nested;
      return value(X, i, j);
    });
    EXPECT_EQ(outer.value, alone_x);
    EXPECT_GT(nested, 0);
  }
  // Bad input.
  const Bvh t(randomPieces(rng, 4, 1.0));
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = std::nan("");
  const auto none = [](int, int, double) { return 0.0; };
  EXPECT_THROW(nearestPair(t, t, nan_pose, none), InvalidInputError);
  EXPECT_THROW(nearestPair(t, t, Eigen::Isometry3d::Identity(), none, std::nan("")), InvalidInputError);
  EXPECT_EQ(nearestPair(Bvh(), t, Eigen::Isometry3d::Identity(), none).piece_a, -1);
  EXPECT_EQ(nearestPair(t, Bvh(), Eigen::Isometry3d::Identity(), none).piece_a, -1);
  EXPECT_EQ(nearestPair(t, t, Eigen::Isometry3d::Identity(), none, -kInf).piece_a, -1);  // nothing below -inf
}

TEST(Bvh, DegenerateInputs) {
  // One piece: the root is a leaf.
  const Bvh one({generators::box({1, 1, 1})});
  EXPECT_EQ(one.numNodes(), 1);
  EXPECT_EQ(one.height(), 0);
  EXPECT_TRUE(one.node(0).isLeaf());
  int calls = 0;
  forEachOverlappingPair(one, one, Eigen::Isometry3d::Identity(), 0.0, [&](int, int) { return ++calls > 0; });
  EXPECT_EQ(calls, 1);
  // Coincident pieces: all found, the tree still balanced.
  const Points tri = generators::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const std::vector<Points> same(33, tri);
  const Bvh coincident(same);
  expectInvariants(coincident, same);
  EXPECT_LE(coincident.height(), 6);
  std::set<int> found;
  coincident.queryBox(Eigen::AlignedBox3d(Eigen::Vector3d(0.2, 0.2, -0.1), Eigen::Vector3d(0.3, 0.3, 0.1)),
                      [&](int p) { return found.insert(p).second; });
  EXPECT_EQ(found.size(), 33u);
  // Flat triangles in one plane (a floor): flat boxes, and a cast down onto it.
  std::vector<Points> floor;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      floor.push_back(generators::triangle({1.0 * i, 1.0 * j, 0}, {i + 1.0, 1.0 * j, 0}, {1.0 * i, j + 1.0, 0}));
      floor.push_back(generators::triangle({i + 1.0, 1.0 * j, 0}, {i + 1.0, j + 1.0, 0}, {1.0 * i, j + 1.0, 0}));
    }
  }
  BvhOptions hulls;
  hulls.hull_max_pieces = 16;  // flat hulls
  const Bvh flat(floor, hulls);
  expectInvariants(flat, floor);
  EXPECT_GT(flat.numHulls(), 0);
  for (int n = 0; n < flat.numNodes(); ++n) EXPECT_LE(flat.node(n).obb.half.minCoeff(), 1e-9);
  const std::vector<ConvexPolytope> cf = polytopes(floor);
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({0.3, 0.3, 0.3}));
  const Bvh robot({cube.vertices()}, hulls);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(4.4, 5.7, 2.0);
  const CastHit hit = castFirst(flat, robot, X, -Eigen::Vector3d::UnitZ(), kInf, [&](int i, int, double limit) {
    DirectionalInput in;
    in.a = &cf[static_cast<std::size_t>(i)];
    in.b = &cube;
    in.X_WB = X;
    in.s_W = -Eigen::Vector3d::UnitZ();
    in.max_distance = limit;
    const ToiResult r = toi(in);
    return r.status == ToiStatus::kNever ? kInf : r.toi;
  });
  EXPECT_NEAR(hit.distance, 1.7, 1e-12);
  // Collinear and single-point pieces on one line: volumes, but no hull (not
  // a polytope), and no error.
  const std::vector<Points> thin{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{2.5, 0, 0}}, {{3, 0, 0}, {4, 0, 0}}};
  const Bvh odd(thin, hulls);
  expectInvariants(odd, thin);
  EXPECT_EQ(odd.numHulls(), 0);
}

TEST(Bvh, ACallbackMayRunAnotherTraversal) {
  Rng rng(9);
  const std::vector<Points> pa = randomPieces(rng, 50, 3.0);
  const Bvh a(pa);
  int outer = 0, inner = 0;
  forEachOverlappingPair(a, a, Eigen::Isometry3d::Identity(), 0.0, [&](int i, int) {
    ++outer;
    a.queryBox(a.node(a.leafOf(i)).box, [&](int) { return ++inner > 0; });
    return outer < 20;
  });
  EXPECT_EQ(outer, 20);
  EXPECT_GE(inner, 20);
}

/// A tree-against-tree traversal nested in another's callback, on the same
/// trees at another pose: each finds the pairs it finds alone (the outer one's
/// posed nodes, cached per query in two stages, survive the inner query).
TEST(Bvh, NestedTreeAgainstTreeTraversalsKeepTheirOwnPoses) {
  Rng rng(12);
  const std::vector<Points> pa = randomPieces(rng, 60, 3.0), pb = randomPieces(rng, 30, 1.5);
  const Bvh a(pa), b(pb);
  using Pairs = std::set<std::pair<int, int>>;
  const auto alone = [&](const Eigen::Isometry3d& X) {
    Pairs out;
    forEachOverlappingPair(a, b, X, 0.0, [&](int i, int j) { return out.emplace(i, j).second; });
    return out;
  };
  int nested_calls = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::Isometry3d X_outer = randomPose(rng, 2.0);
    const Eigen::Isometry3d X_inner = randomPose(rng, 2.0);
    const Pairs want_outer = alone(X_outer), want_inner = alone(X_inner);
    Pairs outer;
    forEachOverlappingPair(a, b, X_outer, 0.0, [&](int i, int j) {
      outer.emplace(i, j);
      Pairs inner;
      forEachOverlappingPair(a, b, X_inner, 0.0, [&](int k, int l) { return inner.emplace(k, l).second; });
      EXPECT_EQ(inner, want_inner) << "trial " << trial;
      ++nested_calls;
      return true;
    });
    EXPECT_EQ(outer, want_outer) << "trial " << trial;
  }
  EXPECT_GE(nested_calls, 20);  // not a degenerate sample: the outer traversals reached pairs
}

TEST(Bvh, BadInputIsReportedByPieceAndPoint) {
  const auto expectMessage = [](const auto& f, const std::string& part) {
    try {
      f();
      ADD_FAILURE() << "no error; expected one mentioning '" << part << "'";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expectMessage([] { Bvh({generators::box({1, 1, 1}), {}}); }, "piece 1 has no points");
  expectMessage([] { Bvh({{{0, 0, 0}, {1, std::nan(""), 0}}}); }, "piece 0, point 1");
  BvhOptions negative;
  negative.hull_max_pieces = -1;
  expectMessage([&] { Bvh({generators::box({1, 1, 1})}, negative); }, "hull_max_pieces");
  const ConvexPolytope cube = ConvexPolytope::fromPoints(generators::box({1, 1, 1}));
  expectMessage([&] { Bvh::fromPolytopes({&cube, nullptr}); }, "polytope 1 is null");
  expectMessage(
      [&] {
        Bvh::fromPolytopes({&cube}, {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()});
      },
      "2 poses for 1 polytopes");
  const Bvh t = Bvh::fromPolytopes({&cube});
  const auto none = [](int, int, double) { return kInf; };
  expectMessage([&] { castFirst(t, t, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(), 1.0, none); },
                "must be finite and nonzero");
  // A NaN or scaled pose failed every volume test: no pair and no contact,
  // where the answer overlaps everything (hostile-input hunt).
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().y() = std::nan("");
  expectMessage([&] { castFirst(t, t, nan_pose, Eigen::Vector3d::UnitX(), 1.0, none); }, "non-finite translation");
  expectMessage([&] { forEachOverlappingPair(t, t, nan_pose, 0.0, [](int, int) { return true; }); },
                "non-finite translation");
  expectMessage(
      [&] {
        t.queryBox(Eigen::AlignedBox3d(Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d(1, 1, 1)),
                   [](int) { return true; });
      },
      "NaN corner");
  int unbounded = 0;  // an infinite box is an unbounded query, not an error
  t.queryBox(Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf)), [&](int) {
    ++unbounded;
    return true;
  });
  EXPECT_EQ(unbounded, 1);
  // Directions whose norm under- or overflows are directions all the same.
  Eigen::Isometry3d apart = Eigen::Isometry3d::Identity();
  apart.translation().x() = -5.0;
  const auto first = [&](int, int, double limit) { return limit < 3.0 ? limit : 3.0; };
  for (const double size : {1e-170, 1.0, 1e200}) {
    EXPECT_EQ(castFirst(t, t, apart, Eigen::Vector3d(size, 0, 0), 10.0, first).distance, 3.0) << size;
  }
  expectMessage([&] { castFirst(t, t, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), -1.0, none); },
                "max_distance");
  for (const double w : {-1.0, std::nan("")}) {
    CastOptions options;
    options.stop_within = w;
    expectMessage([&] { castFirst(t, t, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), 1.0, none, options); },
                  "stop_within");
  }
  expectMessage(
      [&] { forEachOverlappingPair(t, t, Eigen::Isometry3d::Identity(), -1.0, [](int, int) { return true; }); },
      "margin_b");
  // Empty sets: nothing to visit.
  const Bvh empty(std::vector<Points>{});
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.root(), -1);
  EXPECT_EQ(castFirst(empty, t, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), 1.0, none).distance, kInf);
}

}  // namespace
}  // namespace mddual
