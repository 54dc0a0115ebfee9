#include "mddual/planning/planner_factory.h"

#include <ompl/geometric/planners/AnytimePathShortening.h>
#include <ompl/geometric/planners/cforest/CForest.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include <functional>
#include <map>

#include "mddual/error.h"
#include "mddual/planning/exact_rrt_connect.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Allocator = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

template <class P>
Allocator make() {
  return [](const ob::SpaceInformationPtr& si) { return std::make_shared<P>(si); };
}

/// OMPL.app's names for its geometric planners (ompl_benchmark's list, plus
/// OMPL 1.5's informed planners, the same set mddual::scene::knownPlannerNames
/// accepts in a config), and ours.
const std::map<std::string, Allocator>& registry() {
  static const std::map<std::string, Allocator> planners{
      {"abitstar", make<og::ABITstar>()},
      {"aitstar", make<og::AITstar>()},
      {"aps", make<og::AnytimePathShortening>()},
      {"bfmt", make<og::BFMT>()},
      {"biest", make<og::BiEST>()},
      {"bitstar", make<og::BITstar>()},
      {"bkpiece", make<og::BKPIECE1>()},
      {"cforest", make<og::CForest>()},
      {"est", make<og::EST>()},
      {"fmt", make<og::FMT>()},
      {"informedrrtstar", make<og::InformedRRTstar>()},
      {"kpiece", make<og::KPIECE1>()},
      {"lazyprm", make<og::LazyPRM>()},
      {"lazyprmstar", make<og::LazyPRMstar>()},
      {"lazyrrt", make<og::LazyRRT>()},
      {"lbkpiece", make<og::LBKPIECE1>()},
      {"lbtrrt", make<og::LBTRRT>()},
      {"pdst", make<og::PDST>()},
      {"prm", make<og::PRM>()},
      {"prmstar", make<og::PRMstar>()},
      {"projest", make<og::ProjEST>()},
      {"rrt", make<og::RRT>()},
      {"rrtconnect", make<og::RRTConnect>()},
      {"rrtsharp", make<og::RRTsharp>()},
      {"rrtstar", make<og::RRTstar>()},
      {"rrtxstatic", make<og::RRTXstatic>()},
      {"sbl", make<og::SBL>()},
      {"sorrtstar", make<og::SORRTstar>()},
      {"spars", make<og::SPARS>()},
      {"spars2", make<og::SPARStwo>()},
      {"stride", make<og::STRIDE>()},
      {"trrt", make<og::TRRT>()},
      // ours
      {"mdd_rrtconnect", make<ExactRRTConnect>()},
  };
  return planners;
}

}  // namespace

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const auto& [name, alloc] : registry()) names.push_back(name);
  return names;
}

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si,
                           const std::vector<std::pair<std::string, std::string>>& params) {
  const auto it = registry().find(name);
  if (it == registry().end()) {
    std::string known;
    for (const std::string& n : plannerNames()) known += (known.empty() ? "" : ", ") + n;
    throw InvalidInputError("unknown planner '" + name + "' (known: " + known + ")");
  }
  ob::PlannerPtr planner = it->second(si);
  for (const auto& [key, value] : params) {
    if (key == "name") {
      planner->setName(value);
    } else if (!planner->params().hasParam(key)) {
      throw InvalidInputError("planner '" + name + "' has no parameter '" + key + "'");
    } else if (!planner->params().setParam(key, value)) {
      throw InvalidInputError("planner '" + name + "': parameter '" + key + "' rejects the value '" + value + "'");
    }
  }
  return planner;
}

}  // namespace mddual::planning
