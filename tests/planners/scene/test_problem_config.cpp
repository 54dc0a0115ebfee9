// The OMPL.app cfg reader and writer: complete SE(2) and SE(3) configs,
// OMPL.app's planner-section semantics, translation_only, defaults, the
// write/read round trip, and one test per documented error.
#include <gtest/gtest.h>

#include "mddual/scene/problem_config.h"
#include "scene_test_util.h"

namespace mddual::scene {
namespace {

using testing::expectSceneError;
using testing::TempDir;

using Params = std::vector<std::pair<std::string, std::string>>;

/// A planar maze in OMPL.app's format (our own text).
const char* kPlanar = R"(# a planar problem
[problem]
name = maze_se2
robot = car.stl
world = maze.urdf
start.x = 0.5
start.y = -1.25
start.theta = 0.0
goal.x = 40
goal.y = 3.5   # inline comment
goal.theta = 1.5707963267948966
volume.min.x = -50
volume.min.y = -50
volume.max.x = 50
volume.max.y = 50
threshold = 1e-12

[benchmark]
time_limit = 20.0
mem_limit = 1000.0
run_count = 30

[planner]
; semicolon comments too
est=
rrt=
rrt.range = 2.5
kpiece=
)";

/// An SE(3) problem with every kind of key, and OMPL.app's planner-section
/// semantics (instances, parameters of the last instance, per-planner
/// problem.* overrides).
const char* kSpatial = R"([problem]
name = office
robot = robot.urdf
world = sub/office.dae
objective = length
objective.threshold = 0
start.x = -4.5
start.y = -40.25
start.z = 70.5
start.theta = 0
start.axis.x = 1
start.axis.y = 0
start.axis.z = 0
goal.x = 200
goal.y = -40.25
goal.z = 70.5
goal.theta = 3.14159
goal.axis.x = 0
goal.axis.y = 0
goal.axis.z = 2
volume.min.x = -500
volume.min.y = -230.5
volume.min.z = -123.75
volume.max.x = 320
volume.max.y = 531.875
volume.max.z = 101
solution_length = 1000
Longest_Valid_Segment_Fraction = 0.01
sampler = obstacle_based

[benchmark]
time_limit = 8.0
mem_limit = 4096.0
run_count = 50
output = ../results
save_paths = best
simplify = false

[planner]
problem.projection.cellsize_factor = 2.0
rrtconnect.range = 50
rrtconnect =
rrtconnect.range = 100
rrtconnect =
rrtconnect.range = 200
kpiece =
problem.longest_valid_segment_fraction = 0.2
kpiece =
problem.projection.cellsize_factor = 4.0
prmstar =
prmstar.name = PRM*
problem.objective = length
mdd_rrtconnect =
mdd_rrtconnect.range = 3
)";

TEST(ProblemConfig, ReadsAPlanarConfig) {
  TempDir dir;
  const ProblemConfig c = readProblemConfig(dir.write("maze.cfg", kPlanar));
  EXPECT_EQ(c.name, "maze_se2");
  EXPECT_EQ(c.robot, "car.stl");
  EXPECT_EQ(c.world, "maze.urdf");
  EXPECT_EQ(c.space, SpaceKind::kSE2);
  EXPECT_EQ(c.start.position, Eigen::Vector3d(0.5, -1.25, 0));
  EXPECT_EQ(c.start.axis, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(c.goal.position, Eigen::Vector3d(40, 3.5, 0));
  EXPECT_DOUBLE_EQ(c.goal.theta, 1.5707963267948966);
  ASSERT_TRUE(c.volume.has_value());
  EXPECT_EQ(c.volume->min(), Eigen::Vector3d(-50, -50, 0));
  EXPECT_EQ(c.volume->max(), Eigen::Vector3d(50, 50, 0));
  EXPECT_EQ(c.threshold, 1e-12);
  EXPECT_TRUE(c.objective.empty());
  EXPECT_TRUE(c.space_parameters.empty());
  EXPECT_EQ(c.time_limit, 20.0);
  EXPECT_EQ(c.mem_limit, 1000.0);
  EXPECT_EQ(c.run_count, 30);
  EXPECT_TRUE(c.output.empty());
  EXPECT_EQ(c.save_paths, SavePaths::kNone);
  EXPECT_TRUE(c.simplify);
  ASSERT_EQ(c.planners.size(), 3u);
  EXPECT_EQ(c.planners[0].name, "est");
  EXPECT_EQ(c.planners[1].name, "rrt");
  EXPECT_EQ(c.planners[1].params, (Params{{"range", "2.5"}}));
  EXPECT_EQ(c.planners[1].line, 26);
  EXPECT_EQ(c.planners[2].name, "kpiece");
  EXPECT_EQ(resolvePath(c, c.robot), dir.path() / "car.stl");
}

TEST(ProblemConfig, ReadsASpatialConfigWithOmplAppPlannerSemantics) {
  TempDir dir;
  const ProblemConfig c = readProblemConfig(dir.write("office.cfg", kSpatial), {"mdd_rrtconnect"});
  EXPECT_EQ(c.space, SpaceKind::kSE3);
  EXPECT_EQ(c.world, "sub/office.dae");
  EXPECT_EQ(c.start.position, Eigen::Vector3d(-4.5, -40.25, 70.5));
  EXPECT_EQ(c.start.axis, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(c.goal.axis, Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(c.goal.theta, 3.14159);
  ASSERT_TRUE(c.volume.has_value());
  EXPECT_EQ(c.volume->min(), Eigen::Vector3d(-500, -230.5, -123.75));
  EXPECT_EQ(c.volume->max(), Eigen::Vector3d(320, 531.875, 101));
  EXPECT_EQ(c.objective, "length");
  EXPECT_EQ(c.objective_threshold, 0.0);
  EXPECT_FALSE(c.threshold.has_value());
  EXPECT_EQ(c.solution_length, 1000.0);
  EXPECT_EQ(c.space_parameters, (Params{{"longest_valid_segment_fraction", "0.01"}, {"sampler", "obstacle_based"}}));
  EXPECT_EQ(c.time_limit, 8.0);
  EXPECT_EQ(c.run_count, 50);
  EXPECT_EQ(c.output, "../results");
  EXPECT_EQ(c.save_paths, SavePaths::kShortest);
  EXPECT_FALSE(c.simplify);

  ASSERT_EQ(c.planners.size(), 7u);
  // rrtconnect.range before any instance creates one (and takes the pending
  // problem.* override); later ones set the last instance.
  EXPECT_EQ(c.planners[0].name, "rrtconnect");
  EXPECT_EQ(c.planners[0].params, (Params{{"range", "50"}}));
  EXPECT_EQ(c.planners[0].context, (Params{{"projection.cellsize_factor", "2.0"}}));
  EXPECT_EQ(c.planners[1].params, (Params{{"range", "100"}}));
  EXPECT_TRUE(c.planners[1].context.empty());
  EXPECT_EQ(c.planners[2].params, (Params{{"range", "200"}}));
  EXPECT_EQ(c.planners[3].name, "kpiece");
  EXPECT_EQ(c.planners[3].context, (Params{{"longest_valid_segment_fraction", "0.2"}}));
  EXPECT_EQ(c.planners[4].context, (Params{{"projection.cellsize_factor", "4.0"}}));
  EXPECT_EQ(c.planners[5].name, "prmstar");
  EXPECT_EQ(c.planners[5].params, (Params{{"name", "PRM*"}}));  // value case kept
  EXPECT_EQ(c.planners[6].name, "mdd_rrtconnect");
  EXPECT_EQ(c.planners[6].params, (Params{{"range", "3"}}));
}

TEST(ProblemConfig, DefaultsAreOmplAppsAndOmpls) {
  TempDir dir;
  const ProblemConfig c = readProblemConfig(dir.write("min.cfg", R"([problem]
robot = r.stl
world = w.stl
start.x = 0
start.y = 0
start.theta = 0
goal.x = 1
goal.y = 1
goal.theta = 0
)"));
  EXPECT_TRUE(c.name.empty());
  EXPECT_FALSE(c.volume.has_value());
  EXPECT_FALSE(c.threshold.has_value());
  EXPECT_EQ(c.time_limit, 5.0);
  EXPECT_EQ(c.mem_limit, 4096.0);
  EXPECT_EQ(c.run_count, 100);
  EXPECT_EQ(c.save_paths, SavePaths::kNone);
  EXPECT_TRUE(c.simplify);
  EXPECT_TRUE(c.planners.empty());
}

TEST(ProblemConfig, TranslationOnly) {
  TempDir dir;
  std::string planar = kPlanar;
  planar.replace(planar.find("goal.theta = 1.5707963267948966"), 31, "goal.theta = 0");
  planar.replace(planar.find("threshold = 1e-12"), 17, "translation_only = true");
  const ProblemConfig c2 = readProblemConfig(dir.write("t2.cfg", planar));
  EXPECT_EQ(c2.space, SpaceKind::kR2);
  EXPECT_TRUE(c2.space_parameters.empty());  // not a space parameter
  EXPECT_TRUE(isPlanar(c2.space));
  EXPECT_TRUE(isTranslationOnly(c2.space));

  std::string spatial = kSpatial;
  spatial.replace(spatial.find("goal.theta = 3.14159"), 20, "goal.theta = 0");
  spatial.replace(spatial.find("sampler = obstacle_based"), 24, "translation_only = yes");
  const ProblemConfig c3 = readProblemConfig(dir.write("t3.cfg", spatial), {"mdd_rrtconnect"});
  EXPECT_EQ(c3.space, SpaceKind::kR3);
  // translation_only = false keeps the rigid-body space.
  spatial.replace(spatial.find("translation_only = yes"), 22, "translation_only = false");
  EXPECT_EQ(readProblemConfig(dir.write("t4.cfg", spatial), {"mdd_rrtconnect"}).space, SpaceKind::kSE3);
}

// Ours: the tolerance under which a mesh loads as its hull (LoadOptions::
// mesh_convex_tolerance); not a space parameter; written back.
TEST(ProblemConfig, MeshConvexTolerance) {
  TempDir dir;
  std::string planar = kPlanar;
  EXPECT_FALSE(readProblemConfig(dir.write("none.cfg", planar)).mesh_convex_tolerance);
  planar.replace(planar.find("threshold = 1e-12"), 17, "threshold = 1e-12\nmesh_convex_tolerance = 2.5e-3");
  const ProblemConfig c = readProblemConfig(dir.write("t.cfg", planar));
  ASSERT_TRUE(c.mesh_convex_tolerance);
  EXPECT_EQ(*c.mesh_convex_tolerance, 2.5e-3);
  EXPECT_TRUE(c.space_parameters.empty());
  const auto out = dir.path() / "written.cfg";
  writeProblemConfig(c, out);
  const ProblemConfig back = readProblemConfig(out);
  EXPECT_TRUE(back == c);
  EXPECT_EQ(back.mesh_convex_tolerance, c.mesh_convex_tolerance);
  ProblemConfig other = c;
  other.mesh_convex_tolerance = 0.0;
  EXPECT_FALSE(other == c);
  other.mesh_convex_tolerance = 0.5;
  expectSceneError([&] { writeProblemConfig(other, out); }, {"written.cfg", "mesh_convex_tolerance 0.5 is not in"});
}

TEST(ProblemConfig, RoundTrips) {
  TempDir dir;
  std::string spatial = kSpatial;
  spatial.replace(spatial.find("goal.theta = 3.14159"), 20, "goal.theta = 0");
  std::string translation = spatial;
  translation.replace(translation.find("sampler = obstacle_based"), 24, "translation_only = true");
  const std::vector<std::string> texts = {kPlanar, spatial, translation};
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const ProblemConfig first =
        readProblemConfig(dir.write("in" + std::to_string(i) + ".cfg", texts[i]), {"mdd_rrtconnect"});
    const auto out = dir.path() / "written" / ("out" + std::to_string(i) + ".cfg");
    std::filesystem::create_directories(out.parent_path());
    writeProblemConfig(first, out);
    const ProblemConfig second = readProblemConfig(out, {"mdd_rrtconnect"});
    EXPECT_TRUE(first == second) << "config " << i;
    EXPECT_EQ(second.file, out);
    EXPECT_EQ(second.planners.size(), first.planners.size());
  }
}

TEST(ProblemConfig, RoundTripsValuesBuiltInCode) {
  TempDir dir;
  ProblemConfig c;
  c.name = "built";
  c.robot = "a b/robot.urdf";
  c.world = "/abs/world.stl";
  c.space = SpaceKind::kSE3;
  c.start.position = {0.1, 1.0 / 3.0, -2e-17};
  c.start.axis = {0.3, -0.4, 0.5};
  c.start.theta = 2.0 / 7.0;
  c.goal.position = {1e300, -4.9e-324, 7};
  c.volume = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -2, -3), Eigen::Vector3d(1, 2, 3));
  c.space_parameters = {{"longest_valid_segment_fraction", "0.005"}};
  c.time_limit = 0.1;
  c.run_count = 0;
  c.save_paths = SavePaths::kAll;
  c.planners = {{"rrtstar", {{"range", "1"}, {"goal_bias", "0.1"}}, {{"sampler", "gaussian"}}, 0},
                {"rrtstar", {}, {}, 0}};
  const auto file = dir.path() / "built.cfg";
  writeProblemConfig(c, file);
  const ProblemConfig back = readProblemConfig(file);
  EXPECT_TRUE(back == c);
  EXPECT_EQ(back.start.position.y(), 1.0 / 3.0);
  EXPECT_EQ(back.goal.position.y(), -4.9e-324);
  c.space = SpaceKind::kR3;  // the goal's rotation differs from the start's
  expectSceneError([&] { writeProblemConfig(c, file); }, {"built.cfg", "translation_only"});
}

TEST(ProblemConfig, PlanarVolumeWithZRoundTrips) {
  TempDir dir;
  std::string planar = kPlanar;
  planar.replace(planar.find("volume.max.y = 50"), 17, "volume.max.y = 50\nvolume.min.z = -1\nvolume.max.z = 2");
  const ProblemConfig c = readProblemConfig(dir.write("z.cfg", planar));
  EXPECT_EQ(c.volume->min().z(), -1.0);
  writeProblemConfig(c, dir.path() / "z2.cfg");
  EXPECT_TRUE(readProblemConfig(dir.path() / "z2.cfg") == c);
}

TEST(ProblemConfig, AByteOrderMarkIsNoText) {
  // A hostile-input hunt's case: "maze.cfg:1: expected 'key = value', got
  // '[problem]'" with the mark invisible in the message.
  TempDir dir;
  const ProblemConfig plain = readProblemConfig(dir.write("plain.cfg", kPlanar));
  const ProblemConfig marked = readProblemConfig(dir.write("marked.cfg", "\xEF\xBB\xBF" + std::string(kPlanar)));
  EXPECT_TRUE(marked == plain);
}

TEST(ProblemConfig, PosesFollowOmplConventions) {
  PoseSpec p;
  p.position = {1, 2, 3};
  p.axis = {0, 0, 2};  // not unit: normalised
  p.theta = 0.5;
  const Eigen::Isometry3d X = toIsometry(p, SpaceKind::kSE3);
  EXPECT_TRUE(X.linear().isApprox(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-15));
  EXPECT_EQ(X.translation(), Eigen::Vector3d(1, 2, 3));
  p.axis = Eigen::Vector3d::Zero();  // OMPL: identity
  EXPECT_TRUE(toIsometry(p, SpaceKind::kR3).linear().isIdentity());
  PoseSpec q;
  q.position = {1, 2, 0};
  q.theta = 1.0;
  const Eigen::Isometry3d Y = toIsometry(q, SpaceKind::kSE2);
  EXPECT_TRUE(Y.linear().isApprox(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-15));
  EXPECT_EQ(Y.translation(), Eigen::Vector3d(1, 2, 0));
  EXPECT_STREQ(toString(SpaceKind::kR2), "r2");
  // An axis whose norm overflows (a hostile-input hunt's case) is still a
  // direction: the rotation about (1, 1, 0) / sqrt(2).
  p.axis = {1e308, 1e308, 0};
  const Eigen::Isometry3d Z = toIsometry(p, SpaceKind::kSE3);
  EXPECT_TRUE(
      Z.linear().isApprox(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix(), 1e-15));
}

// --- errors: one per case, each naming the file and the line ------------

/// Writes kPlanar with `from` replaced by `to` and expects a SceneError
/// mentioning each of `parts`.
void expectPlanarError(const std::string& from, const std::string& to, const std::vector<std::string>& parts) {
  TempDir dir;
  std::string text = kPlanar;
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const auto file = dir.write("maze.cfg", text);
  expectSceneError([&] { readProblemConfig(file); }, parts);
}

TEST(ProblemConfigErrors, MissingFile) {
  TempDir dir;
  expectSceneError([&] { readProblemConfig(dir.path() / "nope.cfg"); }, {"nope.cfg", "file not found"});
}
TEST(ProblemConfigErrors, NotANumber) {
  expectPlanarError("start.x = 0.5", "start.x = abc", {"maze.cfg:6: start.x: 'abc' is not a number"});
}
TEST(ProblemConfigErrors, NumberWithTrailingText) {
  expectPlanarError("goal.x = 40", "goal.x = 40m", {"maze.cfg:9: goal.x: '40m' is not a number"});
}
TEST(ProblemConfigErrors, NonFiniteNumber) {
  expectPlanarError("goal.x = 40", "goal.x = inf", {"maze.cfg:9: goal.x: 'inf' is not a number"});
}
TEST(ProblemConfigErrors, ControlBytesAreShownSafely) {
  // A hostile-input hunt: NUL and escape bytes of the input went raw into
  // messages (a terminal ran the escape). Shown as '?'.
  expectPlanarError("goal.x = 40", std::string("goal.x = 4\x1b[31m0"),
                    {"maze.cfg:9: goal.x: '4?[31m0' is not a number"});
}
TEST(ProblemConfigErrors, UnknownSection) {
  expectPlanarError("[benchmark]", "[benchmarks]", {"maze.cfg:18: unknown section [benchmarks]"});
}
TEST(ProblemConfigErrors, MalformedSectionHeader) {
  expectPlanarError("[benchmark]", "[benchmark", {"maze.cfg:18: malformed section header"});
}
TEST(ProblemConfigErrors, LineWithoutEquals) {
  expectPlanarError("est=", "est", {"maze.cfg:25: expected 'key = value'"});
}
TEST(ProblemConfigErrors, KeyBeforeAnySection) {
  expectPlanarError("[problem]\n", "", {"maze.cfg:2: 'name' comes before any section"});
}
TEST(ProblemConfigErrors, NoProblemSection) {
  TempDir dir;
  const auto file = dir.write("b.cfg", "[benchmark]\nrun_count = 2\n");
  expectSceneError([&] { readProblemConfig(file); }, {"b.cfg: no [problem] section"});
}
TEST(ProblemConfigErrors, DuplicateKey) {
  expectPlanarError("start.y = -1.25", "start.y = -1.25\nstart.x = 3",
                    {"maze.cfg:8: start.x given twice (first at line 6)"});
}
TEST(ProblemConfigErrors, DuplicateSpaceParameter) {
  expectPlanarError("threshold = 1e-12", "foo = 1\nFOO = 2", {"maze.cfg:17: foo given twice (first at line 16)"});
}
TEST(ProblemConfigErrors, MissingRobot) {
  expectPlanarError("robot = car.stl\n", "", {"maze.cfg: [problem]: robot is missing"});
}
TEST(ProblemConfigErrors, EmptyWorldPath) {
  expectPlanarError("world = maze.urdf", "world =", {"maze.cfg:5: world: empty path"});
}
TEST(ProblemConfigErrors, MissingTheta) {
  expectPlanarError("start.theta = 0.0\n", "", {"maze.cfg: [problem]: start.theta is missing"});
}
TEST(ProblemConfigErrors, MixOfPlanarAndSpatialKeys) {
  expectPlanarError("goal.theta", "goal.z = 1\ngoal.theta", {"maze.cfg: [problem]: start.z is missing", "SE(3)"});
}
TEST(ProblemConfigErrors, VolumeGivenInPart) {
  expectPlanarError("volume.max.y = 50\n", "", {"maze.cfg: [problem]: volume.max.y is missing"});
}
TEST(ProblemConfigErrors, EmptyVolume) {
  expectPlanarError("volume.max.x = 50", "volume.max.x = -60", {"maze.cfg:14: volume.max.x is below volume.min.x"});
}
TEST(ProblemConfigErrors, VolumeBeyondTheSupportedRange) {
  // A hostile-input hunt's cases: -1e308 gave OMPL's "lower bound must be
  // strictly less than upper bound" (the extent overflows), 1e200 a core
  // error in the middle of planning; neither named the cfg or the key.
  expectPlanarError("volume.max.x = 50", "volume.max.x = 1e308",
                    {"maze.cfg:14: volume.max.x: 1e+308 is outside the supported range [-1e+50, 1e+50]"});
  expectPlanarError("volume.max.x = 50", "volume.max.x = 1e51",
                    {"maze.cfg:14: volume.max.x: 1e+51 is outside the supported range"});
}
TEST(ProblemConfigErrors, TheWriterRefusesWhatTheReaderWould) {
  TempDir dir;
  ProblemConfig c = readProblemConfig(dir.write("maze.cfg", kPlanar));
  c.volume->max().x() = 1e51;
  expectSceneError([&] { writeProblemConfig(c, dir.path() / "far.cfg"); },
                   {"far.cfg", "a volume corner is outside the supported range"});
}
TEST(ProblemConfigErrors, NegativeThreshold) {
  expectPlanarError("threshold = 1e-12", "threshold = -1", {"maze.cfg:16: threshold: must be >= 0"});
}
TEST(ProblemConfigErrors, UnknownObjective) {
  expectPlanarError("threshold = 1e-12", "objective = shortest",
                    {"maze.cfg:16: objective: unknown objective 'shortest'"});
}
TEST(ProblemConfigErrors, ControlProblem) {
  expectPlanarError("threshold = 1e-12", "control = kinematic_car", {"maze.cfg:16: control-based problems"});
}
TEST(ProblemConfigErrors, BadTranslationOnlyValue) {
  expectPlanarError("threshold = 1e-12", "translation_only = maybe",
                    {"maze.cfg:16: translation_only: 'maybe' is not true or false"});
}
TEST(ProblemConfigErrors, TranslationOnlyWithARotatingGoal) {
  expectPlanarError("threshold = 1e-12", "translation_only = true",
                    {"maze.cfg:16: translation_only: the goal's rotation differs"});
}
TEST(ProblemConfigErrors, MeshConvexToleranceOutOfRange) {
  expectPlanarError("threshold = 1e-12", "mesh_convex_tolerance = 0.02",
                    {"maze.cfg:16: mesh_convex_tolerance: must be in [0, 0.01]", "mesh_convex_hull"});
  expectPlanarError("threshold = 1e-12", "mesh_convex_tolerance = -1e-4",
                    {"maze.cfg:16: mesh_convex_tolerance: must be in [0, 0.01]"});
  expectPlanarError("threshold = 1e-12", "mesh_convex_tolerance = tight",
                    {"maze.cfg:16: mesh_convex_tolerance: 'tight' is not a number"});
}
TEST(ProblemConfigErrors, UnknownBenchmarkKey) {
  expectPlanarError("run_count = 30", "runs = 30", {"maze.cfg:21: unknown [benchmark] key 'runs'"});
}
TEST(ProblemConfigErrors, BadRunCount) {
  expectPlanarError("run_count = 30", "run_count = 99999999999999999999",
                    {"maze.cfg:21: run_count: '99999999999999999999' is not an integer in [0, 2147483647]"});
  expectPlanarError("run_count = 30", "run_count = -3",
                    {"maze.cfg:21: run_count: '-3' is not an integer in [0, 2147483647]"});
  expectPlanarError("run_count = 30", "run_count = 2.5",
                    {"maze.cfg:21: run_count: '2.5' is not an integer in [0, 2147483647]"});
}
TEST(ProblemConfigErrors, NonPositiveTimeLimit) {
  expectPlanarError("time_limit = 20.0", "time_limit = 0", {"maze.cfg:19: time_limit: must be > 0"});
}
TEST(ProblemConfigErrors, BadSimplify) {
  expectPlanarError("run_count = 30", "run_count = 30\nsimplify = perhaps",
                    {"maze.cfg:22: simplify: 'perhaps' is not true or false"});
}
TEST(ProblemConfigErrors, BadSavePaths) {
  expectPlanarError("run_count = 30", "run_count = 30\nsave_paths = some",
                    {"maze.cfg:22: save_paths: 'some' is not none, all or shortest"});
}
TEST(ProblemConfigErrors, UnknownPlanner) {
  expectPlanarError("kpiece=", "mdd_rrtconnect=", {"maze.cfg:28: unknown planner 'mdd_rrtconnect'"});
}
TEST(ProblemConfigErrors, UnknownPlannerWithParameter) {
  expectPlanarError("kpiece=", "rrtconnected.range = 1", {"maze.cfg:28: unknown planner 'rrtconnected'"});
}
TEST(ProblemConfigErrors, PlannerLineWithValue) {
  expectPlanarError("kpiece=", "kpiece = 1", {"maze.cfg:28: 'kpiece = 1': a planner line takes no value"});
}
TEST(ProblemConfigErrors, EmptyPlannerParameter) {
  expectPlanarError("kpiece=", "kpiece. = 1", {"maze.cfg:28: empty parameter name"});
}
TEST(ProblemConfigErrors, ContextForNoPlanner) {
  expectPlanarError("est=\nrrt=\nrrt.range = 2.5\nkpiece=\n", "problem.sampler = gaussian\n",
                    {"maze.cfg:25: problem.sampler applies to no planner"});
}
TEST(ProblemConfigErrors, ConflictingObjective) {
  TempDir dir;
  std::string text = kPlanar;
  text.replace(text.find("threshold = 1e-12"), 17, "objective = length");
  text += "problem.objective = length\n";  // the same one is fine
  EXPECT_EQ(readProblemConfig(dir.write("same.cfg", text)).objective, "length");
  text += "problem.objective = max_min_clearance\n";
  const auto file = dir.write("maze.cfg", text);
  expectSceneError([&] { readProblemConfig(file); },
                   {"maze.cfg:30: problem.objective: planners cannot have different"});
}

TEST(ProblemConfigErrors, ObjectiveFromThePlannerSection) {
  TempDir dir;
  const auto file = dir.write("maze.cfg", std::string(kPlanar) + "problem.objective = mechanical_work\n");
  EXPECT_EQ(readProblemConfig(file).objective, "mechanical_work");
}

TEST(ProblemConfigErrors, WriterRejectsUnwritableValues) {
  TempDir dir;
  ProblemConfig c = readProblemConfig(dir.write("maze.cfg", kPlanar));
  ProblemConfig hash = c;
  hash.name = "a#b";
  expectSceneError([&] { writeProblemConfig(hash, dir.path() / "o.cfg"); }, {"name", "'#'"});
  ProblemConfig lifted = c;
  lifted.start.position.z() = 1.0;
  expectSceneError([&] { writeProblemConfig(lifted, dir.path() / "o.cfg"); }, {"start", "planar"});
  ProblemConfig upper = c;
  upper.space_parameters = {{"Sampler", "x"}};
  expectSceneError([&] { writeProblemConfig(upper, dir.path() / "o.cfg"); }, {"Sampler", "lower case"});
  ProblemConfig clash = c;
  clash.space_parameters = {{"start.x", "1"}};
  expectSceneError([&] { writeProblemConfig(clash, dir.path() / "o.cfg"); }, {"start.x"});
  expectSceneError([&] { writeProblemConfig(c, dir.path() / "no" / "such" / "dir.cfg"); }, {"dir.cfg", "cannot open"});
}

}  // namespace
}  // namespace mddual::scene
