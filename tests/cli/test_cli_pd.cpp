// `mddual pd` and `mddual width`: known answers (overlapping, touching and
// separated cubes, a polyhedral metric, widths of a tetrahedron and a cube),
// the methods against the brute force on random pairs, --output, and bad
// lines / bad options.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cli_fixtures.h"
#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

constexpr double kTol = 1e-9;
const char* const kPdMethods[] = {"exact", "shallow", "approx", "brute"};

std::string pdLine(const Json& id, const Json& a, const Json& b) {
  return Json{{"id", id}, {"a", a}, {"b", b}}.dump() + "\n";
}

std::vector<Json> run(const std::vector<std::string>& args, const std::string& input, int expected_exit = 0) {
  const CliRun r = runCli(args, input);
  EXPECT_EQ(r.exit_code, expected_exit) << r.err;
  return parseLines(r.out);
}

Json answerOne(const std::vector<std::string>& args, const std::string& line) {
  const std::vector<Json> out = run(args, line);
  EXPECT_EQ(out.size(), 1u);
  return out.empty() ? Json() : out[0];
}

TEST(CliPd, OverlappingCubes) {
  // A = [0,1]^3, B = [0.7,1.7] x [0.2,1.2] x [0,1]: B leaves by +x 0.3.
  for (const char* method : kPdMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne({"pd", "--method", method}, pdLine("o", cube(0.0), cube(0.7, 0.2)));
    EXPECT_EQ(r["id"], "o");
    expectNumber(r["pd"], 0.3, kTol, "pd");
    expectVector(r["translation"], 0.3, 0.0, 0.0, kTol, "translation");
    expectVector(r["normal"], 1.0, 0.0, 0.0, kTol, "normal");
    EXPECT_EQ(r["intersecting"], true);
    EXPECT_EQ(r["status"], "penetrating");
    EXPECT_EQ(r["method"], method);
    EXPECT_EQ(r.contains("stats"), std::string(method) != "brute");
    EXPECT_TRUE(r["facet"].is_object());
    EXPECT_TRUE(r["features"]["a"].is_object());
  }
}

TEST(CliPd, SeparatedAndTouchingHaveZeroDepth) {
  for (const char* method : kPdMethods) {
    SCOPED_TRACE(method);
    const Json sep = answerOne({"pd", "--method", method}, pdLine("s", cube(0.0), cube(-3.0)));
    expectNumber(sep["pd"], 0.0, 0.0, "pd");
    expectVector(sep["translation"], 0.0, 0.0, 0.0, 0.0, "translation");
    EXPECT_EQ(sep["intersecting"], false);
    EXPECT_EQ(sep["status"], "separated");
    EXPECT_TRUE(sep["normal"].is_null());
    const Json touch = answerOne({"pd", "--method", method}, pdLine("t", cube(0.0), cube(-1.0)));
    expectNumber(touch["pd"], 0.0, 0.0, "pd");
    EXPECT_EQ(touch["intersecting"], true);
    EXPECT_EQ(touch["status"], "touching");
  }
}

TEST(CliPd, DirectionIsIgnored) {
  const Json r = answerOne({"pd"}, queryLine("d", cube(0.0), cube(0.7, 0.2), {0, 0, 1}));
  expectNumber(r["pd"], 0.3, kTol, "pd");
}

TEST(CliPd, DeltaIsUsedAndReported) {
  const Json r = answerOne({"pd", "--method", "approx", "--delta", "0.01"}, pdLine(1, cube(0.0), cube(0.7, 0.2)));
  expectNumber(r["delta"], 0.01, 0.0, "delta");
  EXPECT_GT(r["stats"]["rays"].get<int>(), 500);
  const Json d = answerOne({"pd", "--method", "approx"}, pdLine(1, cube(0.0), cube(0.7, 0.2)));
  expectNumber(d["delta"], 0.1, 0.0, "default delta");
  const Json e = answerOne({"pd", "--method", "exact", "--delta", "0.01"}, pdLine(1, cube(0.0), cube(0.7, 0.2)));
  EXPECT_TRUE(e["delta"].is_null());
}

TEST(CliPd, PolyhedralMetric) {
  // K = [-2,2]^3: lambda K fits in M = [-1.7,0.3] x [-1.2,0.8] x [-1,1] up to
  // lambda = 0.15, along a vertex (2, +-2, +-2).
  const Json k = cube(-2.0, -2.0, -2.0, 4.0);
  for (const char* method : kPdMethods) {
    SCOPED_TRACE(method);
    const std::string line = Json{{"id", "k"}, {"a", cube(0.0)}, {"b", cube(0.7, 0.2)}, {"metric", k}}.dump() + "\n";
    const Json r = answerOne({"pd", "--method", method}, line);
    expectNumber(r["pd"], 0.15, kTol, "pd");
    expectNumber(r["translation"][0], 0.3, kTol, "translation x");
    expectNumber(r["euclidean_length"], 0.3 * std::sqrt(3.0), kTol, "euclidean_length");
    EXPECT_TRUE(r["metric_vertex"].is_number_integer());
    EXPECT_EQ(r["metric"], true);
    EXPECT_EQ(r["method"], std::string(method) == "brute" ? "brute" : "exact");
  }
}

TEST(CliPd, MethodsAgreeWithTheBruteForceOnRandomPairs) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  auto blob = [&](int n, double r) {
    Json points = Json::array();
    for (int i = 0; i < n; ++i) {
      // z, y, x: the order GCC evaluated the constructor's arguments (C++
      // leaves it unspecified), kept so the seeded points stay as they were.
      const double z = normal(rng);
      const double y = normal(rng);
      const double x = normal(rng);
      Eigen::Vector3d v(x, y, z);
      v = r * v.normalized();
      points.push_back({v.x(), v.y(), v.z()});
    }
    return points;
  };
  std::string input;
  for (int i = 0; i < 30; ++i) {
    Json b = blob(12, 1.0);
    for (Json& p : b) p[0] = p[0].get<double>() + 0.05 * i;
    input += pdLine(i, blob(15, 1.2), b);
  }
  const std::vector<Json> brute = run({"pd", "--method", "brute"}, input);
  ASSERT_EQ(brute.size(), 30u);
  // The comparison is about depths: every pair penetrates (B slides at most
  // 1.45 along x, against radii 1.2 + 1.0), or the sample tests nothing.
  int penetrating = 0;
  for (const Json& r : brute) penetrating += r["status"] == "penetrating" ? 1 : 0;
  EXPECT_EQ(penetrating, 30);
  for (const char* method : {"exact", "shallow", "approx"}) {
    const std::vector<Json> out = run({"pd", "--method", method}, input);
    ASSERT_EQ(out.size(), 30u);
    for (size_t i = 0; i < out.size(); ++i) {
      EXPECT_EQ(out[i]["id"], brute[i]["id"]);
      EXPECT_EQ(out[i]["status"], brute[i]["status"]) << i;
      const double pd = out[i]["pd"].get<double>();
      const double ref = brute[i]["pd"].get<double>();
      if (std::string(method) == "approx") {
        EXPECT_GE(pd, ref - kTol) << method << " " << i;
        EXPECT_LE(pd, 1.1 * ref + kTol) << method << " " << i;
      } else {
        EXPECT_NEAR(pd, ref, kTol) << method << " " << i;
      }
    }
  }
}

TEST(CliPd, OutputOptionWritesTheFile) {
  const TempDir dir;
  const std::string input = dir.write("in.jsonl", pdLine("f", cube(0.0), cube(0.7, 0.2)));
  const std::string output = dir.path() + "/out.jsonl";
  const CliRun r = runCli({"pd", "--input", input, "--output", output});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  const std::vector<Json> out = parseLines(readFile(output));
  ASSERT_EQ(out.size(), 1u);
  expectNumber(out[0]["pd"], 0.3, kTol, "pd");
}

TEST(CliPd, BadLinesGetErrorsAndTheRunGoesOn) {
  std::string input;
  input += pdLine("good-1", cube(0.0), cube(0.7, 0.2));
  input += Json{{"id", "no-b"}, {"a", cube(0.0)}}.dump() + "\n";
  input += pdLine("collinear", Json::array({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}), cube(0.0));
  input += "not json\n";
  input += Json{{"id", "asymmetric-k"}, {"a", cube(0.0)}, {"b", cube(0.5)}, {"metric", cube(0.0)}}.dump() + "\n";
  input += Json{{"id", "flat-k"},
                {"a", cube(0.0)},
                {"b", cube(0.5)},
                {"metric", Json::array({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}})}}
               .dump() +
           "\n";
  input += Json{{"id", "k-not-array"}, {"a", cube(0.0)}, {"b", cube(0.5)}, {"metric", 3}}.dump() + "\n";
  input += pdLine("good-2", cube(0.0), cube(-3.0));
  const std::vector<Json> out = run({"pd"}, input, 1);
  ASSERT_EQ(out.size(), 8u);
  auto expectError = [](const Json& r, const Json& id, const std::string& needle) {
    EXPECT_EQ(r["id"], id);
    ASSERT_TRUE(r.contains("error")) << r.dump();
    EXPECT_NE(r["error"].get<std::string>().find(needle), std::string::npos) << r.dump();
    EXPECT_FALSE(r.contains("pd"));
  };
  expectNumber(out[0]["pd"], 0.3, kTol, "good-1");
  expectError(out[1], "no-b", "b: missing field");
  expectError(out[2], "collinear", "a: ");
  expectError(out[3], nullptr, "invalid JSON");
  expectError(out[4], "asymmetric-k", "metric: K is not centrally symmetric");
  expectError(out[5], "flat-k", "metric: K is flat");
  expectError(out[6], "k-not-array", "metric: expected an array");
  expectNumber(out[7]["pd"], 0.0, 0.0, "good-2");
}

TEST(CliPd, BadOptionsAreUsageErrors) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"pd", "--method", "fast"},
                                               {"pd", "--delta", "0"},
                                               {"pd", "--delta", "-1"},
                                               {"pd", "--delta", "x"},
                                               {"width", "--method", "shallow"},
                                               {"width", "--delta", "1e9"}}) {
    const CliRun r = runCli(args, pdLine(1, cube(0.0), cube(0.5)));
    EXPECT_NE(r.exit_code, 0) << args[1] << " " << args[2];
    EXPECT_NE(r.exit_code, 1) << "usage errors are not line failures";
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const CliRun missing = runCli({"pd", "--input", "/nonexistent/in.jsonl"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("cannot open input file"), std::string::npos) << missing.err;
}

std::string widthLine(const Json& id, const Json& a) {
  return Json{{"id", id}, {"a", a}}.dump() + "\n";
}

TEST(CliWidth, KnownSolids) {
  // Regular tetrahedron of edge sqrt(2) (alternate cube corners): width 1,
  // between opposite edges; cube of edge 2: width 2, along an axis.
  const Json tetra = Json::array({{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}});
  for (const char* method : {"exact", "approx", "brute"}) {
    SCOPED_TRACE(method);
    std::string input = widthLine("tetra", tetra) + widthLine("cube", cube(0.0, 0.0, 0.0, 2.0));
    const std::vector<Json> out = run({"width", "--method", method, "--delta", "0.1"}, input);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0]["id"], "tetra");
    const double t = out[0]["width"].get<double>();
    const double c = out[1]["width"].get<double>();
    if (std::string(method) == "approx") {
      EXPECT_GE(t, 1.0 - kTol);
      EXPECT_LE(t, 1.1 + kTol);
      EXPECT_GE(c, 2.0 - kTol);
      EXPECT_LE(c, 2.2 + kTol);
      expectNumber(out[0]["delta"], 0.1, 0.0, "delta");
    } else {
      EXPECT_NEAR(t, 1.0, kTol);
      EXPECT_NEAR(c, 2.0, kTol);
    }
    const Json& d = out[1]["direction"];
    ASSERT_TRUE(d.is_array() && d.size() == 3u);
    EXPECT_NEAR(std::hypot(d[0].get<double>(), d[1].get<double>(), d[2].get<double>()), 1.0, 1e-12);
    EXPECT_EQ(out[0]["method"], method);
  }
}

TEST(CliWidth, FlatPolygonAndErrors) {
  std::string input = widthLine("flat", Json::array({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}));
  input += Json{{"id", "no-a"}, {"b", cube(0.0)}}.dump() + "\n";
  input += widthLine("point", Json::array({{0, 0, 0}}));
  const std::vector<Json> out = run({"width"}, input, 1);
  ASSERT_EQ(out.size(), 3u);
  expectNumber(out[0]["width"], 0.0, 0.0, "width");
  expectVector(out[0]["direction"], 0.0, 0.0, 1.0, 1e-12, "direction");
  EXPECT_NE(out[1]["error"].get<std::string>().find("a: missing field"), std::string::npos) << out[1].dump();
  EXPECT_NE(out[2]["error"].get<std::string>().find("a: "), std::string::npos) << out[2].dump();
}

}  // namespace
}  // namespace mddual::cli_test
