// Edges as values: EdgeMotion (state_space.h) built from a pose and a
// direction, or continued past its end, for MddScene::checkEdge and
// edgeContact() (clearance.h) without filling its seven fields by hand.
//
//   // Where does the edge s1 -> s2 first hit if the robot goes on to three
//   // times its length?
//   const EdgeMotion edge = space.motion(s1, s2);
//   const EdgeContact c = edgeContact(scene, extendedEdge(edge, 3.0));
//   // c.fraction is a fraction of the extended edge: 3 * c.fraction in the
//   // parameter of the original one (+infinity: no contact).
//
// For a pure translation from a pose, directedClearance() (clearance.h)
// already gives the distance to the first contact along a direction (and the
// signed MDD when the start collides); translationEdge() is the same motion as
// an edge, for code that handles edges.
#pragma once

#include <Eigen/Geometry>

#include "mddual/planning/state_space.h"

namespace mddual::planning {

/// Largest deviation from a rotation (entries of R^T R - I) and from a unit
/// axis accepted in an edge's input; the tolerance of PlanningSpace::setPose.
inline constexpr double kEdgeRotationTolerance = 1e-9;

/// The robot at X_WR translating by `length` (world units) along direction_W
/// (any non-zero length; normalised), orientation fixed: p_start =
/// X_WR.translation(), p_end = p_start + length u, angle 0, X_end the end pose.
/// Throws InvalidInputError for a non-finite pose, a linear part that is not a
/// rotation, a zero or non-finite direction, or a negative, NaN or infinite
/// length (0 gives a single state).
EdgeMotion translationEdge(const Eigen::Isometry3d& X_WR, const Eigen::Vector3d& direction_W, double length);

/// The same motion continued (factor > 1) or cut short (factor < 1): the
/// result at t is `edge` at factor t, for t in [0, 1]:
///   p_end' = p_start + factor (p_end - p_start), angle' = factor angle,
///   the same start orientation and body-frame axis (so the same translation
///   and angular speed per unit of the original parameter), X_end' = pose'(1).
/// A rotating edge keeps turning about its axis; angle' may exceed pi (the
/// motion is no longer an OMPL edge between two states, which would take the
/// shorter arc; MddScene::checkEdge's scheme holds for any angle, at a cost in
/// sub-edges proportional to it). An edge whose X_end differed from pose(1)
/// (a sub-threshold SE(2)/SE(3) rotation, state_space.h) ends at pose'(1): the
/// end state of the original edge is not kept.
/// Throws InvalidInputError for a factor that is not finite and positive, or
/// an edge with non-finite fields, a negative angle, a rotation axis that is
/// not a unit vector, or a start orientation that is not a rotation.
EdgeMotion extendedEdge(const EdgeMotion& edge, double factor);

}  // namespace mddual::planning
