// The soundness suite: named, seeded families of edges where collision
// checkers are known to go wrong, each edge with an independent ground truth,
// and the checkers it compares (mdd, fcl, fcl-continuous, hull-cast,
// hull-cast-edge; on the mesh families also fcl-continuous-obb and
// fcl-continuous-rss; for the arm family the same without fcl-continuous, its
// arm checkers).
// Shared by the runner (run_soundness.cpp, scripts/run-soundness.sh) and the
// tests (tests/benchmarks/soundness).
//
// Every body is a box (an oriented box in its owner's frame), so the ground
// truth needs neither MDD-DUAL nor FCL:
//   - dense check: the edge under OMPL's own interpolation
//     (StateSpace::interpolate), sampled from t = 0 with steps of at least
//     `min_step` of the edge, each step as long as the smallest separating-axis
//     gap between a robot box and a world box (a lower bound of their
//     distance) over the largest point speed allows: no state between two
//     samples can touch unless the gap is below min_step's travel. Touching
//     (a gap of 0) is a collision, as for the checkers.
//   - exact first contact on translation edges: the separating-axis test on
//     the moving box (15 axes per pair, each giving an interval of t), the
//     earliest t at which every axis overlaps.
//
// Families (makeFamily):
//   translating-boxes      R^3: a box translating past or through another
//                          (sizes 0.02 to 1, random orientations).
//   obb-hierarchy          the same with the world's boxes as triangle meshes
//                          (FCL: FclScene's one BVHModel<OBBRSS> soup; the
//                          checkers fcl-continuous-obb and -rss rerun FCL's
//                          conservative advancement on BVHModel<OBB> and
//                          BVHModel<RSS>, fcl_bvh.h).
//   rotating-link-arc      SE(2): a link 1.5 to 3 long turning 30 to 120
//                          degrees about one end; the obstacle mostly inside
//                          its arc but outside the hull of its end poses.
//   screw-vs-interpolated  SE(3): a link turning 90 to 170 degrees while
//                          moving; the obstacle on OMPL's interpolated path,
//                          off FCL's screw motion between the same poses.
//   thin-wall              R^3: a wall 0.004 to 0.04 thick (OMPL's discrete
//                          step here is about 0.35), crossed or passed.
//   far-from-origin        translating boxes and rotating links at 1e6.
//   grazing                R^3: a box sliding along a face of another at a
//                          gap of +-1e-6 of the bodies' size (half free).
//   arm-rotating-link      a planar arm of three box links
//                          (examples::planarArm) turning one joint 30 to 120
//                          degrees past a small box that mostly sits on a
//                          link's path in mid-edge (inside the arc, outside the
//                          hull of the end poses). Joint-space edges; the
//                          ground truth is the dense check on the links'
//                          boxes (forward kinematics of the planar chain, in
//                          this file) against the world and each other
//                          (the non-adjacent pairs, as the arm checkers).
//   sliver-mesh            R^3: one flat mesh obstacle, a large flat
//                          triangle pair (4 to 9 across), a strip 1 to 4 long
//                          and 0.001 to 0.02 wide (two needle triangles) or a
//                          sheet 2 to 4 long cut into 32 to 64 strips of two
//                          slivers (50 to 640 times as long as high); a
//                          box of 0.02 to 0.6 across crossing its plane or
//                          sliding along it (the ground truth sees the
//                          rectangle, a box of thickness 0: the same points).
#pragma once

#include <ompl/base/SpaceInformation.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mddual/planning/arm_scene.h"
#include "mddual/planning/arm_space.h"
#include "mddual/planning/dense_contact.h"
#include "mddual/planning/state_space.h"
#include "mddual/scene/scene.h"

namespace mddual::soundness {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// An oriented box: half extents `half` in the frame X (in its owner's frame).
struct Box {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Ones();
};

/// One scene and its edges (the robot's poses X_WR at both ends).
struct Case {
  std::string family;
  planning::SpaceKind kind = planning::SpaceKind::kR3;
  Eigen::AlignedBox3d bounds;
  Eigen::Quaterniond q_fixed = Eigen::Quaterniond::Identity();  ///< kR3: the robot's orientation
  std::vector<Box> robot;                                       ///< body frame
  std::vector<Box> world;                                       ///< world frame
  bool world_triangles = false;                                 ///< world boxes as 12 triangles each (mesh pieces)
  /// Mesh worlds: a flat box (half.z() 0) is a rectangle cut across its y
  /// side into `flat_strips` strips of two triangles each, not 12 triangles.
  int flat_strips = 1;
  std::vector<std::pair<Eigen::Isometry3d, Eigen::Isometry3d>> edges;
  /// Arm cases: the planar arm's link lengths (empty for a rigid body; then
  /// `robot` is unused), its links' half width and height, and its edges
  /// (full configurations at both ends) instead of `edges`.
  std::vector<double> arm_lengths;
  double arm_half_width = 0.0;
  double arm_half_height = 0.0;
  std::vector<std::pair<std::vector<double>, std::vector<double>>> arm_edges;
  bool isArm() const { return !arm_lengths.empty(); }
  int numEdges() const { return static_cast<int>(isArm() ? arm_edges.size() : edges.size()); }
};

/// The family names, in the order of the results table.
const std::vector<std::string>& familyNames();
/// About `edges` edges of the family (cases of one or more edges each), drawn
/// from `seed`; every edge starts collision-free. Throws InvalidInputError for
/// an unknown name.
std::vector<Case> makeFamily(const std::string& family, std::uint64_t seed, int edges);

/// A case's planning objects: the space, the robot and the world as pieces
/// (rigid cases), or the arm's space and scene (arm cases; `world` set too).
struct Scene {
  planning::PlanningSpacePtr space;
  std::shared_ptr<const scene::RigidBody> robot;
  std::shared_ptr<const scene::World> world;
  planning::ArmSpacePtr arm_space;
  std::shared_ptr<const planning::ArmScene> arm;
};
Scene buildScene(const Case& c);
/// The OMPL state of the space at pose X (allocated by the space; free it).
ompl::base::State* makeState(const Scene& s, const Eigen::Isometry3d& X);
/// The states of edge `edge`'s two ends (rigid or arm; free them with the
/// scene's state space).
std::pair<ompl::base::State*, ompl::base::State*> makeEdgeStates(const Case& c, const Scene& s, int edge);
/// The smallest separating-axis gap of the edge's start (> 0: free).
double startGap(const Case& c, int edge);

/// The ground truth of one edge (see the file comment).
struct Truth {
  bool collides = false;
  double dense_contact = kInf;  ///< first colliding sample of the dense check (+inf: free)
  /// Exact first contact of a translation edge (+inf: free); NaN on rotating edges.
  double exact_contact = std::numeric_limits<double>::quiet_NaN();
};
Truth groundTruth(const Case& c, const Scene& s, int edge, double min_step = 1e-5);

/// Separating-axis gap of two boxes placed in the world: the largest gap of
/// their projections over the 15 axes; <= 0 iff they touch or overlap, and
/// never above their distance.
double boxGap(const Box& a, const Box& b);
/// The dense check on an arbitrary motion pose(t) of the robot, t in [0, 1],
/// whose points move at most `speed` per unit of t.
template <class PoseFn>
double denseFirstContact(const Case& c, const PoseFn& pose, double speed, double min_step);
/// The first contact along the screw motion between the edge's two poses (the
/// motion FCL's continuous check takes on rotating edges), densely.
double screwFirstContact(const Case& c, int edge, double min_step = 1e-5);

/// The checkers compared: "mdd", "fcl", "fcl-continuous", "hull-cast" (the
/// Bullet cast over OMPL's segments), "hull-cast-edge" (one cast per edge).
const std::vector<std::string>& checkerNames();
/// Whether the family's world is a triangle mesh (obb-hierarchy,
/// sliver-mesh).
bool meshFamily(const std::string& family);
/// The checkers of a family: checkerNames(); on the mesh families with
/// "fcl-continuous-obb" and "fcl-continuous-rss" after "fcl-continuous"
/// (fcl_bvh.h); for the arm family the arm checkers "mdd", "fcl",
/// "hull-cast", "hull-cast-edge" (there is no continuous FCL arm check).
const std::vector<std::string>& checkerNames(const std::string& family);
/// A SpaceInformation whose motion validator is `checker`'s (see
/// run-soundness.sh), of the case's kind (rigid or arm); throws
/// InvalidInputError for a checker the kind has not.
ompl::base::SpaceInformationPtr makeChecker(const std::string& checker, const Scene& s);
/// checkMotion(s1, s2) of `si` on every edge: its verdicts and times (seconds).
struct CheckerRun {
  std::vector<bool> valid;
  std::vector<double> seconds;
};
CheckerRun runChecker(const ompl::base::SpaceInformation& si, const Case& c, const Scene& s);

// ---- template implementation -----------------------------------------------

namespace detail {
/// The smallest boxGap between the robot at X_WR and the world.
double sceneGap(const Case& c, const Eigen::Isometry3d& X_WR);
/// The smallest boxGap of an arm case at configuration q: each link box
/// against the world boxes and the non-adjacent link boxes.
double armGap(const Case& c, const std::vector<double>& q);
}  // namespace detail

template <class PoseFn>
double denseFirstContact(const Case& c, const PoseFn& pose, double speed, double min_step) {
  return planning::denseFirstContact([&](double t) { return detail::sceneGap(c, pose(t)); }, speed, min_step);
}

}  // namespace mddual::soundness
