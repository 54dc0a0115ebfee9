// `mddual query` on bad input: per-line error lines (the run goes on), exit
// statuses, usage errors and files that cannot be opened.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_fixtures.h"
#include "cli_runner.h"

namespace mddual::cli_test {
namespace {

/// Expects an error line with this id whose message contains `needle`.
void expectError(const Json& r, const Json& id, const std::string& needle) {
  EXPECT_EQ(r["id"], id) << r.dump();
  ASSERT_TRUE(r.contains("error") && r["error"].is_string()) << r.dump();
  EXPECT_NE(r["error"].get<std::string>().find(needle), std::string::npos)
      << "error should mention '" << needle << "': " << r.dump();
  EXPECT_FALSE(r.contains("status")) << r.dump();
}

void expectAnswer(const Json& r, const Json& id, const std::string& status) {
  EXPECT_EQ(r["id"], id) << r.dump();
  EXPECT_FALSE(r.contains("error")) << r.dump();
  EXPECT_EQ(r["status"], status) << r.dump();
}

std::string badInput() {
  const Json a = cube(0.0);
  const Json b = cube(-3.0);
  std::string in;
  in += queryLine("good-1", a, b, {1, 0, 0});
  in += "{\"id\": \"broken\", \"a\": [[0, 0, 0], \n";  // unparsable: the id cannot be read
  in += Json{{"id", "no-b"}, {"a", a}, {"direction", {1, 0, 0}}}.dump() + "\n";
  in += queryLine("two-numbers", Json::array({{0, 0, 0}, {1, 2}, {0, 1, 0}, {0, 0, 1}}), b, {1, 0, 0});
  in += queryLine("collinear", Json::array({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}), b, {1, 0, 0});
  in += queryLine("zero-direction", a, b, {0, 0, 0});
  in += "\n   \t \n";  // blank lines: no output
  in += queryLine("direction-text", a, b, "x");
  in += queryLine("b-not-array", a, 7, {1, 0, 0});
  in += queryLine("string-coordinate", a, Json::array({{0, 0, 0}, {1, 0, "0"}, {0, 1, 0}, {0, 0, 1}}), {1, 0, 0});
  in += queryLine("empty-a", Json::array(), b, {1, 0, 0});
  in += "[1, 2, 3]\n";  // not an object
  in += queryLine("good-2", a, cube(-0.5), {1, 0, 0});
  return in;
}

void checkBadInputOutput(const CliRun& run) {
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const std::vector<Json> out = parseLines(run.out);
  ASSERT_EQ(out.size(), 12u) << run.out;
  expectAnswer(out[0], "good-1", "separated");
  expectError(out[1], nullptr, "invalid JSON");
  expectError(out[2], "no-b", "b: missing field");
  expectError(out[3], "two-numbers", "a[1]: expected 3 numbers");
  expectError(out[4], "collinear", "a: ");
  expectError(out[4], "collinear", "collinear");
  expectError(out[5], "zero-direction", "direction: must be finite and nonzero");
  expectError(out[6], "direction-text", "direction: expected 3 numbers");
  expectError(out[7], "b-not-array", "b: expected an array of points");
  expectError(out[8], "string-coordinate", "b[1]: expected 3 numbers");
  expectError(out[9], "empty-a", "a: expected at least one point");
  expectError(out[10], nullptr, "expected a JSON object");
  expectAnswer(out[11], "good-2", "penetrating");
}

TEST(CliErrors, BadLinesGetErrorLinesAndTheRunGoesOn) {
  const CliRun run = runQuery(badInput());
  checkBadInputOutput(run);
}

TEST(CliErrors, BadLinesWithTheBruteForce) {
  const CliRun run = runQuery(badInput(), "brute");
  checkBadInputOutput(run);
}

TEST(CliErrors, NonFiniteNumbersAreErrorLines) {
  const Json a = cube(0.0);
  std::string in = R"({"id": "nan", "a": [[NaN, 0, 0]], "b": [[0, 0, 0]], "direction": [1, 0, 0]})"
                   "\n";
  in += R"({"id": "huge", "a": [[0, 0, 0], [1e400, 0, 0]], "b": [[0, 0, 0]], "direction": [1, 0, 0]})"
        "\n";
  in += queryLine("after", a, cube(-3.0), {1, 0, 0});
  const CliRun run = runQuery(in);
  EXPECT_EQ(run.exit_code, 1);
  const std::vector<Json> out = parseLines(run.out);
  ASSERT_EQ(out.size(), 3u) << run.out;
  EXPECT_TRUE(out[0].contains("error")) << out[0];
  EXPECT_TRUE(out[1].contains("error")) << out[1];
  expectAnswer(out[2], "after", "separated");
}

TEST(CliErrors, AllGoodInputExitsZero) {
  std::string in;
  for (int i = 0; i < 5; ++i) in += queryLine(i, cube(0.0), cube(-3.0 + i), {1, 0.1 * i, 0});
  in += "\n";
  const CliRun run = runQuery(in);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(parseLines(run.out).size(), 5u);
}

TEST(CliErrors, EmptyInputExitsZero) {
  const CliRun run = runQuery("");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(CliErrors, UnknownOptionFails) {
  const CliRun run = runCli({"query", "--frobnicate"});
  EXPECT_EQ(run.exit_code, 2) << "signal " << run.signal;  // a usage error is bad input
  EXPECT_NE(run.err.find("--frobnicate"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(CliErrors, BadMethodFails) {
  const CliRun run = runCli({"query", "--method", "foo"}, queryLine(1, cube(0.0), cube(-3.0), {1, 0, 0}));
  EXPECT_EQ(run.exit_code, 2) << "signal " << run.signal;
  EXPECT_NE(run.err.find("foo"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(CliErrors, MissingSubcommandFails) {
  const CliRun run = runCli({});
  EXPECT_EQ(run.exit_code, 2) << "signal " << run.signal;
}

// Every usage error exits with 2, the status of bad input (CLI11's own codes,
// 105 to 115, before): an unknown subcommand, an extra argument, an option
// given twice or without its value, a value out of its range.
TEST(CliErrors, UsageErrorsExitTwo) {
  const std::vector<std::vector<std::string>> cases = {
      {"frobnicate"},           {"query", "extra-positional"},
      {"query", "--method"},    {"query", "--method", "mdd", "--method", "mdd"},
      {"demo", "--pairs", "0"},
  };
  for (const std::vector<std::string>& args : cases) {
    const CliRun run = runCli(args);
    std::string shown;
    for (const std::string& a : args) shown += " " + a;
    EXPECT_EQ(run.exit_code, 2) << "mddual" << shown << ": signal " << run.signal << ", " << run.err;
    EXPECT_FALSE(run.err.empty()) << "mddual" << shown;
  }
}

TEST(CliErrors, MissingInputFileExitsTwo) {
  const TempDir dir;
  const std::string missing = dir.path() + "/no-such-file.jsonl";
  const CliRun run = runCli({"query", "--input", missing});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("mddual: cannot open input file '" + missing + "'"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(CliErrors, UnwritableOutputFileExitsTwo) {
  const TempDir dir;
  const std::string input = dir.write("in.jsonl", queryLine(1, cube(0.0), cube(-3.0), {1, 0, 0}));
  const std::string bad = dir.path() + "/no-such-dir/out.jsonl";
  const CliRun run = runCli({"query", "--input", input, "--output", bad});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("cannot open output file '" + bad + "'"), std::string::npos) << run.err;
}

TEST(CliErrors, OutputOverInputIsRefused) {
  const TempDir dir;
  const std::string line = queryLine(1, cube(0.0), cube(-3.0), {1, 0, 0});
  const std::string file = dir.write("in.jsonl", line);
  const CliRun run = runCli({"query", "--input", file, "--output", file});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("same file"), std::string::npos) << run.err;
  EXPECT_EQ(readFile(file), line);  // not truncated
}

TEST(CliErrors, HelpExitsZero) {
  const CliRun run = runCli({"query", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("--method"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace mddual::cli_test
