// The planning front end: shard parsing, a cfg's problem set up in
// OMPL (space parameters, planner parameters and contexts, start, goal,
// threshold, objective), the checkers' counters, and its errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mddual/error.h"
#include "mddual/planning/bench_runner.h"
#include "mddual/planning/problem_setup.h"
#include "planner_budget.h"
#include "tiny_config.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace fs = std::filesystem;

/// A fresh folder per test, removed at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("mddual_frontend_" + std::string(info->test_suite_name()) + "_" +
                                         info->name() + "_" + std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// Expects `f` to throw InvalidInputError whose message contains `needle`.
void expectError(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error (expected one mentioning '" << needle << "')";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(FrontendNames, Shards) {
  const BenchShard s = parseShard("1/3");
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(s.sharded());
  EXPECT_FALSE(parseShard("0/1").sharded());
  EXPECT_EQ(toString(s), "1/3");
  for (const char* bad : {"3/2", "2/2", "-1/2", "1", "a/b", "1/0", "/2", "1/", "0/2/3", " 0/2"}) {
    expectError([bad] { parseShard(bad); }, "--shard '" + std::string(bad) + "'");
  }
  EXPECT_EQ(shardRuns(7, parseShard("1/3")), (std::vector<int>{1, 4}));
  EXPECT_EQ(shardRuns(7, parseShard("0/1")), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  // The shards of any N partition the runs.
  for (int n = 1; n <= 5; ++n) {
    std::vector<int> seen(9, 0);
    for (int i = 0; i < n; ++i) {
      for (int r : shardRuns(9, BenchShard{i, n})) ++seen[static_cast<std::size_t>(r)];
    }
    EXPECT_EQ(seen, std::vector<int>(9, 1)) << n;
  }
  EXPECT_EQ(logFileName("tiny", "fcl-continuous", BenchShard{}), "tiny-fcl-continuous.log");
  EXPECT_EQ(logFileName("tiny", "mdd", BenchShard{1, 4}), "tiny-mdd.shard1of4.log");
}

class FrontendSetup : public ::testing::Test {
 protected:
  void SetUp() override { ompl::msg::setLogLevel(ompl::msg::LOG_ERROR); }
  TempDir dir_;
};

TEST_F(FrontendSetup, SetsSpaceParametersPlannerParametersAndContexts) {
  testing::TinyConfigText text;
  text.problem_extra = "longest_valid_segment_fraction = 0.05\nthreshold = 0.01\nobjective = length\n";
  text.planners =
      "rrtconnect =\nrrtconnect.range = 3.5\n"
      "rrt =\nproblem.longest_valid_segment_fraction = 0.2\nrrt.goal_bias = 0.25\n"
      "mdd_rrtconnect =\n";
  const Problem problem = loadProblem(testing::writeTinyConfig(dir_.path(), text));
  EXPECT_EQ(problem.name, "tiny");
  ASSERT_EQ(problem.config.planners.size(), 3u);
  for (const std::string& kind : rigidCheckerNames()) {
    ProblemSetup setup(problem, kind);
    const ob::SpaceInformationPtr& si = setup.spaceInformation();
    const ob::StateSpacePtr& space = si->getStateSpace();
    const double extent = space->getMaximumExtent();
    EXPECT_NEAR(extent, std::sqrt(300.0), 1e-12);
    // The cfg's space parameter, in effect (the segment length follows it).
    EXPECT_DOUBLE_EQ(space->getLongestValidSegmentFraction(), 0.05);
    EXPECT_NEAR(space->getLongestValidSegmentLength(), 0.05 * extent, 1e-12);
    EXPECT_EQ(setup.planningSpace()->kind(), SpaceKind::kR3);

    // Planners: the cfg's names and parameters.
    const ob::PlannerPtr connect = setup.makePlanner(problem.config.planners[0]);
    EXPECT_EQ(connect->getName(), "rrtconnect");
    EXPECT_EQ(connect->params().getParam("range")->getValue(), "3.5");
    const ob::PlannerPtr rrt = setup.makePlanner(problem.config.planners[1]);
    EXPECT_EQ(rrt->getName(), "rrt");
    EXPECT_EQ(rrt->params().getParam("goal_bias")->getValue(), "0.25");
    EXPECT_EQ(setup.makePlanner(problem.config.planners[2])->getName(), "mdd_rrtconnect");
    // A planner made in code (no cfg line): the message names the cfg, not a line 0.
    scene::PlannerSpec unknown;
    unknown.name = "nosuch";
    try {
      setup.makePlanner(unknown);
      ADD_FAILURE() << "an unknown planner was made";
    } catch (const InvalidInputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("tiny.cfg: unknown planner 'nosuch'", 0), 0u) << e.what();
    }
    // The MDD scene is exposed only with the MDD checkers.
    EXPECT_EQ(setup.mddScene() != nullptr, kind == "mdd");

    // Contexts: rrt's on top of the space parameters, and reset for the others.
    setup.applyPlannerContext(problem.config.planners[1]);
    EXPECT_DOUBLE_EQ(space->getLongestValidSegmentFraction(), 0.2);
    EXPECT_NEAR(space->getLongestValidSegmentLength(), 0.2 * extent, 1e-12);
    setup.applyPlannerContext(problem.config.planners[2]);
    EXPECT_DOUBLE_EQ(space->getLongestValidSegmentFraction(), 0.05);
    EXPECT_NEAR(space->getLongestValidSegmentLength(), 0.05 * extent, 1e-12);
    // R^3's default projection: the position, cells of 1/20 of the bounds,
    // kept through the set-ups above (not OMPL's random 2-D map).
    const ob::ProjectionEvaluatorPtr projection = space->getDefaultProjection();
    EXPECT_EQ(projection->getDimension(), 3u);
    EXPECT_EQ(projection->getCellSizes(), (std::vector<double>{0.5, 0.5, 0.5}));
    ob::ScopedState<> s(space);
    setup.planningSpace()->setPose(problem.scene->goal, s.get());
    Eigen::VectorXd p(3);
    projection->project(s.get(), p);
    EXPECT_TRUE(p.isApprox(Eigen::Vector3d(8, 5, 5)));

    // Start, goal, threshold, objective.
    const ob::ProblemDefinitionPtr& pdef = setup.simpleSetup().getProblemDefinition();
    ASSERT_EQ(pdef->getStartStateCount(), 1u);
    const Eigen::Isometry3d start = setup.planningSpace()->pose(pdef->getStartState(0));
    EXPECT_TRUE(start.translation().isApprox(Eigen::Vector3d(2, 5, 5)));
    const auto* goal = dynamic_cast<const ob::GoalState*>(pdef->getGoal().get());
    ASSERT_NE(goal, nullptr);
    EXPECT_DOUBLE_EQ(goal->getThreshold(), 0.01);
    EXPECT_TRUE(setup.planningSpace()->pose(goal->getState()).translation().isApprox(Eigen::Vector3d(8, 5, 5)));
    EXPECT_TRUE(pdef->hasOptimizationObjective());
  }
}

TEST_F(FrontendSetup, DefaultsAndPlannersSolveWithEveryChecker) {
  const Problem problem = loadProblem(testing::writeTinyConfig(dir_.path()));
  for (const std::string& kind : rigidCheckerNames()) {
    ProblemSetup setup(problem, kind);
    const auto& pdef = setup.simpleSetup().getProblemDefinition();
    const auto* goal = dynamic_cast<const ob::GoalState*>(pdef->getGoal().get());
    ASSERT_NE(goal, nullptr);
    EXPECT_DOUBLE_EQ(goal->getThreshold(), scene::kDefaultGoalThreshold);
    EXPECT_FALSE(pdef->hasOptimizationObjective());
    EXPECT_DOUBLE_EQ(setup.spaceInformation()->getStateSpace()->getLongestValidSegmentFraction(), 0.01);
    setup.simpleSetup().setPlanner(setup.makePlanner(problem.config.planners[1]));
    setup.resetStats();
    EXPECT_EQ(setup.simpleSetup().solve(testing::iterationBudget(testing::kPlannerIterations)),
              ob::PlannerStatus::EXACT_SOLUTION)
        << kind;
    const CheckStats st = setup.stats();
    EXPECT_GT(st.motion_checks, 0u) << kind;
    EXPECT_GT(st.state_checks, 0u) << kind;
    EXPECT_GT(st.seconds, 0.0) << kind;
    setup.resetStats();
    EXPECT_EQ(setup.stats().motion_checks, 0u);
    EXPECT_EQ(setup.stats().seconds, 0.0);
  }
}

TEST_F(FrontendSetup, CountsChecksOnceAndTimesThemOnce) {
  const Problem problem = loadProblem(testing::writeTinyConfig(dir_.path()));
  for (const std::string& kind : rigidCheckerNames()) {
    ProblemSetup setup(problem, kind);
    const ob::SpaceInformationPtr& si = setup.spaceInformation();
    ob::ScopedState<> a(si->getStateSpace());
    ob::ScopedState<> b(si->getStateSpace());
    setup.planningSpace()->setPose(problem.scene->start, a.get());
    Eigen::Isometry3d X = problem.scene->start;
    X.translation().y() = 7.5;  // through the door: free
    setup.planningSpace()->setPose(X, b.get());
    setup.resetStats();
    EXPECT_TRUE(si->isValid(a.get()));
    EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
    const CheckStats st = setup.stats();
    EXPECT_EQ(st.motion_checks, 1u) << kind;
    // fcl: OMPL's discrete validator checks its samples with the state checker.
    if (kind == "fcl") {
      EXPECT_GT(st.state_checks, 2u);
    } else {
      EXPECT_GE(st.state_checks, 1u);
    }
    EXPECT_EQ(si->getMotionValidator()->getValidMotionCount(), 1u);
    EXPECT_GT(st.seconds, 0.0);
  }
}

// A planar translation-only problem (R^2) with KPIECE, which uses the space's
// default projection (OMPL 1.5.2's own for R^2 trips an Eigen assertion).
TEST_F(FrontendSetup, PlanarTranslationOnlyWithKpiece) {
  testing::writeTinyConfig(dir_.path());  // robot and world
  testing::writeTextFile(dir_.path() / "planar.cfg",
                         "[problem]\nrobot = robot.urdf\nworld = world.urdf\nstart.x = 2\nstart.y = 5\n"
                         "start.theta = 0\ngoal.x = 8\ngoal.y = 5\ngoal.theta = 0\nvolume.min.x = 0\n"
                         "volume.min.y = 0\nvolume.max.x = 10\nvolume.max.y = 10\ntranslation_only = true\n"
                         "[planner]\nkpiece =\n");
  const Problem problem = loadProblem(dir_.path() / "planar.cfg");
  EXPECT_EQ(problem.name, "planar");
  for (const std::string& kind : rigidCheckerNames()) {
    ProblemSetup setup(problem, kind);
    EXPECT_EQ(setup.planningSpace()->kind(), SpaceKind::kR2);
    EXPECT_EQ(setup.spaceInformation()->getStateSpace()->getDefaultProjection()->getDimension(), 2u);
    setup.simpleSetup().setPlanner(setup.makePlanner(problem.config.planners[0]));
    EXPECT_EQ(setup.simpleSetup().solve(testing::iterationBudget(testing::kPlannerIterations)),
              ob::PlannerStatus::EXACT_SOLUTION)
        << kind;
  }
}

// A convex robot against a world mesh (triangles): FCL 0.7's conservative
// advancement between a shape and a mesh crashes or misses contacts; the FCL
// baseline checks such pairs as two meshes (planners/ompl/src/fcl_scene.cpp).
TEST_F(FrontendSetup, ContinuousCheckerWithAMeshWorld) {
  // Two separate boxes in one OBJ: not convex, so it loads as triangles.
  std::string obj;
  for (const double x0 : {4.0, 6.0}) {
    for (int i = 0; i < 8; ++i) {
      obj += "v " + std::to_string(i & 1 ? x0 + 0.05 : x0) + " " + std::to_string(i & 2 ? 10.0 : 0.0) + " " +
             std::to_string(i & 4 ? 10.0 : 0.0) + "\n";
    }
  }
  for (const int base : {1, 9}) {
    for (const auto& f : {std::array<int, 3>{0, 1, 3},
                          {0, 3, 2},
                          {4, 7, 5},
                          {4, 6, 7},
                          {0, 5, 1},
                          {0, 4, 5},
                          {2, 3, 7},
                          {2, 7, 6},
                          {0, 2, 6},
                          {0, 6, 4},
                          {1, 7, 3},
                          {1, 5, 7}}) {
      obj += "f " + std::to_string(base + f[0]) + " " + std::to_string(base + f[1]) + " " +
             std::to_string(base + f[2]) + "\n";
    }
  }
  const fs::path cfg = testing::writeTinyConfig(dir_.path());
  testing::writeTextFile(dir_.path() / "walls.obj", obj);
  testing::writeTextFile(dir_.path() / "world.urdf",
                         "<?xml version=\"1.0\"?>\n<robot name=\"walls\"><link name=\"walls\"><collision><geometry>"
                         "<mesh filename=\"walls.obj\"/></geometry></collision></link></robot>\n");
  const Problem problem = loadProblem(cfg);
  ASSERT_GT(problem.world()->pieces().size(), 2u);
  EXPECT_EQ(problem.world()->pieces()[0].kind, scene::PieceKind::kTriangle);
  for (const FclCcdSolver solver : {FclCcdSolver::kConservativeAdvancement, FclCcdSolver::kNaive}) {
    SetupOptions options;
    options.continuous_solver = solver;
    ProblemSetup setup(problem, "fcl-continuous", options);
    const ob::SpaceInformationPtr& si = setup.spaceInformation();
    ob::ScopedState<> a(si->getStateSpace());
    ob::ScopedState<> b(si->getStateSpace());
    auto at = [&](double x, ob::ScopedState<>& s) {
      Eigen::Isometry3d X = problem.scene->start;
      X.translation().x() = x;
      setup.planningSpace()->setPose(X, s.get());
    };
    at(4.5, a);
    at(5.5, b);
    EXPECT_TRUE(si->checkMotion(a.get(), b.get()));  // between the walls
    at(2.0, a);
    at(5.0, b);
    std::pair<ob::State*, double> last(nullptr, -1.0);
    const bool valid = si->checkMotion(a.get(), b.get(), last);  // through the first wall
    if (solver == FclCcdSolver::kNaive) {
      EXPECT_FALSE(valid);  // 10 samples 0.33 apart: the 0.55 overlap interval is seen
      EXPECT_GE(last.second, 0.0);
      EXPECT_LE(2.0 + 3.0 * last.second, 4.0 - 0.25);
    } else {
      // Conservative advancement: no crash, and FCL 0.7's known answer (its
      // mesh-mesh advancement misses this wall), pinned so that a change of
      // FCL's behaviour shows here: the baseline's misses are measured by
      // the benchmarks.
      EXPECT_TRUE(valid) << "FCL's conservative advancement now sees the wall: update this test and the baseline's "
                            "description";
    }
    EXPECT_EQ(setup.stats().motion_checks, 2u);
  }
}

TEST_F(FrontendSetup, Errors) {
  {
    testing::TinyConfigText text;
    text.problem_extra = "no_such_parameter = 3\n";
    const Problem p = loadProblem(testing::writeTinyConfig(dir_.path(), text));
    expectError([&] { ProblemSetup s(p, "mdd"); }, "no_such_parameter: not a parameter");
  }
  {
    testing::TinyConfigText text;
    text.problem_extra = "longest_valid_segment_fraction = 7\n";
    const Problem p = loadProblem(testing::writeTinyConfig(dir_.path(), text));
    expectError([&] { ProblemSetup s(p, "fcl"); }, "longest_valid_segment_fraction: OMPL rejects");
  }
  {
    testing::TinyConfigText text;
    text.problem_extra = "sampler = fancy\n";
    const Problem p = loadProblem(testing::writeTinyConfig(dir_.path(), text));
    expectError([&] { ProblemSetup s(p, "fcl"); }, "unknown sampler 'fancy'");
  }
  {
    testing::TinyConfigText text;
    text.planners = "rrtconnect =\nrrtconnect.no_such = 1\n";
    const Problem p = loadProblem(testing::writeTinyConfig(dir_.path(), text));
    ProblemSetup s(p, "mdd");
    expectError([&] { s.makePlanner(p.config.planners[0]); }, "tiny.cfg:33: planner 'rrtconnect' has no parameter");
  }
  {
    testing::TinyConfigText text;
    text.planners = "rrt =\nproblem.bogus = 1\n";
    const Problem p = loadProblem(testing::writeTinyConfig(dir_.path(), text));
    expectError([&] { ProblemSetup s(p, "mdd"); }, "tiny.cfg:33: problem.bogus: not a parameter");
  }
  // Planner selection by the cfg's names.
  const Problem p = loadProblem(testing::writeTinyConfig(dir_.path()));
  EXPECT_EQ(selectPlanners(p, {}).size(), 2u);
  ASSERT_EQ(selectPlanners(p, {"mdd_rrtconnect"}).size(), 1u);
  EXPECT_EQ(selectPlanners(p, {"mdd_rrtconnect"})[0].name, "mdd_rrtconnect");
  // A planner the cfg does not list runs with OMPL's defaults.
  ASSERT_EQ(selectPlanners(p, {"prm"}).size(), 1u);
  EXPECT_EQ(selectPlanners(p, {"prm"})[0].name, "prm");
  expectError([&] { selectPlanners(p, {"prn"}); },
              "unknown planner 'prn': not in tiny.cfg (its planners: rrtconnect, mdd_rrtconnect)");
  // Bad config files name the file and line.
  {
    testing::TinyConfigText text;
    text.problem_extra = "this line has no equals sign\n";
    const fs::path cfg = testing::writeTinyConfig(dir_.path() / "malformed", text);
    expectError([&] { loadProblem(cfg); }, "tiny.cfg:26");
  }
  expectError([&] { loadProblem(dir_.path() / "missing.cfg"); }, "missing.cfg");
}

/// The tiny cfg in `dir` with lines of it replaced (first -> second).
fs::path tinyConfigWith(const fs::path& dir, const std::vector<std::pair<std::string, std::string>>& edits) {
  const fs::path cfg = testing::writeTinyConfig(dir);
  std::ifstream in(cfg);
  std::ostringstream text;
  text << in.rdbuf();
  std::string edited = text.str();
  for (const auto& [from, to] : edits) {
    const std::size_t at = edited.find(from);
    if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the tiny cfg");
    edited.replace(at, from.size(), to);
  }
  testing::writeTextFile(cfg, edited);
  return cfg;
}

TEST_F(FrontendSetup, StartAndGoalAreCheckedBeforePlanning) {
  // The tiny cfg's own start and goal are free and within the bounds.
  EXPECT_NO_THROW(checkStartAndGoal(loadProblem(testing::writeTinyConfig(dir_.path() / "good"))));
  const std::string robot = "robot piece \"robot.urdf: link 'cube_link', collision 0 (box)\"";
  const std::string wall0 = "world piece \"world.urdf: link 'wall_link', collision 0 (box)\"";
  const std::string wall1 = "world piece \"world.urdf: link 'wall_link', collision 1 (box)\"";
  const std::string tail = " (exact check; touching counts as collision)";
  // The deepest overlap in closed form: the 0.5 m cube centred in the 0.02 m
  // wall leaves it by 0.25 + 0.01 along x (along y it would need 0.35 or
  // more); FCL's discrete check on the same boxes names a contact too.
  const std::string deep = "; the deepest overlap is 0.26 (penetration depth of pair 1 of 1)";
  const std::string fcl = "; FCL's collide() on the same pieces finds a contact";
  struct Case {
    std::vector<std::pair<std::string, std::string>> edits;
    std::string message;
  };
  const std::vector<Case> cases = {
      // The 0.5 m robot cube inside the wall (x in [4.99, 5.01], y < 6.5).
      {{{"start.x = 2\n", "start.x = 5\n"}},
       "tiny.cfg: the start state (position 5, 5, 5) is in collision: " + robot + " overlaps " + wall0 + tail + deep +
           fcl},
      // Its face on the wall's face: touching is a collision for the exact checker.
      {{{"goal.x = 8\n", "goal.x = 5.26\n"}},
       "tiny.cfg: the goal state (position 5.26, 5, 5) is in collision: " + robot + " touches " + wall0 + tail +
           "; every pair only touches (penetration depth 0)" + fcl},
      // In the wall above the door (y in [6.5, 8.5]): the other piece.
      {{{"start.x = 2\n", "start.x = 5\n"}, {"start.y = 5\n", "start.y = 8.6\n"}},
       "tiny.cfg: the start state (position 5, 8.6, 5) is in collision: " + robot + " overlaps " + wall1 + tail + deep +
           fcl},
      {{{"goal.x = 8\n", "goal.x = 12\n"}},
       "tiny.cfg: the goal state is outside the bounds of the space: goal.x = 12 is not in [0, 10] (volume.min.x, "
       "volume.max.x)"},
      {{{"start.z = 5\n", "start.z = -0.5\n"}},
       "tiny.cfg: the start state is outside the bounds of the space: start.z = -0.5 is not in [0, 10] (volume.min.z, "
       "volume.max.z)"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    SCOPED_TRACE(c.edits[0].second);
    const Problem p = loadProblem(tinyConfigWith(dir_.path() / std::to_string(i), c.edits));
    try {
      checkStartAndGoal(p);
      ADD_FAILURE() << "no error";
    } catch (const InvalidInputError& e) {
      EXPECT_EQ(std::string(e.what()), c.message);
    }
  }
  // Five world pieces on the start: three named, two counted.
  const fs::path cfg = testing::writeTinyConfig(dir_.path() / "crowd");
  std::string boxes;
  for (int k = 0; k < 5; ++k) {
    boxes += "<collision><origin xyz=\"2 5 " + std::to_string(4.8 + 0.1 * k) +
             "\"/><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>";
  }
  testing::writeTextFile(dir_.path() / "crowd" / "world.urdf",
                         "<?xml version=\"1.0\"?><robot name=\"crowd\"><link name=\"l\">" + boxes + "</link></robot>");
  try {
    checkStartAndGoal(loadProblem(cfg));
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("tiny.cfg: the start state (position 2, 5, 5) is in collision: " + robot + " overlaps ", 0),
              0u)
        << what;
    EXPECT_NE(what.find("; and 2 more pairs (exact check; touching counts as collision)"), std::string::npos) << what;
    // Boxes of 0.1 m at heights 4.8 .. 5.2 in the cube [4.75, 5.25]: the
    // middle one leaves it by 0.25 + 0.05 along any axis, the others by 0.1
    // or 0.2 along z.
    EXPECT_NE(what.find("; the deepest overlap is 0.3 (penetration depth of pair "), std::string::npos) << what;
    std::size_t named = 0;
    for (std::size_t at = what.find("world piece"); at != std::string::npos; at = what.find("world piece", at + 1)) {
      ++named;
    }
    EXPECT_EQ(named, kMaxCollisionsNamed);
  }
}

TEST_F(FrontendSetup, EachCheckerMustFindTheStartAndGoalFree) {
  // A start in the wall: every checker refuses it when the setup is made,
  // instead of OMPL's "invalid start" in every run.
  for (const std::string& kind : rigidCheckerNames()) {
    SCOPED_TRACE(kind);
    const Problem p = loadProblem(tinyConfigWith(dir_.path() / kind, {{"start.x = 2\n", "start.x = 5\n"}}));
    expectError([&] { ProblemSetup s(p, kind); },
                std::string("tiny.cfg: the start state is in collision for the ") + kind + " checker");
  }
  // Found by a hostile-input hunt: a world triangle 1e12 across, 0.75 m from
  // the robot. The exact check of the pieces may find the start free while the
  // MDD checker, within its precision at that size, finds it touching; the
  // bench then returned "success 0%" runs (status "invalid start") and exit 0.
  const fs::path cfg = testing::writeTinyConfig(dir_.path() / "huge");
  testing::writeTextFile(dir_.path() / "huge" / "world.obj", "v 3 -1e12 -1e12\nv 3 1e12 -1e12\nv 3 0 1e12\nf 1 2 3\n");
  std::ifstream in(cfg);
  std::ostringstream text;
  text << in.rdbuf();
  std::string edited = text.str();
  edited.replace(edited.find("world = world.urdf"), 18, "world = world.obj");
  testing::writeTextFile(cfg, edited);
  const Problem p = loadProblem(cfg);
  // Either the setup says so, or its checker finds the start free (without
  // the check, the setup was made with a start its checker refuses).
  try {
    ProblemSetup s(p, "mdd");
    EXPECT_TRUE(s.spaceInformation()->isValid(s.simpleSetup().getProblemDefinition()->getStartState(0)));
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("the start state is in collision for the mdd checker"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mddual::planning
