// The rotating-edge scheme's robot volumes (mdd_scene_rotation.cpp):
// rotationSweptBox (a box grown across the rotation axis) and partSweep (a
// part's motion over a time interval as a straight sweep plus a growth, the
// arc or the chord of the header's argument), each against the true rotated
// points of OMPL's interpolation model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "mddual/generators.h"
#include "mddual/planning/mdd_scene.h"
#include "mddual/scene/loaders.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

using testing::kInf;

/// mdd_scene_rotation.cpp's kGrowthSafety and kSlerpRoundoffRel (file-local
/// there): the growth's safety factor 1 + this, and the round-off part per
/// unit of distance from the body origin.
constexpr double kRotationGrowthSafety = 1e-6;
constexpr double kRotationRoundoffRel = 1e-8;
/// Above this half angle the chord never grows less than the arc (h / 2 +
/// h^2 / 6 >= 1): (sqrt(33) - 3) / 2.
const double kChordMaxHalfAngle = (std::sqrt(33.0) - 3.0) / 2.0;

// rotationSweptBox: every point of the box, rotated about the axis by any
// angle up to h (across = h times the box's largest distance from the axis,
// the arc bound the rotating scheme uses; h up to pi / 2, a root interval's
// half angle) and posed at X_WR, lies in the grown box; along a box axis
// that is the rotation axis it does not grow (only by `any`); and the growth
// is not loose: with 0.9 of `across` some rotated point falls outside.
TEST(RotationSweptBox, HoldsTheRotatedBoxAndDoesNotGrowAlongTheAxis) {
  testing::Rng rng(testing::seed() * 43);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int near_limit = 0, outside_shrunk = 0;
  for (int k = 0; k < 60; ++k) {
    Obb box_R;
    box_R.axes_F = generators::randomRotation(rng);
    box_R.centre_F = generators::drawVector(unit, rng) * 2.0 - Eigen::Vector3d::Ones();
    // z, y, x: the order GCC evaluated the constructor's arguments (C++ leaves
    // it unspecified), kept so the seeded cases stay as they were.
    const double half_z = 0.01 + 0.2 * unit(rng);
    const double half_y = 0.05 + unit(rng);
    const double half_x = 0.05 + unit(rng);
    box_R.half = Eigen::Vector3d(half_x, half_y, half_z);
    // Every third case rotates about one of the box's own axes.
    const Eigen::Vector3d axis_R =
        k % 3 == 0 ? Eigen::Vector3d(box_R.axes_F.col(k % 9 / 3)) : generators::randomUnitVector(rng);
    const double h = 0.5 * kPi * unit(rng);
    double rho = 0.0;
    for (const Eigen::Vector3d& c : box_R.corners()) rho = std::max(rho, (c - c.dot(axis_R) * axis_R).norm());
    Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
    X_WR.linear() = generators::randomRotation(rng);
    X_WR.translation() = generators::drawVector(unit, rng) * 10.0;
    const double any = 1e-9;
    const Obb swept_W = rotationSweptBox(box_R, X_WR, axis_R, h * rho, any);
    const Obb shrunk_W = rotationSweptBox(box_R, X_WR, axis_R, 0.9 * h * rho, any);
    if (k % 3 == 0) {
      const int along = k % 9 / 3;
      EXPECT_NEAR(swept_W.half[along], box_R.half[along] + any, 1e-14) << "case " << k;
    }
    bool escaped = false;
    for (int m = 0; m < 200; ++m) {
      const Eigen::Vector3d y = 2.0 * generators::drawVector(unit, rng) - Eigen::Vector3d::Ones();
      // Corners half of the time: the farthest points from the axis.
      const Eigen::Vector3d s = m % 2 == 0 ? Eigen::Vector3d(y.cwiseSign()) : y;
      const Eigen::Vector3d x_R = box_R.centre_F + box_R.axes_F * s.cwiseProduct(box_R.half);
      const double a = h * (2.0 * unit(rng) - 1.0);
      const Eigen::Vector3d p_W = X_WR * (Eigen::AngleAxisd(a, axis_R) * x_R);
      EXPECT_TRUE(swept_W.contains(p_W, 1e-12)) << "case " << k << " point " << m << ": angle " << a << " of " << h;
      escaped = escaped || !shrunk_W.contains(p_W, 1e-12);
      near_limit += std::abs(a) > 0.8 * h && s.cwiseAbs().minCoeff() == 1.0;
    }
    outside_shrunk += escaped;
  }
  EXPECT_GT(near_limit, 600);  // about 1/10 of the points: corners turned by more than 0.8 h
  // Some case needs more than 0.9 of the growth (6 of the 60 at this seed:
  // a point moves along one tangent, which reaches the disk's support along
  // a box axis only when it lies near that axis).
  EXPECT_GT(outside_shrunk, 0);
}

// partSweep: every point within `radius` of the centre, turned about the axis
// by a = (2s - 1) h at s in [0, 1] (the interval's constant-speed rotation
// about its middle orientation) and translated by s v, lies within the
// growth of the point's place in the sweep (X_WR_start x + s v_W), with at most
// `any` of the displacement along the axis; the growth is never more than
// the arc bound (h times the part's largest distance from the axis); and it
// is not loose: at 0.9 of `across` some point escapes in some case of each
// kind. Half angles: most of them small (where the chord is taken), a
// quarter just above kChordMaxHalfAngle ~ 1.372 (where the arc is always
// taken and still within 0.92 of tight: 2 sin(h / 2) / h), an eighth in
// (pi, 4 pi] (an extended edge's root interval; the arc). A fifth of the
// parts have a `rho` below |centre| + radius (their points are drawn within
// rho of the origin) and an axis perpendicular to the centre, so that rho
// caps the arc's growth.
TEST(PartSweep, HoldsTheRotatedPartAndTakesTheSmallerGrowth) {
  testing::Rng rng(testing::seed() * 47);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int chord_cases = 0, rho_capped = 0, chord_tight = 0, arc_tight = 0;
  const int kCases = 120;
  for (int k = 0; k < kCases; ++k) {
    const Eigen::Vector3d centre_R = (generators::drawVector(unit, rng) * 2.0 - Eigen::Vector3d::Ones()) * 2.0;
    const double radius = 0.01 + 0.5 * unit(rng);
    const bool capped = k % 5 == 1;
    const Eigen::Vector3d axis_R = capped
                                       ? Eigen::Vector3d(centre_R.cross(generators::randomUnitVector(rng)).normalized())
                                       : generators::randomUnitVector(rng);
    const double h = k % 4 == 0   ? kChordMaxHalfAngle + 0.01 + 0.07 * unit(rng)
                     : k % 8 == 2 ? kPi * (1.0 + 3.0 * unit(rng))
                                  : 0.2 * unit(rng);
    const double rho = centre_R.norm() + (capped ? 0.3 : 1.0) * radius;
    Eigen::Isometry3d X_WI = Eigen::Isometry3d::Identity();
    X_WI.linear() = generators::randomRotation(rng);
    X_WI.translation() = generators::drawVector(unit, rng) * 10.0;
    const Eigen::Vector3d v_W = generators::drawVector(unit, rng) - 0.5 * Eigen::Vector3d::Ones();
    const PartSweep ps = partSweep(centre_R, radius, rho, axis_R, h, X_WI, v_W);
    const double to_axis = axis_R.cross(centre_R).norm();
    const double arc = h * std::min(rho, to_axis + radius) * (1.0 + kRotationGrowthSafety);
    EXPECT_LE(ps.across, arc * (1.0 + 1e-15)) << "case " << k;
    EXPECT_EQ(ps.any, kRotationRoundoffRel * rho) << "case " << k;
    const bool chord = ps.v_W != v_W;
    if (h >= kChordMaxHalfAngle) {
      EXPECT_FALSE(chord) << "case " << k << ": the chord at h " << h;
    }
    chord_cases += chord;
    rho_capped += !chord && rho < to_axis + radius;
    const Eigen::Vector3d axis_W = X_WI.linear() * axis_R;
    double worst = 0.0;  // largest displacement over `across`
    for (int m = 0; m < 400; ++m) {
      // On the sphere three times in four (the farthest points), inside
      // otherwise; within rho of the origin (drawn again until it is).
      Eigen::Vector3d y;
      do {
        // The factor before the direction: the order GCC evaluated the
        // product's operands (C++ leaves them unsequenced).
        const double factor = m % 4 == 0 ? unit(rng) : 1.0;
        y = generators::randomUnitVector(rng) * radius * factor;
      } while ((centre_R + y).norm() > rho);
      // The interval's ends a quarter of the time (where the chord's error peaks).
      const double s = m % 4 == 1 ? 0.0 : m % 4 == 2 ? 1.0 : unit(rng);
      const Eigen::Vector3d x_R = centre_R + y;
      const Eigen::Vector3d p_W =
          X_WI.translation() + s * v_W + X_WI.linear() * (Eigen::AngleAxisd((2.0 * s - 1.0) * h, axis_R) * x_R);
      const Eigen::Vector3d swept_W = ps.X_WR_start * x_R + s * ps.v_W;
      const Eigen::Vector3d off_W = p_W - swept_W;
      const double along = std::abs(off_W.dot(axis_W));
      EXPECT_LE(off_W.norm(), ps.total() + 1e-12)
          << "case " << k << " point " << m << ": centre (" << centre_R.transpose() << ") radius " << radius
          << " axis (" << axis_R.transpose() << ") h " << h << " s " << s << (chord ? " chord" : " arc");
      EXPECT_LE(along, ps.any + 1e-12) << "case " << k << " point " << m;
      worst = std::max(worst, (off_W - off_W.dot(axis_W) * axis_W).norm() / ps.across);
    }
    (chord ? chord_tight : arc_tight) += worst > 0.9;
  }
  // The chord is the common case, rho does cap some arcs, and neither bound
  // is loose in every case.
  EXPECT_GT(chord_cases, kCases / 2);
  EXPECT_GT(rho_capped, 0);
  EXPECT_GT(chord_tight, 0);
  EXPECT_GT(arc_tight, 0);
}

// partSweep in closed form. A small part far from the axis takes the chord:
// start shifted by -sin(h) k, sweep v + 2 sin(h) k, growth h r + (h^2 / 2 +
// h^3 / 6) |k| (times 1 + kRotationGrowthSafety), k = axis x centre. A
// large part over a half angle of 1 keeps the arc, capped by rho (centre (1,
// 0, 0), radius 0.5, rho 1: the arc grows by 1, the chord would by 0.5 + 2 /
// 3): no sweep of its own, growth h rho.
TEST(PartSweep, ClosedFormChordAndArc) {
  const double h = 0.01, r = 0.01;
  const Eigen::Vector3d axis_R = Eigen::Vector3d::UnitZ();
  Eigen::Isometry3d X_WI = Eigen::Isometry3d::Identity();
  X_WI.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
  const Eigen::Vector3d v_W(0.0, 0.0, 1.0);
  const PartSweep far = partSweep(Eigen::Vector3d(1.0, 0.0, 0.0), r, 1.0 + r, axis_R, h, X_WI, v_W);
  EXPECT_NEAR(far.across, (h * r + (0.5 * h * h + h * h * h / 6.0)) * (1.0 + kRotationGrowthSafety), 1e-17);
  EXPECT_NEAR(far.any, kRotationRoundoffRel * (1.0 + r), 1e-20);
  EXPECT_LT(far.across, 0.02 * h * (1.0 + r));  // the arc's growth would be h (1 + r)
  EXPECT_TRUE(far.X_WR_start.translation().isApprox(Eigen::Vector3d(5.0, -std::sin(h), 0.0), 1e-15));
  EXPECT_TRUE(far.X_WR_start.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-15));
  EXPECT_TRUE(far.v_W.isApprox(Eigen::Vector3d(0.0, 2.0 * std::sin(h), 1.0), 1e-15));
  const PartSweep large = partSweep(Eigen::Vector3d(1.0, 0.0, 0.0), 0.5, 1.0, axis_R, 1.0, X_WI, v_W);
  EXPECT_NEAR(large.across, 1.0 + kRotationGrowthSafety, 1e-15);
  EXPECT_EQ(large.any, kRotationRoundoffRel);
  EXPECT_EQ(large.v_W, v_W);
  EXPECT_EQ(large.X_WR_start.translation(), X_WI.translation());
}

// checkEdge where only the arc's bulge beyond the chord touches: a robot
// turns by 1 rad about z (from -0.5 to 0.5 rad), and a small cube (side
// 0.01) sits on the arc of the robot's tip, at radius 0.975, where the tip
// passes at t = 7/16, between the probe states (t = k / 4) and the eighths: 0.117 outside
// the line of the tip's chord over the whole edge. Two robots: a rod of 20
// cubes (side 0.05) along the body x axis from the origin, and a lone cube
// of side 0.01 at (0.975, 0, 0) (a part far from its body origin, the
// robot's only piece: its leaf meets the obstacle's over the whole edge with
// a growth below delta, where a chord sweep without its (h^2 / 2 + h^3 / 6)
// |k| term would clear the pair at once). The edge must collide (a dense
// check of 20,001 states finds the contact; none of the probe states, nor
// any eighth, does),
// its first-contact bound no later than the dense check's first colliding
// state; each robot also turning the other way round, from 0.5 to -0.5 rad.
TEST(ChordSweep, EdgeTouchedOnlyByTheArcsBulgeCollides) {
  std::vector<scene::Piece> rod;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Isometry3d X_RB(Eigen::Translation3d(0.025 + 0.05 * i, 0.0, 0.0));
    rod.push_back(scene::boxPiece(Eigen::Vector3d::Constant(0.05), X_RB, "rod cube " + std::to_string(i)));
  }
  const double angle = 1.0, r_tip = 0.975;
  const std::vector<scene::Piece> tip = {scene::boxPiece(
      Eigen::Vector3d::Constant(0.01), Eigen::Isometry3d(Eigen::Translation3d(r_tip, 0.0, 0.0)), "tip cube")};
  const double a_hit = -0.5 + angle * 7.0 / 16.0;
  const Eigen::Isometry3d X_WO(Eigen::Translation3d(r_tip * std::cos(a_hit), r_tip * std::sin(a_hit), 0.0));
  const auto world = std::make_shared<scene::World>(
      std::vector<scene::Piece>{scene::boxPiece(Eigen::Vector3d::Constant(0.01), X_WO, "obstacle")}, "world");
  for (const auto& [name, pieces] : {std::make_pair("rod", rod), std::make_pair("tip", tip)}) {
    const MddScene mdd(std::make_shared<scene::RigidBody>(pieces, name), world);
    for (const double sign : {1.0, -1.0}) {
      const std::string what = std::string(name) + (sign > 0 ? ", turning from -0.5 rad" : ", turning from 0.5 rad");
      EdgeMotion m;
      m.q_start = Eigen::Quaterniond(Eigen::AngleAxisd(-0.5 * sign, Eigen::Vector3d::UnitZ()));
      m.R_start = m.q_start.toRotationMatrix();
      m.axis_R = sign * Eigen::Vector3d::UnitZ();
      m.angle = angle;
      m.X_end = m.pose(1.0);
      double first = kInf;  // the dense check's first colliding state
      for (int k = 0; k <= 20000 && !(first < kInf); ++k) {
        if (mdd.collides(m.pose(k / 20000.0))) first = k / 20000.0;
      }
      ASSERT_LT(first, 1.0) << what << ": the robot never touches the obstacle";
      for (int k = 0; k <= 8; ++k)
        EXPECT_FALSE(mdd.collides(m.pose(k / 8.0))) << what << ": probe state " << k << " / 8";
      EXPECT_TRUE(mdd.checkEdge(m, EdgeQuery::kValidity).collides) << what << ": first colliding state t = " << first;
      const EdgeContact contact = mdd.checkEdge(m, EdgeQuery::kFirstContact);
      EXPECT_TRUE(contact.collides) << what;
      EXPECT_LE(contact.fraction, first) << what;
      // Near t = 7/16 (9/16 the other way), less the tip's and the obstacle's half widths over the tip's speed.
      EXPECT_GT(contact.fraction, sign > 0 ? 0.35 : 0.45) << what;
    }
  }
}

// Rotating edges whose growth cannot shrink below a floor: the search must
// end (before the fix, each of these halved intervals until memory ran out)
// and stay sound. A turn about z keeps the robot's height, so an obstacle
// above it by a gap is never touched; one overlapping it always is.
EdgeMotion turnAboutZ(double from, double angle) {
  EdgeMotion m;
  m.q_start = Eigen::Quaterniond(Eigen::AngleAxisd(from, Eigen::Vector3d::UnitZ()));
  m.R_start = m.q_start.toRotationMatrix();
  m.axis_R = Eigen::Vector3d::UnitZ();
  m.angle = angle;
  m.X_end = m.pose(1.0);
  return m;
}

/// A slab of half height 0.5 whose underside is at height `underside`,
/// above the robot's pieces near (1, 0, 0).
std::shared_ptr<scene::World> slabAt(double underside) {
  const Eigen::Isometry3d X_WO(Eigen::Translation3d(1.0, 0.0, underside + 0.5));
  return std::make_shared<scene::World>(
      std::vector<scene::Piece>{scene::boxPiece(Eigen::Vector3d::Constant(1.0), X_WO, "slab")}, "world");
}

/// Bounded search (a count, not a time: 23 to 63 triples per query here;
/// with the node split on the whole growth, 101 to 204 in the first test,
/// and without the out-of-reach level rule, 107 to 2,149 in the second,
/// before their intervals stopped halving; with neither guard, no end), the
/// verdict sound against the closed form.
void expectEndsAndSound(const MddScene& mdd, const EdgeMotion& m, bool touches, const std::string& what) {
  for (const EdgeQuery q : {EdgeQuery::kValidity, EdgeQuery::kFirstContact, EdgeQuery::kLastValid}) {
    const EdgeContact c = mdd.checkEdge(m, q);
    EXPECT_LT(c.sub_edges, 80) << what << ", query " << static_cast<int>(q);
    // The search runs (the validity check of a colliding edge may end at a
    // probe state instead).
    if (!touches || q != EdgeQuery::kValidity) {
      EXPECT_GT(c.sub_edges, 0) << what << ", query " << static_cast<int>(q);
    }
    if (touches) {
      EXPECT_TRUE(c.collides) << what << ", query " << static_cast<int>(q);
    }
  }
}

TEST(RotatingSearchEnds, NodesSmallerThanTheRoundOffGrowthFarFromTheBodyOrigin) {
  // Four cubes of 1e-9 m at 1 m from the body origin: the growth's round-off
  // part (1e-8 of that distance) exceeds a tenth of their nodes' radii.
  std::vector<scene::Piece> tiny;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Isometry3d X_RB(Eigen::Translation3d(1.0 + 2e-9 * i, 0.0, 0.0));
    tiny.push_back(scene::boxPiece(Eigen::Vector3d::Constant(1e-9), X_RB, "tiny cube " + std::to_string(i)));
  }
  const auto robot = std::make_shared<scene::RigidBody>(tiny, "tiny cubes");
  const EdgeMotion m = turnAboutZ(-0.05, 0.1);
  // A gap of 5.5e-9 (within the enlargement: free or a false alarm), an
  // overlap of 1e-10, and a gap of 0.5 (beyond every enlargement: free).
  expectEndsAndSound(MddScene(robot, slabAt(6e-9)), m, false, "gap 5.5e-9");
  expectEndsAndSound(MddScene(robot, slabAt(4e-10)), m, true, "overlap 1e-10");
  const MddScene far(robot, slabAt(0.5));
  EXPECT_FALSE(far.checkEdge(m, EdgeQuery::kValidity).collides);
}

TEST(RotatingSearchEnds, FinestEnlargementBelowTheRoundOffGrowth) {
  // rotation_tolerance at its minimum (1e-6 of the radius) with 8 levels:
  // the finest enlargement, delta / 256, is below the growth's round-off
  // part, so that level is out of reach of any interval.
  const auto robot = std::make_shared<scene::RigidBody>(
      std::vector<scene::Piece>{scene::boxPiece(Eigen::Vector3d::Constant(0.1),
                                                Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.0)), "cube")},
      "cube");
  MddSceneOptions options;
  options.rotation_tolerance = 1.01e-6 * robot->radius();
  options.refinement_levels = 8;
  const EdgeMotion m = turnAboutZ(-0.05, 0.1);
  expectEndsAndSound(MddScene(robot, slabAt(0.05 + 1e-9), options), m, false, "gap 1e-9");
  expectEndsAndSound(MddScene(robot, slabAt(0.05 - 1e-9), options), m, true, "overlap 1e-9");
  const MddScene far(robot, slabAt(0.5), options);
  EXPECT_FALSE(far.checkEdge(m, EdgeQuery::kValidity).collides);
}

// A rod of half length 1 centred at the body origin turning by pi in place:
// every orientation keeps it within about 1 of the origin, so an obstacle
// whose near face is at 1.04 from the origin (centre 1.05) in the plane of
// the turn is never touched, and the root triple is cleared by the origin's
// sphere at once (the rod's sphere grown by the turn, 1 + pi / 2, reaches it:
// without that test, 23 triples). An obstacle centred at 0.98 at the polar
// angle 7 pi / 16 is swept by the rod's tip near t = 7 / 16, between the
// probe states, so the validity search is the one that finds it.
TEST(OriginSphere, ClearsATurnInPlaceAtOnceAndMissesNoContact) {
  std::vector<scene::Piece> rod;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Isometry3d X_RB(Eigen::Translation3d(-0.95 + 0.1 * i, 0.0, 0.0));
    rod.push_back(scene::boxPiece(Eigen::Vector3d::Constant(0.1), X_RB, "rod cube " + std::to_string(i)));
  }
  const auto robot = std::make_shared<scene::RigidBody>(rod, "rod");
  const auto obstacleAt = [](double radius, double polar_angle) {
    const Eigen::Isometry3d X_WO(
        Eigen::Translation3d(radius * std::cos(polar_angle), radius * std::sin(polar_angle), 0.0));
    return std::make_shared<scene::World>(
        std::vector<scene::Piece>{scene::boxPiece(Eigen::Vector3d::Constant(0.02), X_WO, "obstacle")}, "world");
  };
  const EdgeMotion m = turnAboutZ(0.0, kPi);
  const MddScene far(robot, obstacleAt(1.05, kPi / 2.0));
  for (const EdgeQuery q : {EdgeQuery::kValidity, EdgeQuery::kFirstContact, EdgeQuery::kLastValid}) {
    const EdgeContact c = far.checkEdge(m, q);
    EXPECT_FALSE(c.collides) << "query " << static_cast<int>(q);
    EXPECT_EQ(c.sub_edges, 1) << "query " << static_cast<int>(q);
  }
  const MddScene near(robot, obstacleAt(0.98, 7.0 * kPi / 16.0));
  double first = kInf;  // the dense check's first colliding state
  for (int k = 0; k <= 20000 && !(first < kInf); ++k) {
    if (near.collides(m.pose(k / 20000.0))) first = k / 20000.0;
  }
  ASSERT_GT(first, 0.4);
  ASSERT_LT(first, 0.4375);
  for (const double t : {0.25, 0.5, 0.75, 1.0}) EXPECT_FALSE(near.collides(m.pose(t))) << "probe state " << t;
  const EdgeContact validity = near.checkEdge(m, EdgeQuery::kValidity);
  EXPECT_TRUE(validity.collides);
  EXPECT_GT(validity.sub_edges, 1);
  const EdgeContact contact = near.checkEdge(m, EdgeQuery::kFirstContact);
  EXPECT_TRUE(contact.collides);
  EXPECT_LE(contact.fraction, first);
  EXPECT_GT(contact.fraction, first - 0.01);
}

}  // namespace
}  // namespace mddual::planning
