// The planner factory: OMPL.app's names, OMPL's, ours, parameters, the
// planners `mddual bench --planners` selects, and errors.
#include <gtest/gtest.h>

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <string>

#include "mddual/error.h"
#include "mddual/planning/planner_factory.h"
#include "mddual/scene/problem_config.h"
#include "planner_budget.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

/// Iterations each planner gets in the short solves below (a count, not a
/// time: the same outcome on any machine; planner_budget.h).
constexpr long kShortSolve = 2000;

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
  EXPECT_EQ(makePlanner("mdd_rrtconnect", si)->getName(), "mdd_rrtconnect");
}

TEST(PlannerFactory, DiscardedLastValidFractionIsTheKpieceFamilysMinValidPathFraction) {
  const auto si = se3();
  // OMPL 1.5's defaults: 0.2 for KPIECE1 and STRIDE, 0.5 for the bidirectional two.
  for (const auto& [name, fraction] :
       std::map<std::string, double>{{"kpiece", 0.2}, {"bkpiece", 0.5}, {"lbkpiece", 0.5}, {"stride", 0.2}}) {
    EXPECT_EQ(discardedLastValidFraction(*makePlanner(name, si)), fraction) << name;
    EXPECT_EQ(discardedLastValidFraction(*makePlanner(name, si, {{"min_valid_path_fraction", "0.35"}})), 0.35) << name;
  }
  for (const char* name : {"rrt", "rrtconnect", "mdd_rrtconnect", "est", "pdst", "prm"}) {
    EXPECT_EQ(discardedLastValidFraction(*makePlanner(name, si)), 0.0) << name;
  }
}

TEST(PlannerFactory, BuildsEveryPlannerAConfigMayName) {
  const auto si = se3();
  for (const std::string& name : scene::knownPlannerNames()) {
    EXPECT_NE(makePlanner(name, si), nullptr) << name;
  }
}

/// A small problem: the space's bounds are [-1, 1] (position), a ball of
/// radius 0.3 at the origin is the obstacle, start and goal on either side.
std::shared_ptr<og::SimpleSetup> ballProblem(bool planar) {
  ob::RealVectorBounds bounds(planar ? 2 : 3);
  bounds.setLow(-1);
  bounds.setHigh(1);
  ob::StateSpacePtr space;
  if (planar) {
    auto se2 = std::make_shared<ob::SE2StateSpace>();
    se2->setBounds(bounds);
    space = se2;
  } else {
    auto se3 = std::make_shared<ob::SE3StateSpace>();
    se3->setBounds(bounds);
    space = se3;
  }
  auto ss = std::make_shared<og::SimpleSetup>(space);
  ss->setStateValidityChecker([planar](const ob::State* s) {
    double x = 0;
    double y = 0;
    double z = 0;
    if (planar) {
      const auto* p = s->as<ob::SE2StateSpace::StateType>();
      x = p->getX();
      y = p->getY();
    } else {
      const auto* p = s->as<ob::SE3StateSpace::StateType>();
      x = p->getX();
      y = p->getY();
      z = p->getZ();
    }
    return x * x + y * y + z * z > 0.3 * 0.3;
  });
  ob::ScopedState<> start(space);
  ob::ScopedState<> goal(space);
  start = std::vector<double>(space->getDimension() == 3 ? 3 : 7, 0.0);
  goal = std::vector<double>(space->getDimension() == 3 ? 3 : 7, 0.0);
  start[0] = -0.8;
  goal[0] = 0.8;
  if (!planar) {
    start[6] = 1.0;  // identity quaternion (x, y, z, w)
    goal[6] = 1.0;
  }
  ss->setStartAndGoalStates(start, goal, 0.05);
  return ss;
}

// Every planner name (OMPL.app's, the rest of OMPL 1.5's
// geometric planners that need only the space information, ours) builds a
// planner that sets up and runs on a small SE(2) and SE(3) problem, seeded
// and within a budget of iterations; all but SST solve it, with a valid path.
TEST(PlannerFactory, EveryNameSolvesASmallProblemBriefly) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(42);
  for (const bool planar : {true, false}) {
    for (const std::string& name : plannerNames()) {
      SCOPED_TRACE(name + (planar ? " (SE2)" : " (SE3)"));
      const auto ss = ballProblem(planar);
      ob::PlannerPtr planner;
      ASSERT_NO_THROW(planner = makePlanner(name, ss->getSpaceInformation()));
      ss->setPlanner(planner);
      ob::PlannerStatus status;
      // Until the first exact solution or the budget (the optimizing planners
      // run to it: 2,000 iterations, up to 0.8 s each, 5 s in all). Some
      // planners evaluate the condition from several threads, and a shared
      // count would depend on their interleaving: prm, prmstar, spars and
      // spars2 count their main thread's iterations only (their other thread
      // checks for a solution in a busy loop); cforest, prrt and psbl, whose
      // worker threads do the iterations, get ten times the budget (they
      // solve within 315); aps, whose main thread spins while its sub-planner
      // works, stops at its first exact solution (the safety net aside).
      const std::set<std::string> kMainThread = {"prm", "prmstar", "spars", "spars2"};
      const std::set<std::string> kWorkers = {"cforest", "prrt", "psbl"};
      // prm and spars2 also get ten times the budget: their solution check,
      // every millisecond, must see the roadmap connected before the budget
      // ends (they stop then, or after 0.2 s). sorrtstar's iterations are the
      // slowest (8 s for 2,000): it gets 500.
      const bool more = kWorkers.count(name) > 0 || name == "prm" || name == "spars2";
      const long iterations = more ? 10 * kShortSolve : (name == "sorrtstar" ? 500 : kShortSolve);
      const ob::PlannerTerminationCondition budget =
          name == "aps" ? ob::timedPlannerTerminationCondition(testing::kPlannerSafetyNetSeconds)
                        : testing::iterationBudget(iterations, kMainThread.count(name) > 0);
      ASSERT_NO_THROW(status = ss->solve(ob::plannerOrTerminationCondition(
                          ob::exactSolnPlannerTerminationCondition(ss->getProblemDefinition()), budget)));
      // Every planner solves this easy problem within the budget (the most a
      // non-optimizing one needed was 1,569 iterations), except SST, whose
      // sparse tree only comes near the goal (an approximate solution).
      EXPECT_EQ(ob::PlannerStatus::StatusType(status),
                name == "sst" ? ob::PlannerStatus::APPROXIMATE_SOLUTION : ob::PlannerStatus::EXACT_SOLUTION)
          << status.asString();
      if (ob::PlannerStatus::StatusType(status) == ob::PlannerStatus::EXACT_SOLUTION) {
        EXPECT_TRUE(ss->getSolutionPath().check());
      }
    }
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
}

// The names OMPL gives its planners (Planner::getName()) are accepted in any
// case and stand for the registry's names.
TEST(PlannerFactory, OmplsOwnNamesAndAnyCaseAreAccepted) {
  const auto si = se3();
  for (const std::string& name : plannerNames()) {
    const std::string own = makePlanner(name, si)->getName();
    std::string upper = name;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    EXPECT_EQ(canonicalPlannerName(own), name) << own;
    EXPECT_EQ(canonicalPlannerName(upper), name) << upper;
  }
  EXPECT_EQ(makePlanner("KPIECE1", si)->getName(), "KPIECE1");
  EXPECT_EQ(canonicalPlannerName("kpiece1"), "kpiece");
  EXPECT_EQ(canonicalPlannerName("SPARStwo"), "spars2");
  EXPECT_EQ(canonicalPlannerName("rrtt"), "");
  EXPECT_EQ(canonicalPlannerName(""), "");
}

scene::PlannerSpec spec(const std::string& name, std::vector<std::pair<std::string, std::string>> params, int line) {
  scene::PlannerSpec p;
  p.name = name;
  p.params = std::move(params);
  p.line = line;
  return p;
}

std::vector<std::string> namesOf(const std::vector<scene::PlannerSpec>& specs) {
  std::vector<std::string> out;
  for (const auto& p : specs) out.push_back(p.name);
  return out;
}

// `mddual bench --planners`: the cfg's instances when it lists the planner,
// one with OMPL's defaults when it does not.
TEST(PlannerSelection, ListedInstancesOrDefaults) {
  const std::vector<scene::PlannerSpec> listed = {spec("rrt", {{"range", "5"}}, 10), spec("rrtconnect", {}, 11),
                                                  spec("rrt", {{"range", "9"}}, 12)};
  EXPECT_EQ(selectPlannerSpecs(listed, {}, "a.cfg"), listed);
  const auto rrt = selectPlannerSpecs(listed, {"rrt"}, "a.cfg");
  ASSERT_EQ(rrt.size(), 2u);
  EXPECT_EQ(rrt[0].params, (std::vector<std::pair<std::string, std::string>>{{"range", "5"}}));
  EXPECT_EQ(rrt[1].line, 12);
  EXPECT_EQ(namesOf(selectPlannerSpecs(listed, {"RRT"}, "a.cfg")), (std::vector<std::string>{"rrt", "rrt"}));
  const auto mixed = selectPlannerSpecs(listed, {"KPIECE1", "rrtconnect", "prm", "prm", "kpiece"}, "a.cfg");
  EXPECT_EQ(namesOf(mixed), (std::vector<std::string>{"rrtconnect", "kpiece", "prm"}));
  EXPECT_TRUE(mixed[1].params.empty());
  EXPECT_EQ(mixed[1].line, 0);
  // A cfg without planners runs the ones asked for.
  EXPECT_EQ(namesOf(selectPlannerSpecs({}, {"rrtconnect"}, "a.cfg")), (std::vector<std::string>{"rrtconnect"}));
}

TEST(PlannerSelection, ErrorsNameTheCfgAndTheKnownPlanners) {
  const std::vector<scene::PlannerSpec> listed = {spec("rrt", {}, 3), spec("rrtconnect", {}, 4), spec("rrt", {}, 5)};
  try {
    selectPlannerSpecs(listed, {"rrtconnect", "rrtt"}, "a.cfg");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown planner 'rrtt': not in a.cfg (its planners: rrt, rrtconnect) and not a planner name "
                     "(known: abitstar, "),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("mdd_rrtconnect"), std::string::npos) << m;
  }
  try {
    selectPlannerSpecs({}, {}, "b.cfg");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("b.cfg: the [planner] section names no planner"), std::string::npos)
        << e.what();
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
  // A hostile-input hunt's cases: a real parameter that is no finite number
  // failed with OMPL's "Failed converting string to real number", naming
  // neither; each message now names the planner, the parameter and the value.
  for (const char* bad : {"nan", "inf", "abc", "1.5x", ""}) {
    try {
      makePlanner("rrtconnect", si, {{"range", bad}});
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("planner 'rrtconnect': parameter 'range' = '") + bad + "': not a finite number");
    }
  }
  try {
    makePlanner("prm", si, {{"max_nearest_neighbors", "many"}});  // an integer parameter
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("planner 'prm': parameter 'max_nearest_neighbors' = 'many'"),
              std::string::npos)
        << e.what();
  }
  // Outside the range OMPL declares: a warning only (a range may exceed it).
  struct Capture : ompl::msg::OutputHandler {
    void log(const std::string& text, ompl::msg::LogLevel level, const char*, int) override {
      if (level == ompl::msg::LOG_WARN) warnings += text + "\n";
    }
    std::string warnings;
  } capture;
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::msg::useOutputHandler(&capture);
  EXPECT_EQ(makePlanner("rrt", si, {{"range", "20000"}})->params().getParam("range")->getValue(), "20000");
  makePlanner("rrt", si, {{"goal_bias", "0.5"}});  // inside: no warning
  makePlanner("rrt", si, {{"goal_bias", "5"}});
  ompl::msg::restorePreviousOutputHandler();
  ompl::msg::setLogLevel(level);
  EXPECT_EQ(capture.warnings,
            "planner 'rrt': parameter 'range' = '20000': outside the range OMPL declares for it, [0., 10000.]\n"
            "planner 'rrt': parameter 'goal_bias' = '5': outside the range OMPL declares for it, [0., 1.]\n");
}

/// The message of makePlanner(planner, se3(), {{key, value}}), or "" when it is accepted.
std::string refusal(const std::string& planner, const std::string& key, const std::string& value) {
  try {
    makePlanner(planner, se3(), {{key, value}});
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

// A hostile-input hunt's cases: OMPL's conversion stored -1 as 4294967295 in
// an unsigned parameter (FMT* then sampled without end), 2.5 as 2 and 1e300
// as 1; a boolean took "no", "off" and "abc" as true. Each is refused with the
// planner, the parameter and the value named.
TEST(PlannerFactory, IntegerAndBooleanParametersAreCheckedForTheirType) {
  const std::string at = "planner 'fmt': parameter 'num_samples' = '";
  EXPECT_EQ(refusal("fmt", "num_samples", "-1"), at + "-1': must be 0 or more");
  EXPECT_EQ(refusal("fmt", "num_samples", "2.5"), at + "2.5': not an integer");
  EXPECT_EQ(refusal("fmt", "num_samples", "1e300"), at + "1e300': not an integer");
  EXPECT_EQ(refusal("fmt", "num_samples", ""), at + "': not an integer");
  EXPECT_EQ(refusal("fmt", "num_samples", "4294967296"), at + "4294967296': out of range (0 to 4294967295)");
  EXPECT_EQ(refusal("fmt", "num_samples", "5000"), "");
  EXPECT_EQ(makePlanner("fmt", se3(), {{"num_samples", "+5000"}})->params().getParam("num_samples")->getValue(),
            "5000");
  EXPECT_EQ(makePlanner("fmt", se3(), {{"num_samples", "-0"}})->params().getParam("num_samples")->getValue(), "0");
  EXPECT_EQ(refusal("fmt", "num_samples", "+-5"), at + "+-5': not an integer");
  // A signed integer (RRTXstatic's rejection_variant) takes a sign; a size_t (AIT*'s batch) none.
  EXPECT_EQ(refusal("rrtxstatic", "rejection_variant", "2"), "");
  EXPECT_EQ(refusal("rrtxstatic", "rejection_variant", "-1"),  // parsed, then OMPL's own check
            "planner 'rrtxstatic': parameter 'rejection_variant' = '-1': Variant must be 0 (original RRT#) or in "
            "[1, 3]");
  EXPECT_EQ(refusal("rrtxstatic", "rejection_variant", "2147483648"),
            "planner 'rrtxstatic': parameter 'rejection_variant' = '2147483648': out of range (-2147483648 to "
            "2147483647)");
  EXPECT_EQ(refusal("aitstar", "samples_per_batch", "-5"),
            "planner 'aitstar': parameter 'samples_per_batch' = '-5': must be 0 or more");
  for (const char* yes : {"1", "true", "Yes", "ON", "t"}) {
    const ob::PlannerPtr p = makePlanner("mdd_rrtconnect", se3(), {{"rotate_first", yes}});
    EXPECT_EQ(p->params().getParam("rotate_first")->getValue(), "1") << yes;
  }
  for (const char* no : {"0", "false", "no", "Off", "F"}) {
    const ob::PlannerPtr p = makePlanner("mdd_rrtconnect", se3(), {{"rotate_first", no}});
    EXPECT_EQ(p->params().getParam("rotate_first")->getValue(), "0") << no;
  }
  // mdd_rrtconnect's step when blocked: a finite distance >= 0 and a boolean.
  EXPECT_EQ(makePlanner("mdd_rrtconnect", se3(), {{"whole_edge_last_valid", "yes"}})
                ->params()
                .getParam("whole_edge_last_valid")
                ->getValue(),
            "1");
  EXPECT_EQ(refusal("mdd_rrtconnect", "blocked_range", "2.5"), "");
  EXPECT_EQ(refusal("mdd_rrtconnect", "blocked_range", "inf"),
            "planner 'mdd_rrtconnect': parameter 'blocked_range' = 'inf': not a finite number");
  EXPECT_EQ(refusal("mdd_rrtconnect", "blocked_range", "-1"),
            "planner 'mdd_rrtconnect': parameter 'blocked_range' = '-1': mdd_rrtconnect: blocked_range must be a "
            "finite distance >= 0 (0: OMPL's default range), got -1");
  for (const char* bad : {"abc", "", "-1", "00", "0.0"}) {
    EXPECT_EQ(refusal("mdd_rrtconnect", "rotate_first", bad),
              std::string("planner 'mdd_rrtconnect': parameter 'rotate_first' = '") + bad +
                  "': not a boolean (true/false, t/f, 1/0, yes/no, on/off)");
  }
}

// Values at which OMPL 1.5.2's planner crashes or aborts (hardMinimum in
// planner_factory.cpp): refused; the smallest value that runs is accepted.
TEST(PlannerFactory, ValuesThatCrashOmplAreRefused) {
  const std::vector<std::pair<std::string, std::string>> crashing = {
      {"aps", "num_planners"},  {"stride", "degree"},     {"stride", "min_degree"},
      {"psbl", "thread_count"}, {"prrt", "thread_count"}, {"aitstar", "samples_per_batch"},
  };
  for (const auto& [planner, key] : crashing) {
    EXPECT_EQ(refusal(planner, key, "0"), "planner '" + planner + "': parameter '" + key +
                                              "' = '0': must be at least 1 (OMPL's planner fails below it)");
    EXPECT_EQ(refusal(planner, key, "1"), "") << planner << "." << key;
  }
  EXPECT_EQ(refusal("cforest", "num_threads", "0"), "");  // runs (checked alone in OMPL 1.5.2)
}

// APS's list of planners, read as OMPL 1.5.2 reads it: it logged an unknown
// name and went on without it (the parameters after it went to the planner
// before it, or indexed an empty list), and indexed past a piece without '='.
TEST(PlannerFactory, ApsPlannersAreCheckedAsOmplReadsThem) {
  const std::string at = "planner 'aps': parameter 'planners' = '";
  const std::string what =
      "' is not a planner APS makes (OMPL's class names, e.g. RRTConnect,PRM; no spaces around commas; parameters "
      "in brackets are separated by spaces)";
  EXPECT_EQ(refusal("aps", "planners", "foo"), at + "foo': 'foo' in 'foo" + what);
  EXPECT_EQ(refusal("aps", "planners", "RRTConnect, PRM"), at + "RRTConnect, PRM': '' in ' PRM" + what);
  EXPECT_EQ(refusal("aps", "planners", "PRM[max_nearest_neighbors=8,range=1]"),
            at + "PRM[max_nearest_neighbors=8,range=1]': 'range=1' in 'range=1]" + what);
  EXPECT_EQ(refusal("aps", "planners", "LazyLBTRRT"), at + "LazyLBTRRT': 'LazyLBTRRT' in 'LazyLBTRRT" + what);
  EXPECT_EQ(refusal("aps", "planners", "RRTConnect[range]"),
            at + "RRTConnect[range]': 'range' in 'RRTConnect[range]' is not key=value");
  // The bracketed parameters are checked as a planner's own.
  EXPECT_EQ(refusal("aps", "planners", "STRIDE[degree=0]"),
            at + "STRIDE[degree=0]': planner 'stride': parameter 'degree' = '0': must be at least 1 (OMPL's planner "
                 "fails below it)");
  EXPECT_EQ(refusal("aps", "planners", "RRTConnect[rnage=1]"),
            at + "RRTConnect[rnage=1]': planner 'rrtconnect' has no parameter 'rnage'");
  EXPECT_EQ(refusal("aps", "planners", ""), "");  // OMPL's default planners
  EXPECT_EQ(refusal("aps", "planners", "RRTConnect,PRM"), "");
  const ob::PlannerPtr aps =
      makePlanner("aps", se3(), {{"planners", "RRTConnect[range=0.5],PRM[max_nearest_neighbors=8]"}});
  EXPECT_EQ(aps->params().getParam("planners")->getValue(),
            "RRTConnect[intermediate_states=0 range=0.5],PRM[max_nearest_neighbors=8]");
}

TEST(PlannerFactory, NamesAreCheckedForTheResultsTable) {
  EXPECT_EQ(refusal("mdd_rrtconnect", "name", ""), "planner 'mdd_rrtconnect': name is empty");
  const std::string table = "': control characters and '|' are not allowed (the results table)";
  EXPECT_EQ(refusal("mdd_rrtconnect", "name", "x|y"), "planner 'mdd_rrtconnect': name 'x|y" + table);
  EXPECT_EQ(refusal("rrt", "name", "two\nlines"), "planner 'rrt': name 'two?lines" + table);  // shown as '?'
  // Another planner's name (it read as a second instance of that planner);
  // the planner's own name in any spelling is fine.
  EXPECT_EQ(refusal("mdd_rrtconnect", "name", "rrtconnect"),
            "planner 'mdd_rrtconnect': name 'rrtconnect' is the name of another planner, 'rrtconnect'");
  EXPECT_EQ(refusal("mdd_rrtconnect", "name", "RRTConnect"),
            "planner 'mdd_rrtconnect': name 'RRTConnect' is the name of another planner, 'rrtconnect'");
  EXPECT_EQ(refusal("rrt", "name", "RRT"), "");
  EXPECT_EQ(refusal("kpiece", "name", "KPIECE1"), "");
  EXPECT_EQ(refusal("rrt", "name", "rrt with range 2"), "");
  EXPECT_EQ(refusal("rrt", "name", std::string(300, 'x') + "|"),
            "planner 'rrt': name '" + std::string(200, 'x') + "... (301 bytes)" + table);
}

}  // namespace
}  // namespace mddual::planning
