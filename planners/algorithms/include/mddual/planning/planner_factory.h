// Planners by name: OMPL.app's geometric planner names ("rrt", "rrtconnect",
// "kpiece", ...) and ours ("mdd_rrtconnect"), with OMPL parameters given as
// text, the way a benchmark config's [planner] section lists them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <ompl/base/Planner.h>

#include "mddual/scene/problem_config.h"

namespace mddual::planning {

/// Creates the planner called `name` on `si` (any case; OMPL's own names such
/// as "KPIECE1" and "SPARStwo" are accepted for OMPL.app's "kpiece" and
/// "spars2") with OMPL's default parameters, then sets each parameter through
/// its ompl::base::ParamSet ("name" renames the planner). Throws
/// mddual::InvalidInputError naming the unknown planner (with the known names)
/// or the parameter that the planner does not have or rejects.
ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si,
                                   const std::vector<std::pair<std::string, std::string>>& params = {});

/// Every name makePlanner accepts, sorted (OMPL.app's spelling, lower case).
std::vector<std::string> plannerNames();

/// The registry name `name` stands for ("KPIECE1" -> "kpiece"), or empty
/// when makePlanner does not know it.
std::string canonicalPlannerName(const std::string& name);

/// The planner instances to run (`mddual bench --planners`): every instance
/// of `listed` (a cfg's [planner] section) when `names` is empty; otherwise,
/// for each name, the cfg's instances of that planner (their parameters
/// kept; matched by the name as given or its canonical name), or, when the
/// cfg lists none, one instance with OMPL's default parameters (named by the
/// canonical name, line 0). Listed instances come first in cfg order, then
/// the defaults in the order asked. Throws mddual::InvalidInputError, naming
/// `cfg_name`, when nothing is listed and nothing asked, or for a name that
/// is neither in the cfg nor a planner makePlanner knows (with both lists).
std::vector<scene::PlannerSpec> selectPlannerSpecs(const std::vector<scene::PlannerSpec>& listed,
                                                   const std::vector<std::string>& names, const std::string& cfg_name);

/// The largest lastValid fraction that `planner` drops, for
/// MddMotionValidator::setDiscardedLastValidFraction: the
/// min_valid_path_fraction of KPIECE1, BKPIECE1, LBKPIECE1 and STRIDE (each
/// keeps a partial motion only when lastValid.second is above it), 0 for
/// every other planner (the safe default: nothing is dropped).
double discardedLastValidFraction(const ompl::base::Planner& planner);

}  // namespace mddual::planning
