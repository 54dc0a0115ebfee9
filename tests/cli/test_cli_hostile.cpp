// Hostile input to the JSON Lines commands: lines nested tens of
// thousands deep, a line that runs out of memory, ids beyond 64-bit integers,
// a directory as --input, an unknown subcommand, --delta values the methods
// cannot run with, and huge user strings in messages. Each gets a clear error
// (one line's error, or a usage error naming the option), nothing crashes,
// and the lines after a bad one are still answered.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "cli_fixtures.h"
#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

/// Nesting depth the CLI accepts (cli/jsonl.h kMaxJsonDepth).
constexpr int kMaxDepth = 64;
/// Deep enough to overflow the stack of a recursive writer.
constexpr int kHostileDepth = 70000;

std::string nested(int depth) {
  return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']');
}

/// One line for each per-line command (query needs b and a direction, pd and
/// distance b).
std::string goodLine(const std::string& command, const std::string& id_text) {
  const Json a = cube(0.0);
  const Json b = cube(3.0);
  std::string fields = "\"a\": " + a.dump();
  if (command != "width") fields += ", \"b\": " + b.dump();
  if (command == "query") fields += ", \"direction\": [1, 0, 0]";
  return "{\"id\": " + id_text + ", " + fields + "}\n";
}

/// The id's text in a raw output line ({"id":<text>,...}).
std::string rawId(const std::string& line) {
  const std::string prefix = "{\"id\":";
  if (line.compare(0, prefix.size(), prefix) != 0) return "<no id first: " + line.substr(0, 80) + ">";
  const std::size_t comma = line.find(",\"", prefix.size());
  return line.substr(prefix.size(), comma - prefix.size());
}

TEST(CliHostile, DeeplyNestedLinesAreLineErrors) {
  const std::string deep_error =
      "invalid JSON: arrays and objects nested deeper than " + std::to_string(kMaxDepth) + " levels (at byte ";
  for (const std::string command : {"query", "pd", "width", "distance"}) {
    SCOPED_TRACE(command);
    std::string in = goodLine(command, "\"first\"");
    in += goodLine(command, nested(kHostileDepth));  // 70,000 deep in the id
    in += nested(kHostileDepth) + "\n";              // the whole line
    in += std::string(kHostileDepth, '[') + "\n";    // unclosed
    in += goodLine(command, nested(kMaxDepth - 1));  // 64 with the line's object: accepted
    in += goodLine(command, nested(kMaxDepth));      // 65: refused
    in += goodLine(command, "\"[[[[\"");             // brackets in strings do not count
    in += goodLine(command, "\"last\"");
    const CliRun run = runCli({command}, in);
    EXPECT_EQ(run.signal, 0);
    EXPECT_EQ(run.exit_code, 1) << run.err;
    const std::vector<std::string> lines = splitLines(run.out);
    ASSERT_EQ(lines.size(), 8u) << run.out.substr(0, 2000);
    const std::vector<Json> out = parseLines(run.out);
    ASSERT_EQ(out.size(), 8u);
    EXPECT_EQ(out[0]["id"], "first");
    EXPECT_FALSE(out[0].contains("error")) << lines[0];
    for (int k : {1, 2, 3, 5}) {
      EXPECT_TRUE(out[k]["id"].is_null()) << lines[k];
      ASSERT_TRUE(out[k].contains("error")) << lines[k];
      EXPECT_EQ(out[k]["error"].get<std::string>().rfind(deep_error, 0), 0u) << lines[k];
    }
    EXPECT_EQ(out[1]["error"], deep_error + "71)");  // the id's 64th bracket (65th with the object's)
    EXPECT_EQ(out[2]["error"], deep_error + "65)");
    EXPECT_EQ(out[3]["error"], deep_error + "65)");
    EXPECT_EQ(out[5]["error"], deep_error + "71)");
    EXPECT_EQ(rawId(lines[4]), nested(kMaxDepth - 1));
    EXPECT_FALSE(out[4].contains("error")) << lines[4];
    EXPECT_EQ(out[6]["id"], "[[[[");
    EXPECT_FALSE(out[6].contains("error")) << lines[6];
    EXPECT_EQ(out[7]["id"], "last");
    EXPECT_FALSE(out[7].contains("error")) << lines[7];
  }
}

/// Points on a sphere of radius 1 about (cx, 0, 0) (Fibonacci lattice): every
/// one is a vertex of the hull.
Json spherePoints(int n, double cx) {
  Json points = Json::array();
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - y * y);
    points.push_back({cx + r * std::cos(golden * i), y, r * std::sin(golden * i)});
  }
  return points;
}

TEST(CliHostile, OutOfMemoryOnOneLineIsThatLinesError) {
  // The brute force on 3,000 x 3,000 hull vertices builds 9 million
  // differences (about 900 MB); under an address-space limit a little above
  // what a small query needs, that line runs out of memory and the others
  // are answered. The limit: the smallest of these that answers a small
  // query, plus kHeadroom (how much the huge line allocates before failing).
  constexpr std::size_t kMB = 1024 * 1024;
  constexpr std::size_t kHeadroom = 16 * kMB;
  const std::string small = queryLine("small", cube(0.0), cube(3.0), {1, 0, 0});
  std::size_t limit = 0;
  for (std::size_t mb : {64, 96, 128, 192, 256, 384, 512}) {
    const CliRun probe = runCliWithMemoryLimit({"query", "--method", "brute"}, small, mb * kMB);
    if (probe.exit_code == 0 && parseLines(probe.out).size() == 1u) {
      limit = mb * kMB + kHeadroom;
      break;
    }
  }
  ASSERT_GT(limit, 0u) << "mddual query does not run under 512 MB";

  std::string in = queryLine("before", cube(0.0), cube(3.0), {1, 0, 0});
  in += queryLine("huge", spherePoints(3000, 0.0), spherePoints(3000, 3.0), {1, 0, 0});
  in += queryLine("after", cube(0.0), cube(-3.0), {1, 0, 0});
  const CliRun run = runCliWithMemoryLimit({"query", "--method", "brute"}, in, limit);
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(run.err, "");
  const std::vector<Json> out = parseLines(run.out);
  ASSERT_EQ(out.size(), 3u) << run.out;
  EXPECT_EQ(out[0]["id"], "before");
  EXPECT_EQ(out[0]["status"], "separated");
  EXPECT_EQ(out[1], (Json{{"id", "huge"}, {"error", "out of memory while answering this line (std::bad_alloc)"}}));
  EXPECT_EQ(out[2]["id"], "after");
  EXPECT_EQ(out[2]["status"], "separated");
}

TEST(CliHostile, IdsAreEchoedExactlyAsGiven) {
  const std::vector<std::string> ids = {"-99999999999999999999999",
                                        "99999999999999999999999",
                                        "-9223372036854775809",
                                        "18446744073709551616",
                                        "1e2",
                                        "1.0",
                                        "-0.0",
                                        "0.1000000000000000055511151231257827",
                                        "{\"k\": [1, 2.50, {\"x\": null}]}",
                                        "\"caf\\u00e9 \\\"q\\\"\"",
                                        "true"};
  for (const std::string command : {"query", "pd", "width", "distance"}) {
    SCOPED_TRACE(command);
    std::string in;
    for (const std::string& id : ids) in += goodLine(command, id);
    // Error lines echo it too; a repeated id: the last one, as the parser keeps.
    in += "{\"id\": 12345678901234567890123, \"a\": 7}\n";
    in += "{\"id\": 1, \"a\": [], \"id\" : 2e0 }\n";
    in += "{\"\\u0069d\": -1e999999999, \"a\": 1}\n";  // out of range: invalid JSON, no id
    const CliRun run = runCli({command}, in);
    EXPECT_EQ(run.exit_code, 1) << run.err;
    const std::vector<std::string> lines = splitLines(run.out);
    ASSERT_EQ(lines.size(), ids.size() + 3) << run.out;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      EXPECT_EQ(rawId(lines[i]), ids[i]) << lines[i];
      EXPECT_EQ(lines[i].find("\"error\""), std::string::npos) << lines[i];
    }
    EXPECT_EQ(rawId(lines[ids.size()]), "12345678901234567890123") << lines[ids.size()];
    EXPECT_EQ(rawId(lines[ids.size() + 1]), "2e0") << lines[ids.size() + 1];
    EXPECT_EQ(rawId(lines[ids.size() + 2]), "null") << lines[ids.size() + 2];
    const std::vector<Json> out = parseLines(run.out);
    ASSERT_EQ(out.size(), lines.size());
    EXPECT_EQ(out[8]["id"], Json::parse(ids[8]));
  }
}

TEST(CliHostile, DirectoryAsInputOrOutputIsNamed) {
  const TempDir dir;
  const CliRun in = runCli({"query", "--input", dir.path()});
  EXPECT_EQ(in.exit_code, 2);
  EXPECT_EQ(in.err, "mddual: --input '" + dir.path() + "' is a directory, not a file\n");
  EXPECT_EQ(in.out, "");
  const std::string file = dir.write("in.jsonl", queryLine(1, cube(0.0), cube(3.0), {1, 0, 0}));
  const CliRun out = runCli({"pd", "--input", file, "--output", dir.path()});
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_EQ(out.err, "mddual: --output '" + dir.path() + "' is a directory, not a file\n");
}

TEST(CliHostile, UnknownSubcommandIsNamed) {
  const CliRun run = runCli({"frobnicate", "--input", "x"});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(run.err.rfind("mddual: unknown subcommand 'frobnicate' (subcommands: query, demo, pd, width", 0), 0u)
      << run.err;
  EXPECT_NE(run.err.find("; mddual --help describes them)\n"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
  // A huge name is cut in the message.
  const std::string huge(100000, 'x');
  const CliRun long_name = runCli({huge});
  EXPECT_NE(long_name.exit_code, 0);
  EXPECT_NE(long_name.err.find("'" + std::string(200, 'x') + "... (100000 bytes)'"), std::string::npos);
  EXPECT_LT(long_name.err.size(), 1000u);
  // The subcommands still work, and a missing one is still CLI11's error.
  EXPECT_EQ(runCli({"query"}, "").exit_code, 0);
  EXPECT_NE(runCli({}).exit_code, 0);
}

struct DeltaCase {
  std::vector<std::string> args;
  std::string message;  ///< the first line of standard error; empty: accepted
};

TEST(CliHostile, DeltaIsCheckedUpFrontPerMethod) {
  const std::vector<DeltaCase> cases = {
      {{"pd", "--method", "shallow", "--delta", "2e-5"},
       "--delta: '2e-5' is outside [0.0004, 1000], the range of --method shallow (shallow first approximates with "
       "delta / 4)"},
      {{"pd", "--method", "shallow", "--delta", "3e-4"},
       "--delta: '3e-4' is outside [0.0004, 1000], the range of --method shallow (shallow first approximates with "
       "delta / 4)"},
      {{"pd", "--method", "shallow", "--delta", "4e-4"}, ""},
      {{"pd", "--method", "approx", "--delta", "2e-5"},
       "--delta: '2e-5' is outside [0.0001, 1000], the range of --method approx"},
      {{"pd", "--method", "approx", "--delta", "1e-4"}, ""},
      {{"pd", "--delta", "nan"}, "--delta: 'nan' is not a finite number"},
      {{"pd", "--method", "approx", "--delta", "inf"}, "--delta: 'inf' is not a finite number"},
      {{"pd", "--method", "approx", "--delta", "0.1x"}, "--delta: '0.1x' is not a finite number"},
      {{"pd", "--method", "exact", "--delta", "0.01"}, ""},
      {{"width", "--method", "approx", "--delta", "nan"}, "--delta: 'nan' is not a finite number"},
      {{"width", "--method", "approx", "--delta", "1e9"},
       "--delta: '1e9' is outside [0.0001, 1000], the range of --method approx"},
  };
  const TempDir dir;
  for (const DeltaCase& c : cases) {
    std::string shown;
    for (const std::string& a : c.args) shown += a + " ";
    SCOPED_TRACE(shown);
    // --output names a file that a usage error must leave untouched.
    const std::string output = dir.write("out.jsonl", "keep\n");
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--output", output});
    const std::string line = c.args[0] == "width" ? goodLine("width", "1") : goodLine("pd", "1");
    const CliRun run = runCli(args, line);
    if (c.message.empty()) {
      EXPECT_EQ(run.exit_code, 0) << run.err;
      const std::vector<Json> out = parseLines(readFile(output));
      ASSERT_EQ(out.size(), 1u);
      EXPECT_FALSE(out[0].contains("error")) << out[0];
    } else {
      EXPECT_NE(run.exit_code, 0);
      EXPECT_NE(run.exit_code, 1) << "a usage error, not a line failure";
      EXPECT_EQ(splitLines(run.err).at(0), c.message) << run.err;
      EXPECT_EQ(readFile(output), "keep\n");
    }
  }
}

TEST(CliHostile, HugeUserStringsAreCutInMessages) {
  // The JSON parser quotes the token it failed on: a 1 MB string with a raw
  // control character at its end is cut.
  const std::string token = "\"" + std::string(1 << 20, 'z') + "\x01\"";
  const CliRun run = runCli({"query"}, "{\"id\": 1, \"a\": " + token + "}\n");
  EXPECT_EQ(run.exit_code, 1);
  const std::vector<Json> out = parseLines(run.out);
  ASSERT_EQ(out.size(), 1u);
  const std::string error = out[0]["error"].get<std::string>();
  EXPECT_EQ(error.rfind("invalid JSON: ", 0), 0u) << error.substr(0, 300);
  EXPECT_LT(error.size(), 300u) << error.substr(0, 300);
  EXPECT_NE(error.find("... ("), std::string::npos) << error.substr(0, 300);
  // An --input path of 4,000 bytes.
  const std::string path = "/nonexistent/" + std::string(4000, 'p');
  const CliRun missing = runCli({"query", "--input", path});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_LT(missing.err.size(), 300u) << missing.err.substr(0, 300);
  EXPECT_NE(missing.err.find("(4013 bytes)"), std::string::npos) << missing.err.substr(0, 300);
}

}  // namespace
}  // namespace mddual::cli_test
