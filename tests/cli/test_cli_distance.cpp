// `mddual distance`: known answers (separated cubes face to face, edge to
// edge, touching, overlapping), far from the origin, and bad lines.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_fixtures.h"
#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

constexpr double kTol = 1e-9;

std::string line(const Json& id, const Json& a, const Json& b) {
  return Json{{"id", id}, {"a", a}, {"b", b}}.dump() + "\n";
}

std::vector<Json> run(const std::string& input, int expected_exit = 0) {
  const CliRun r = runCli({"distance"}, input);
  EXPECT_EQ(r.exit_code, expected_exit) << r.err;
  return parseLines(r.out);
}

TEST(CliDistance, UnitCubes) {
  std::string input;
  input += line("face", cube(0.0), cube(3.0));            // gap 2 along x
  input += line("edge", cube(0.0), cube(1.5, 1.5));       // edge to edge: sqrt(0.5)
  input += line("touch", cube(0.0), cube(1.0));           // touching faces
  input += line("overlap", cube(0.0), cube(0.75, 0.1));   // overlap 0.25 along x
  input += line("far", cube(1e6), cube(1e6 + 1.5, 0.0));  // 0.5 apart, a million from the origin
  const std::vector<Json> out = run(input);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0]["id"], "face");
  expectNumber(out[0]["distance"], 2.0, kTol, "face");
  EXPECT_EQ(out[0]["status"], "separated");
  EXPECT_EQ(out[0]["intersecting"], false);
  expectVector(out[0]["normal"], 1.0, 0.0, 0.0, kTol, "normal");
  EXPECT_NEAR(out[0]["point_b"][0].get<double>() - out[0]["point_a"][0].get<double>(), 2.0, kTol);
  EXPECT_TRUE(out[0]["stats"].is_object());
  expectNumber(out[1]["distance"], std::sqrt(0.5), kTol, "edge");
  expectNumber(out[2]["distance"], 0.0, 0.0, "touch");
  EXPECT_EQ(out[2]["status"], "touching");
  EXPECT_TRUE(out[2]["normal"].is_null());
  expectNumber(out[3]["distance"], -0.25, kTol, "overlap");
  EXPECT_EQ(out[3]["status"], "penetrating");
  expectVector(out[3]["normal"], 1.0, 0.0, 0.0, kTol, "overlap normal");
  expectNumber(out[4]["distance"], 0.5, kTol, "far");
}

TEST(CliDistance, BadLinesGetErrorsAndTheRunGoesOn) {
  std::string input;
  input += line("good", cube(0.0), cube(3.0));
  input += Json{{"id", "no-b"}, {"a", cube(0.0)}}.dump() + "\n";
  input += line("collinear", Json::array({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}), cube(0.0));
  input += "not json\n";
  const std::vector<Json> out = run(input, 1);
  ASSERT_EQ(out.size(), 4u);
  expectNumber(out[0]["distance"], 2.0, kTol, "good");
  auto expectError = [](const Json& r, const Json& id, const std::string& needle) {
    EXPECT_EQ(r["id"], id);
    ASSERT_TRUE(r.contains("error")) << r.dump();
    EXPECT_NE(r["error"].get<std::string>().find(needle), std::string::npos) << r.dump();
    EXPECT_FALSE(r.contains("distance"));
  };
  expectError(out[1], "no-b", "b: missing field");
  expectError(out[2], "collinear", "a: ");
  expectError(out[3], nullptr, "invalid JSON");
}

}  // namespace
}  // namespace mddual::cli_test
