// FCL's conservative advancement on other mesh hierarchies than FclScene's
// BVHModel<OBBRSS>, for the soundness suite's mesh families: the checkers
// "fcl-continuous-obb" and "fcl-continuous-rss" (checkers.cpp). FCL's
// conservative advancement is reported to work on RSS hierarchies only; these
// measure it on each one instead of assuming it.
//
// The validator models the robot and the world each as one fcl::BVHModel<BV>
// triangle soup (a triangle piece as its triangle, a convex piece as its
// faces fanned into triangles), as FclScene checks a convex robot against a
// mesh world (two meshes: FCL 0.7's shape-mesh advancement crashes or
// misses, planners/ompl/src/fcl_scene.cpp). checkMotion(s1, s2) is
// FclContinuousMotionValidator's: s2 checked with si->isValid first (the FCL
// state check), then
// fcl::continuousCollide with CCDC_CONSERVATIVE_ADVANCEMENT and libccd, the
// translation (CCDM_TRANS) or FCL's screw motion (CCDM_SCREW) on rotating
// edges. What FCL prints to std::cerr during a cast (on OBB hierarchies,
// "OBB distance not implemented!" per bounding-volume test) is counted, not
// shown. Not thread-safe (one validator per thread).
#pragma once

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include <cstdint>

#include "cases.h"

namespace mddual::soundness {

/// The bounding volumes of the two hierarchies.
enum class FclBvh { kObb, kRss };

/// The motion validator on the rigid scene `s` (throws InvalidInputError for
/// an arm scene).
ompl::base::MotionValidatorPtr makeFclBvhContinuous(const ompl::base::SpaceInformationPtr& si, const Scene& s,
                                                    FclBvh bvh);

/// The lines FCL wrote to std::cerr during these validators' casts, since
/// the program started.
std::uint64_t fclBvhWarnings();

}  // namespace mddual::soundness
