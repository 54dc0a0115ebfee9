// Shared by the tests of the OMPL layer (and by the mesh configs' soundness
// test, tests/configs): the scenes, OMPL set-ups with the MDD and FCL checkers
// over the same pieces, seeded random states and edges, the independent
// measures the comparisons rest on (brute-force distance to touching, a dense
// FCL check of an edge, an FCL bisection of a first contact) and the edge
// check built on them (checkEdge).
//
// Scaling: MDDUAL_PLANNING_SCALE=k multiplies every sample count by k (the CI
// runs k = 1), MDDUAL_PLANNING_SEED=n changes the seed of scenes and samples.
#pragma once

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mddual/constants.h"
#include "mddual/planning/example_scenes.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/mdd_checkers.h"

namespace mddual::planning::testing {

using Rng = std::mt19937_64;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// MDDUAL_PLANNING_SCALE (default 1).
int scale();
/// MDDUAL_PLANNING_SEED (default 1).
std::uint64_t seed();

/// A scene with both checkers on one space: `si` carries the MDD checker and
/// motion validator, `fcl_si` the FCL checker and OMPL's DiscreteMotionValidator.
struct Fixture {
  examples::ExampleScene scene;
  PlanningSpacePtr space;
  std::shared_ptr<MddScene> mdd;
  std::shared_ptr<FclScene> fcl;
  ompl::base::SpaceInformationPtr si;
  ompl::base::SpaceInformationPtr fcl_si;
  MddStateValidityCheckerPtr mdd_checker;
  MddMotionValidatorPtr mdd_motion;
  FclStateValidityCheckerPtr fcl_checker;
};
Fixture makeFixture(const examples::ExampleScene& scene, SpaceKind kind,
                    const MddSceneOptions& options = MddSceneOptions());
inline Fixture makeFixture(const examples::ExampleScene& scene) {
  return makeFixture(scene, scene.kind);
}

/// The four scenes built in code: primitives (R^3), mesh (SE(3)), planar
/// (SE(2)), blobs (SE(3)).
std::vector<examples::ExampleScene> standardScenes(std::uint64_t seed);

/// The four scenes loaded from files through the scene loaders:
/// a URDF world and robot of primitives (boxes, cylinders, spheres; SE(3)), a
/// non-convex OBJ world and robot (triangles; SE(3)), and the configs
/// configs/maze_se2 (SE(2)) and configs/cubicles (SE(3)).
std::vector<examples::ExampleScene> fileScenes(std::uint64_t seed);

/// configs/NAME/NAME.cfg loaded through the scene loaders, in the config's
/// space (SE(2) or SE(3)) and bounds.
examples::ExampleScene configScene(const std::string& name);

/// standardScenes(seed()), fileScenes(seed()), then examples::trapScene()
/// (a mesh of OMPL.app's bug-trap size), built once: kSceneCount scenes;
/// indices 4 to 7 are the file scenes.
inline constexpr int kSceneCount = 9;
const std::vector<examples::ExampleScene>& allScenes();
inline bool isFileScene(int index) {
  return index >= 4 && index < 8;
}
/// Test name of allScenes()[index].
std::string sceneName(int index);
/// The instance name of a test parameterized by scene index (INSTANTIATE_TEST_SUITE_P).
inline std::string sceneParamName(const ::testing::TestParamInfo<int>& p) {
  return sceneName(p.param);
}
/// Largest difference between the entries of two poses (rotation and translation).
inline double poseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::max((a.linear() - b.linear()).cwiseAbs().maxCoeff(),
                  (a.translation() - b.translation()).cwiseAbs().maxCoeff());
}

/// A uniformly random state of the space (position in bounds; yaw in (-pi,
/// pi]; uniform rotation).
void randomState(const PlanningSpace& space, Rng& rng, ompl::base::State* state);
/// A random state valid for `si` (rejection sampling).
void randomValidState(const ompl::base::SpaceInformation& si, const PlanningSpace& space, Rng& rng,
                      ompl::base::State* state);
/// s2 from s1: translation by a random vector of length up to max_length (in
/// the space's position dimensions); when `rotate`, a random orientation
/// (SE(2): yaw; SE(3): rotation by up to max_angle about a random axis),
/// otherwise s1's orientation.
void randomEdgeEnd(const PlanningSpace& space, const ompl::base::State* s1, double max_length, bool rotate,
                   double max_angle, Rng& rng, ompl::base::State* s2);

/// Smallest |signed Euclidean distance| between the robot at X_WR and a world
/// piece, over the pairs whose boxes and bounding spheres come within
/// `margin`, computed on the brute-force Minkowski difference (independent of
/// MDD-DUAL and of FCL): exact whenever some pair is within `margin`, else
/// above `margin` (+infinity when no pair is left).
double distanceToTouching(const MddScene& scene, const Eigen::Isometry3d& X_WR, double margin);
/// The tolerance for "within 1e-9 of touching" at X_WR: 1e-9 of the pair's
/// length scale (robot radius + |position| + 1).
double touchTolerance(const MddScene& scene, const Eigen::Isometry3d& X_WR);

/// Dense FCL check of the edge s1 -> s2 under OMPL's interpolation, on the FCL
/// checker of `fx.fcl_si` (bounds included): samples every `step` of the edge
/// from `from`, skipping ahead by half the FCL distance to the world
/// (FclScene::distance: the smaller of FCL's two GJK solvers' answers; a test
/// checks that half of it never exceeds the true distance) over the largest
/// point speed (|p2 - p1| + angle * robot radius, per unit of the edge).
/// Returns the first sample found invalid, or +inf.
double denseFirstInvalid(const Fixture& fx, const ompl::base::State* s1, const ompl::base::State* s2, double from,
                         double step, int* samples = nullptr);
/// Bisection with the FCL checker on [lo, hi] (lo valid, hi invalid) down to
/// `width`: the first invalid fraction.
double fclBisect(const Fixture& fx, const ompl::base::State* s1, const ompl::base::State* s2, double lo, double hi,
                 double width);
/// Whether the FCL checker accepts the state at fraction t of the edge.
bool fclValidAt(const Fixture& fx, const ompl::base::State* s1, const ompl::base::State* s2, double t);

/// What checkEdge found on a sample of edges.
struct EdgeTally {
  int edges = 0;
  int valid = 0;
  int misses = 0;  ///< ours valid, the dense FCL check finds a collision
  int early = 0;   ///< an FCL-invalid state before our first-contact fraction (bound)
  int fraction_checked = 0;
  int fraction_errors = 0;  ///< translation edges: |ours - FCL bisection| > 1e-9
  int grazing = 0;          ///< our contact is a touch that FCL samples do not see
  /// FCL's bisection later than ours by more than 1e-9, ours a touch on the
  /// brute force (FCL's intersection test misses penetrations of ~1e-7)
  int fcl_late = 0;
  int false_alarms = 0;  ///< rotating edges: ours invalid, the dense check finds nothing
  /// Invalid rotating edges whose lastValid is (s1, 0) with the state one
  /// discrete step in colliding (the validator's first-step shortcut)
  int first_step = 0;
  /// Of those, the ones where the kLastValid search's bound is above 1e-3
  /// (lastValid 0 there is the shortcut's, not the search's)
  int first_step_below_bound = 0;
  int samples = 0;  ///< states the dense FCL checks sampled
  double worst_fraction_error = 0.0;
};
/// The tally in one line (for the test's output).
std::string describe(const EdgeTally& t);

/// Checks fx's MddMotionValidator on the edge s1 -> s2 against the measures
/// above, counting into `tally` and failing the test (ADD_FAILURE, with the
/// edge in full precision) on:
///  - a miss: the edge valid for us, the dense FCL check (denseFirstInvalid at
///    1e-4 of the edge) finds an invalid state that is not within
///    touchTolerance of touching on the brute force;
///  - an invalid edge whose lastValid is not a valid state at or before our
///    first invalid fraction (within 1e-3 of it, or (s1, 0) by the first-step
///    shortcut with the first contact within that step), or a valid edge
///    whose lastValid is touched (OMPL's contract);
///  - an FCL collision before our first invalid fraction (exact or a bound);
///  - translation edges: a first contact more than 1e-9 of the edge from an
///    FCL bisection to 1e-13 (a touch FCL does not see counts as grazing, and
///    an FCL bisection later than ours as FCL late, when ours is a touch on
///    the brute force).
void checkEdge(const Fixture& fx, const ompl::base::State* s1, const ompl::base::State* s2, EdgeTally* tally);

/// The edge s1 -> s2 as poses in full precision (position, then the
/// quaternion w x y z), for pinning it as a regression case.
std::string edgeString(const Fixture& fx, const ompl::base::State* s1, const ompl::base::State* s2);

}  // namespace mddual::planning::testing
