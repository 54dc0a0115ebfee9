// Helpers shared by the cfg reader and writer (not installed).
#pragma once

#include <optional>
#include <string>

#include "mddual/scene/problem_config.h"

namespace mddual::scene::detail {

/// True for the [problem] keys the reader interprets itself (OMPL.app's
/// declared keys, translation_only, mesh_convex_tolerance and control); other
/// keys are space
/// parameters.
bool isDeclaredProblemKey(const std::string& key);

/// A finite decimal number (a leading '+' allowed), or nothing.
std::optional<double> parseNumber(const std::string& text);

/// The shortest decimal form of a finite `value` that parseNumber reads back
/// exactly.
std::string formatNumber(double value);

/// length, max_min_clearance or mechanical_work (OMPL.app's objectives).
bool isKnownObjective(const std::string& objective);

/// True when the start and goal rotations agree within 1e-9 rad.
bool sameRotation(const PoseSpec& start, const PoseSpec& goal, SpaceKind kind);

}  // namespace mddual::scene::detail
