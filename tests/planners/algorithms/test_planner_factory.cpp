// The planner factory: OMPL.app's names, ours, parameters, and errors.
#include <gtest/gtest.h>

#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include "mddual/error.h"
#include "mddual/planning/planner_factory.h"
#include "mddual/scene/problem_config.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;

ob::SpaceInformationPtr se3() {
  auto space = std::make_shared<ob::SE3StateSpace>();
  ob::RealVectorBounds bounds(3);
  bounds.setLow(-1);
  bounds.setHigh(1);
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([](const ob::State*) { return true; });
  si->setup();
  return si;
}

TEST(PlannerFactory, KnowsOmplAppNamesAndOurs) {
  const auto si = se3();
  for (const char* name : {"rrt", "rrtconnect", "kpiece", "bkpiece", "lbkpiece", "prm", "lazyprm", "est", "sbl",
                           "rrtstar", "bitstar", "trrt", "stride", "pdst", "mdd_rrtconnect"}) {
    const ob::PlannerPtr p = makePlanner(name, si);
    ASSERT_NE(p, nullptr) << name;
  }
  EXPECT_EQ(makePlanner("mdd_rrtconnect", si)->getName(), "ExactRRTConnect");
}

TEST(PlannerFactory, BuildsEveryPlannerAConfigMayName) {
  const auto si = se3();
  for (const std::string& name : scene::knownPlannerNames()) {
    EXPECT_NE(makePlanner(name, si), nullptr) << name;
  }
}

TEST(PlannerFactory, SetsParametersAndRenames) {
  const auto si = se3();
  const ob::PlannerPtr p = makePlanner("rrt", si, {{"range", "0.25"}, {"goal_bias", "0.2"}, {"name", "myrrt"}});
  EXPECT_EQ(p->getName(), "myrrt");
  EXPECT_EQ(p->params().getParam("range")->getValue(), "0.25");
  EXPECT_EQ(p->params().getParam("goal_bias")->getValue(), "0.2");
}

TEST(PlannerFactory, ErrorsNameTheProblem) {
  const auto si = se3();
  try {
    makePlanner("rrtt", si);
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown planner 'rrtt'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("rrtconnect"), std::string::npos);
  }
  EXPECT_THROW(makePlanner("rrt", si, {{"rnage", "1"}}), InvalidInputError);
}

}  // namespace
}  // namespace mddual::planning
