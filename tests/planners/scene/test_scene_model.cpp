// The scene model: AabbTree queries against a brute-force scan, and
// transformedBox (contains the posed corners, and is tight).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mddual/scene/scene.h"

namespace mddual::scene {
namespace {

Eigen::AlignedBox3d randomBox(std::mt19937_64& rng, double extent, double max_size) {
  std::uniform_real_distribution<double> pos(-extent, extent);
  std::uniform_real_distribution<double> size(0.0, max_size);
  const Eigen::Vector3d lo(pos(rng), pos(rng), pos(rng));
  return Eigen::AlignedBox3d(lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng)));
}

TEST(AabbTree, QueryMatchesBruteForceOnRandomBoxes) {
  std::mt19937_64 rng(12345);
  for (const int count : {0, 1, 3, 4, 5, 17, 200, 1000}) {
    std::vector<Eigen::AlignedBox3d> boxes;
    for (int i = 0; i < count; ++i) boxes.push_back(randomBox(rng, 10.0, 2.0));
    const AabbTree tree(boxes);
    EXPECT_EQ(tree.size(), count);
    int hits = 0;
    for (int q = 0; q < 300; ++q) {
      const Eigen::AlignedBox3d query = randomBox(rng, 11.0, q % 3 == 0 ? 6.0 : 1.0);
      std::vector<int> got;
      tree.query(query, &got);
      std::vector<int> want;
      for (int i = 0; i < count; ++i) {
        if (boxes[static_cast<std::size_t>(i)].intersects(query)) want.push_back(i);
      }
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, want) << count << " boxes, query " << q;
      hits += static_cast<int>(want.size());
    }
    if (count >= 200) {
      EXPECT_GT(hits, 100) << "the sample should produce hits";
    }
  }
}

TEST(AabbTree, TouchingBoxesCount) {
  const std::vector<Eigen::AlignedBox3d> boxes = {
      Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)),
      Eigen::AlignedBox3d(Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(4, 1, 1))};
  const AabbTree tree(boxes);
  std::vector<int> got;
  tree.query(Eigen::AlignedBox3d(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 2, 2)), &got);
  EXPECT_EQ(got, std::vector<int>{0});
  got.clear();
  tree.query(Eigen::AlignedBox3d(Eigen::Vector3d(1.5, 0, 0), Eigen::Vector3d(2.5, 1, 1)), &got);
  EXPECT_TRUE(got.empty());
  Eigen::AlignedBox3d empty;
  empty.setEmpty();
  tree.query(empty, &got);
  EXPECT_TRUE(got.empty());
}

TEST(TransformedBox, ContainsThePosedCornersAndIsTight) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::AlignedBox3d box = randomBox(rng, 5.0, 3.0);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10.0;
    const Eigen::AlignedBox3d out = transformedBox(box, X);
    Eigen::AlignedBox3d corners_box;
    corners_box.setEmpty();
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner = X * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      EXPECT_TRUE(out.exteriorDistance(corner) <= 1e-12) << "corner " << c << " outside";
      corners_box.extend(corner);
    }
    // Tight: the box of the posed corners is the smallest box holding them.
    EXPECT_LE((out.min() - corners_box.min()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((out.max() - corners_box.max()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(RigidBody, RejectsNoPiecesAndComputesBounds) {
  EXPECT_THROW(RigidBody({}, "empty"), SceneError);
  std::vector<Eigen::Vector3d> points = {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}, {1, 2, 3}};
  std::vector<Piece> pieces;
  pieces.push_back(Piece::make(ConvexPolytope::fromPoints(points), PieceKind::kConvex, "p"));
  const RigidBody body(std::move(pieces), "b");
  EXPECT_DOUBLE_EQ(body.radius(), std::sqrt(14.0));
  EXPECT_TRUE(body.box().min().isApprox(Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(body.box().max().isApprox(Eigen::Vector3d(1, 2, 3)));
}

}  // namespace
}  // namespace mddual::scene
