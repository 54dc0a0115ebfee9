// Scenes built in code, for the tests, the benchmark and demos: the four kinds
// of planning problems of the planning layer, each seeded and with a size
// parameter so that the same scene can be scaled up. Each returns the robot,
// the world, position bounds and the scene's natural space kind (any kind can
// be used with any scene through makeSpace()).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mddual/planning/state_space.h"
#include "mddual/scene/robot_model.h"
#include "mddual/scene/scene.h"
#include "mddual/scene/srdf.h"

namespace mddual::planning::examples {

/// A robot, a world, bounds and the natural space kind.
struct ExampleScene {
  std::string name;
  std::shared_ptr<const scene::RigidBody> robot;
  std::shared_ptr<const scene::World> world;
  Eigen::AlignedBox3d bounds;
  SpaceKind kind = SpaceKind::kSE3;
};

/// (a) URDF-like primitives: a floor slab, `obstacles` boxes (random sizes and
/// orientations) and upright "cylinders" (16-gon prisms circumscribing the
/// circle, as a URDF loader would), all convex pieces; robot: a box base with
/// a cylinder on top (two convex pieces). Natural space: R^3.
ExampleScene primitivesScene(std::uint64_t seed, int obstacles = 40);

/// (b) Non-convex meshes as triangles: a room (floor, ceiling, four walls, two
/// partition walls with door openings, each rectangle two triangles) and
/// `obstacles` triangulated boxes; robot: an L-shaped prism as 20 triangles.
/// Natural space: SE(3).
ExampleScene meshScene(std::uint64_t seed, int obstacles = 20);

/// (c) SE(2): random convex polygons extruded over z in [-0.5, 0.5]; robot: a
/// T of two extruded rectangles (z in [-0.25, 0.25]). Natural space: SE(2).
ExampleScene planarScene(std::uint64_t seed, int obstacles = 60);

/// (d) SE(3): random convex blobs (20 to 40 vertices); robot: a blob and a
/// hexagonal prism. Natural space: SE(3).
ExampleScene blobScene(std::uint64_t seed, int obstacles = 80);

/// (e) SE(3), a mesh of the size of OMPL.app's bug trap: a hollow cube (outer
/// half side 5, walls 0.4 thick; the inside of every wall and both sides of
/// the +x wall a grid of `grid` x `grid` squares, the outside of the others
/// 2 x 2 large squares; two triangles per square) with a square opening in its
/// +x wall that leads into an inward tube, tilted so that no wall is parallel
/// to a plane of the frame; robot: a capsule (radius 0.35, length 3.1, along
/// x) as 252 triangles. About 4,600 world triangles at the default grid.
/// Natural space: SE(3).
ExampleScene trapScene(int grid = 18);

/// A wall of the given thickness across a long corridor (x in [0, 100], the
/// wall at x in [50, 50 + thickness]); robot: a cube of side 0.2. Natural
/// space: R^2 (z = 0). OMPL's default resolution here is about 1.0.
ExampleScene thinWallScene(double thickness = 0.05);

/// The space of `kind` over the scene's bounds (identity orientation, z = 0
/// for the translation-only kinds).
PlanningSpacePtr makeSpace(const ExampleScene& scene, SpaceKind kind);
inline PlanningSpacePtr makeSpace(const ExampleScene& scene) {
  return makeSpace(scene, scene.kind);
}

/// A planar arm (the hull-cast tests, the soundness suite's arm family): a
/// base link without pieces, then one link per entry of `lengths`, link i a
/// box from its joint's origin along +x (lengths[i] long, 2 half_width wide
/// along y, 2 half_height high along z) on a revolute joint about z with
/// limits [-pi, pi], placed at the far end of the link before (the first at
/// the base's origin). Variable i turns link i + 1. `filter` skips the
/// adjacent pairs (they overlap at their joint); the others are checked.
/// Throws InvalidInputError for no link or a size that is not positive.
struct PlanarArm {
  std::shared_ptr<const scene::RobotModel> model;
  scene::AllowedCollisions filter;
};
PlanarArm planarArm(const std::vector<double>& lengths, double half_width = 0.05, double half_height = 0.05);

/// Helpers: a convex piece from points; the 12 triangles of a box; the
/// triangles of a prism over a simple polygon (counter-clockwise, any shape)
/// between z0 and z1.
scene::Piece convexPiece(const std::vector<Eigen::Vector3d>& points, const std::string& origin);
std::vector<scene::Piece> boxTriangles(const Eigen::Vector3d& half_extents, const Eigen::Isometry3d& X,
                                       const std::string& origin);
std::vector<scene::Piece> prismTriangles(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1,
                                         const std::string& origin);

}  // namespace mddual::planning::examples
