// Planners by name: OMPL.app's geometric planner names ("rrt", "rrtconnect",
// "kpiece", ...) and ours ("mdd_rrtconnect"), with OMPL parameters given as
// text, the way a benchmark config's [planner] section lists them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <ompl/base/Planner.h>

namespace mddual::planning {

/// Creates the planner called `name` on `si` and sets each parameter through
/// its ompl::base::ParamSet ("name" renames the planner). Throws
/// mddual::InvalidInputError naming the unknown planner (with the known names)
/// or the parameter that the planner does not have or rejects.
ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si,
                                   const std::vector<std::pair<std::string, std::string>>& params = {});

/// Every name makePlanner accepts, sorted.
std::vector<std::string> plannerNames();

}  // namespace mddual::planning
