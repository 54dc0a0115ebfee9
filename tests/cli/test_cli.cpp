// `mddual query` and `mddual demo` on inputs with known answers: the exact
// values of simple placements, MDD-DUAL against the brute force on random
// lines, --output, streaming, and the demo's summary.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cli_fixtures.h"
#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

constexpr double kTol = 1e-9;
const char* const kMethods[] = {"dual", "brute"};

/// Runs one query line by `method` and returns its single output line.
Json answerOne(const std::string& line, const std::string& method) {
  const CliRun run = runQuery(line, method);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::vector<Json> out = parseLines(run.out);
  EXPECT_EQ(out.size(), 1u) << run.out;
  return out.empty() ? Json() : out[0];
}

TEST(CliQuery, SeparatedCubesMoveForward) {
  // A = [0,1]^3, B = [-3,-2] x [0,1]^2 moving along +x: touches after 2.
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne(queryLine("sep", cube(0.0), cube(-3.0), {1, 0, 0}), method);
    EXPECT_EQ(r["id"], "sep");
    EXPECT_EQ(r["status"], "separated");
    expectNumber(r["mdd"], 2.0, kTol, "mdd");
    expectNumber(r["toi"], 2.0, kTol, "toi");
    expectNumber(r["t_lo"], 2.0, kTol, "t_lo");
    EXPECT_EQ(r["intersecting"], false);
    expectVector(r["normal"], -1.0, 0.0, 0.0, kTol, "normal");
    ASSERT_TRUE(r["point"].is_array());
    EXPECT_NEAR(r["point"][0].get<double>(), 0.0, kTol);  // on A's face x = 0
    EXPECT_EQ(r["method"], method);
    EXPECT_EQ(r.contains("stats"), std::string(method) == "dual");
  }
}

TEST(CliQuery, DirectionLengthDoesNotMatter) {
  for (const Json& s : {Json{5, 0, 0}, Json{1e-200, 0, 0}, Json{1e300, 0, 0}}) {
    const Json r = answerOne(queryLine(1, cube(0.0), cube(-3.0), s), "dual");
    EXPECT_EQ(r["status"], "separated") << s;
    expectNumber(r["mdd"], 2.0, kTol, "mdd for direction " + s.dump());
  }
}

TEST(CliQuery, DualStatsAreReported) {
  const Json r = answerOne(queryLine("s", cube(0.0), cube(-3.0), {1, 0, 0}), "dual");
  const Json& stats = r["stats"];
  for (const char* key : {"centre_iterations", "fv_faces", "vf_faces", "ee_faces", "ee_edge_faces", "steps", "rays",
                          "support_vertices"}) {
    EXPECT_TRUE(stats.contains(key) && stats[key].is_number_integer()) << key << " in " << stats.dump();
  }
  EXPECT_TRUE(stats["planar"].is_boolean());
  EXPECT_GE(stats["rays"].get<int>(), 1);
  EXPECT_GT(stats["fv_faces"].get<int>() + stats["vf_faces"].get<int>() + stats["ee_faces"].get<int>(), 0);
}

TEST(CliQuery, TouchingCubes) {
  // B = [-1,0] x [0,1]^2 shares the face x = 0 with A.
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne(queryLine("touch", cube(0.0), cube(-1.0), {1, 0, 0}), method);
    EXPECT_EQ(r["status"], "touching");
    expectNumber(r["mdd"], 0.0, kTol, "mdd");
    expectNumber(r["toi"], 0.0, kTol, "toi");
    expectNumber(r["t_lo"], 0.0, kTol, "t_lo");
    expectNumber(r["t_hi"], 2.0, kTol, "t_hi");
    EXPECT_EQ(r["intersecting"], true);
    EXPECT_EQ(r["intersect_status"], "touching");
    expectVector(r["normal"], -1.0, 0.0, 0.0, kTol, "normal");
  }
}

TEST(CliQuery, PenetratingCubes) {
  // B = [-0.5,0.5] x [0,1]^2: back 0.5 or forward 1.5 separates them.
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne(queryLine("pen", cube(0.0), cube(-0.5), {1, 0, 0}), method);
    EXPECT_EQ(r["status"], "penetrating");
    expectNumber(r["mdd"], -0.5, kTol, "mdd");
    expectNumber(r["toi"], 0.0, kTol, "toi");
    expectNumber(r["t_lo"], -0.5, kTol, "t_lo");
    expectNumber(r["t_hi"], 1.5, kTol, "t_hi");
    EXPECT_EQ(r["intersecting"], true);
    EXPECT_EQ(r["intersect_status"], "penetrating");
    expectVector(r["normal"], -1.0, 0.0, 0.0, kTol, "normal");
  }
}

TEST(CliQuery, SeparatedBehindGivesPositiveMddAndNoToi) {
  // B = [2,3] x [0,1]^2 moving along +x never reaches A; moving back 1 does.
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne(queryLine("behind", cube(0.0), cube(2.0), {1, 0, 0}), method);
    EXPECT_EQ(r["status"], "separated");
    expectNumber(r["mdd"], 1.0, kTol, "mdd");
    EXPECT_TRUE(r["toi"].is_null()) << r["toi"];
    EXPECT_EQ(r["toi_status"], "never");
    expectNumber(r["t_hi"], -1.0, kTol, "t_hi");
    EXPECT_EQ(r["intersecting"], false);
    expectVector(r["normal"], 1.0, 0.0, 0.0, kTol, "normal");
  }
}

TEST(CliQuery, TriangleAboveCube) {
  const Json flat = Json::array({{0.2, 0.2, 3.0}, {0.8, 0.2, 3.0}, {0.5, 0.8, 3.0}});
  const Json tilted = Json::array({{0.5, 0.5, 2.5}, {0.0, 0.0, 4.0}, {1.0, 0.0, 4.0}});
  const Json on_top = Json::array({{0.2, 0.2, 1.0}, {0.8, 0.2, 1.0}, {0.5, 0.8, 1.0}});
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    Json r = answerOne(queryLine("flat", cube(0.0), flat, {0, 0, -2}), method);
    EXPECT_EQ(r["status"], "separated");
    expectNumber(r["mdd"], 2.0, kTol, "mdd");
    expectNumber(r["toi"], 2.0, kTol, "toi");
    EXPECT_EQ(r["intersecting"], false);
    expectVector(r["normal"], 0.0, 0.0, 1.0, kTol, "normal");
    EXPECT_NEAR(r["point"][2].get<double>(), 1.0, kTol);

    r = answerOne(queryLine("tilted", cube(0.0), tilted, {0, 0, -1}), method);
    EXPECT_EQ(r["status"], "separated");
    expectNumber(r["mdd"], 1.5, kTol, "mdd");
    expectVector(r["normal"], 0.0, 0.0, 1.0, kTol, "normal");
    expectVector(r["point"], 0.5, 0.5, 1.0, kTol, "point");  // the triangle's low vertex lands there
    if (std::string(method) == "dual") {
      EXPECT_EQ(r["features"]["a"]["type"], "face");
      EXPECT_EQ(r["features"]["b"]["type"], "vertex");
    }

    r = answerOne(queryLine("on top", cube(0.0), on_top, {0.3, -0.2, 1.0}), method);
    EXPECT_EQ(r["status"], "touching");
    expectNumber(r["mdd"], 0.0, kTol, "mdd");
    EXPECT_EQ(r["intersecting"], true);
  }
}

TEST(CliQuery, NoContact) {
  // B = [-3,-2] x [5,6] x [0,1] moving along +x passes beside A.
  for (const char* method : kMethods) {
    SCOPED_TRACE(method);
    const Json r = answerOne(queryLine("miss", cube(0.0), cube(-3.0, 5.0), {1, 0, 0}), method);
    EXPECT_EQ(r["status"], "no_contact");
    EXPECT_TRUE(r["mdd"].is_null());
    EXPECT_TRUE(r["toi"].is_null());
    EXPECT_TRUE(r["t_lo"].is_null());
    EXPECT_TRUE(r["t_hi"].is_null());
    EXPECT_TRUE(r["normal"].is_null());
    EXPECT_TRUE(r["point"].is_null());
    EXPECT_EQ(r["features"]["a"]["type"], "none");
    EXPECT_EQ(r["features"]["b"]["type"], "none");
    EXPECT_EQ(r["intersecting"], false);
  }
}

TEST(CliQuery, NumbersKeepFullPrecision) {
  const double x = 1.2345678901234567;
  const Json r = answerOne(queryLine("p", cube(0.0), cube(-1.0 - x), {1, 0, 0}), "dual");
  expectNumber(r["mdd"], x, 4e-16, "mdd");
}

TEST(CliQuery, IdsAreEchoedInOrder) {
  const std::vector<Json> ids = {"text", 42, 2.5, nullptr, Json{{"run", 3}, {"k", {1, 2}}}, Json::array({1, "x"})};
  std::string input;
  for (const Json& id : ids) input += queryLine(id, cube(0.0), cube(-3.0), {1, 0, 0});
  input += Json{{"a", cube(0.0)}, {"b", cube(-3.0)}, {"direction", {1, 0, 0}}}.dump() + "\n";  // no id
  const CliRun run = runQuery(input);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::vector<Json> out = parseLines(run.out);
  ASSERT_EQ(out.size(), ids.size() + 1);
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(out[i]["id"], ids[i]) << i;
  EXPECT_TRUE(out.back().contains("id") && out.back()["id"].is_null());
  for (const Json& r : out) EXPECT_EQ(r["status"], "separated");
}

// ---- MDD-DUAL against the brute force ---------------------------------------

Json randomPoints(int n, const Eigen::Vector3d& centre, double size, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> coord(-size, size);
  Json points = Json::array();
  for (int i = 0; i < n; ++i)
    points.push_back({centre.x() + coord(rng), centre.y() + coord(rng), centre.z() + coord(rng)});
  return points;
}

Eigen::Vector3d asVector(const Json& p) {
  return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
}

/// The point of `points` farthest along d.
Eigen::Vector3d support(const Json& points, const Eigen::Vector3d& d) {
  Eigen::Vector3d best = asVector(points[0]);
  for (const Json& p : points) {
    if (d.dot(asVector(p)) > d.dot(best)) best = asVector(p);
  }
  return best;
}

/// Random lines: every fifth one puts a vertex of B on a vertex of A
/// (touching), every fifth one aims B's centre at A (a contact) and every
/// fifth one puts the centres close together (overlap).
std::string randomLines(int count) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> size(4, 16);
  // Draws in the order GCC evaluated the arguments they were once written in,
  // last first (C++ leaves it unspecified): the seeded lines stay as they were.
  auto vec = [&] {
    const double z = unit(rng);
    const double y = unit(rng);
    const double x = unit(rng);
    return Eigen::Vector3d(x, y, z);
  };
  std::string input;
  for (int i = 0; i < count; ++i) {
    const double half_a = 0.5 + std::abs(unit(rng));
    const int n_a = size(rng);
    const Json a = randomPoints(n_a, Eigen::Vector3d::Zero(), half_a, rng);
    Eigen::Vector3d offset = 3.0 * vec();
    const double half_b = 0.5 + std::abs(unit(rng));
    const int n_b = size(rng);
    Json b = randomPoints(n_b, Eigen::Vector3d::Zero(), half_b, rng);
    Eigen::Vector3d s = vec();
    if (i % 5 == 0) {
      const Eigen::Vector3d d = vec().normalized();
      offset = support(a, d) - support(b, -d);
    } else if (i % 5 == 1) {
      s = 0.2 * vec() - offset;
    } else if (i % 5 == 2) {
      offset *= 0.1;
    }
    for (Json& p : b)
      p = {p[0].get<double>() + offset.x(), p[1].get<double>() + offset.y(), p[2].get<double>() + offset.z()};
    input += queryLine(i, a, b, {s.x(), s.y(), s.z()});
  }
  return input;
}

void expectSameNumberOrNull(const Json& x, const Json& y, double tol, const std::string& what) {
  ASSERT_EQ(x.is_null(), y.is_null()) << what << ": " << x << " vs " << y;
  if (!x.is_null()) {
    EXPECT_NEAR(x.get<double>(), y.get<double>(), tol) << what;
  }
}

TEST(CliQuery, DualAgreesWithBruteForceOnRandomLines) {
  constexpr int kLines = 50;
  const std::string input = randomLines(kLines);
  const CliRun dual_run = runQuery(input, "dual");
  const CliRun brute_run = runQuery(input, "brute");
  ASSERT_EQ(dual_run.exit_code, 0) << dual_run.out << dual_run.err;
  ASSERT_EQ(brute_run.exit_code, 0) << brute_run.out << brute_run.err;
  const std::vector<Json> dual = parseLines(dual_run.out);
  const std::vector<Json> brute = parseLines(brute_run.out);
  ASSERT_EQ(dual.size(), static_cast<std::size_t>(kLines));
  ASSERT_EQ(brute.size(), static_cast<std::size_t>(kLines));
  const double tol = 1e-9 * 10.0;  // coordinates stay within about 10
  std::map<std::string, int> statuses;
  for (int i = 0; i < kLines; ++i) {
    const Json& d = dual[static_cast<std::size_t>(i)];
    const Json& b = brute[static_cast<std::size_t>(i)];
    SCOPED_TRACE("line " + std::to_string(i) + "\n  dual:  " + d.dump() + "\n  brute: " + b.dump());
    EXPECT_EQ(d["id"], i);
    EXPECT_EQ(b["id"], i);
    EXPECT_EQ(d["status"], b["status"]);
    expectSameNumberOrNull(d["mdd"], b["mdd"], tol, "mdd");
    expectSameNumberOrNull(d["toi"], b["toi"], tol, "toi");
    EXPECT_EQ(d["intersecting"], b["intersecting"]);
    // Both ends, except the far end of a separated answer, which MDD-DUAL
    // computes only when needed (null, or the brute force's value).
    const bool forward = b["t_lo"].is_number() && b["t_lo"].get<double>() > 0.0;
    for (const char* end : {"t_lo", "t_hi"}) {
      const bool far_end = d["status"] == "separated" && (std::string(end) == "t_lo" ? !forward : forward);
      if (!(far_end && d[end].is_null())) expectSameNumberOrNull(d[end], b[end], tol, end);
    }
    if (d["status"] == "separated" || d["status"] == "penetrating") {
      const Json& n = b["normal"];
      expectVector(d["normal"], n[0].get<double>(), n[1].get<double>(), n[2].get<double>(), 1e-6, "normal");
    }
    ++statuses[d["status"].get<std::string>()];
  }
  for (const auto& [status, count] : statuses) std::printf("  %s: %d\n", status.c_str(), count);
  // The placements must exercise every kind of answer.
  EXPECT_GE(statuses["touching"], 5);
  EXPECT_GE(statuses["separated"], 5);
  EXPECT_GE(statuses["penetrating"], 5);
  EXPECT_GE(statuses["no_contact"], 5);
}

// ---- Files, streaming, demo ---------------------------------------------------

TEST(CliQuery, OutputOptionWritesTheFile) {
  const TempDir dir;
  const std::string input = dir.write(
      "in.jsonl", queryLine("x", cube(0.0), cube(-3.0), {1, 0, 0}) + queryLine("y", cube(0.0), cube(-0.5), {1, 0, 0}));
  const std::string output = dir.path() + "/out.jsonl";
  const CliRun run = runCli({"query", "--input", input, "--output", output});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
  const std::vector<Json> out = parseLines(readFile(output));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0]["id"], "x");
  EXPECT_EQ(out[0]["status"], "separated");
  EXPECT_EQ(out[1]["id"], "y");
  EXPECT_EQ(out[1]["status"], "penetrating");
}

TEST(CliQuery, AnswersEachLineBeforeTheInputEnds) {
  CliProcess process({"query"});
  process.write(queryLine("first", cube(0.0), cube(-3.0), {1, 0, 0}));
  std::string line;
  ASSERT_TRUE(process.readLine(&line, 10000)) << "no answer while the input is still open";
  EXPECT_EQ(Json::parse(line)["id"], "first");
  process.write("{\"id\": \"second\", \"a\": 5}\n");
  ASSERT_TRUE(process.readLine(&line, 10000));
  EXPECT_EQ(Json::parse(line)["id"], "second");
  EXPECT_TRUE(Json::parse(line).contains("error"));
  process.closeInput();
  EXPECT_FALSE(process.readLine(&line, 10000));
  EXPECT_EQ(process.wait(), 1);
}

TEST(CliDemo, RunsAndAgreesWithTheBruteForce) {
  const TempDir dir;
  const std::string jsonl = dir.path() + "/demo.jsonl";
  const CliRun run = runCli({"demo", "--emit-jsonl", jsonl});
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("15 queries, 15 agree with the brute force"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find(" NO"), std::string::npos) << run.out;

  // The emitted queries go through `mddual query` and cover every status,
  // and the brute force (`--method brute`, not the demo's own comparison)
  // gives the same statuses and distances.
  const CliRun query = runCli({"query", "--input", jsonl});
  EXPECT_EQ(query.exit_code, 0) << query.err;
  const std::vector<Json> out = parseLines(query.out);
  ASSERT_EQ(out.size(), 15u);
  const CliRun brute_run = runCli({"query", "--method", "brute", "--input", jsonl});
  EXPECT_EQ(brute_run.exit_code, 0) << brute_run.err;
  const std::vector<Json> brute = parseLines(brute_run.out);
  ASSERT_EQ(brute.size(), 15u);
  std::set<std::string> statuses;
  for (std::size_t i = 0; i < out.size(); ++i) {
    SCOPED_TRACE("query " + std::to_string(i) + "\n  dual:  " + out[i].dump() + "\n  brute: " + brute[i].dump());
    statuses.insert(out[i]["status"].get<std::string>());
    EXPECT_EQ(out[i]["status"], brute[i]["status"]);
    expectSameNumberOrNull(out[i]["mdd"], brute[i]["mdd"], 1e-8, "mdd");
  }
  EXPECT_EQ(statuses, (std::set<std::string>{"separated", "touching", "penetrating", "no_contact"}));
}

TEST(CliDemo, SeedAndPairsOptions) {
  const CliRun run = runCli({"demo", "--seed", "7", "--pairs", "4"});
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("4 queries, 4 agree with the brute force"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace mddual::cli_test
