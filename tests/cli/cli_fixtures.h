// Query lines for the CLI tests: point sets, input lines, parsed output.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace mddual::cli_test {

using Json = nlohmann::json;

/// The 8 corners of the axis-aligned cube [x, x+size] x [y, y+size] x [z, z+size].
inline Json cube(double x, double y = 0.0, double z = 0.0, double size = 1.0) {
  Json points = Json::array();
  for (int i = 0; i < 8; ++i) {
    points.push_back(
        {x + ((i & 1) != 0 ? size : 0.0), y + ((i & 2) != 0 ? size : 0.0), z + ((i & 4) != 0 ? size : 0.0)});
  }
  return points;
}

/// One input line of `mddual query`.
inline std::string queryLine(const Json& id, const Json& a, const Json& b, const Json& direction) {
  return Json{{"id", id}, {"a", a}, {"b", b}, {"direction", direction}}.dump() + "\n";
}

/// Parses every output line; a line that is not JSON fails the test.
inline std::vector<Json> parseLines(const std::string& text) {
  std::vector<Json> out;
  for (const std::string& line : splitLines(text)) {
    try {
      out.push_back(Json::parse(line));
    } catch (const Json::exception& e) {
      ADD_FAILURE() << "output line is not JSON: " << line << " (" << e.what() << ")";
    }
  }
  return out;
}

/// Runs `mddual query [--method method]` on `input` (standard input).
inline CliRun runQuery(const std::string& input, const std::string& method = "") {
  std::vector<std::string> args{"query"};
  if (!method.empty()) args.insert(args.end(), {"--method", method});
  return runCli(args, input);
}

/// Expects a JSON array of three numbers within tol of (x, y, z).
inline void expectVector(const Json& v, double x, double y, double z, double tol, const std::string& what) {
  ASSERT_TRUE(v.is_array() && v.size() == 3) << what << " = " << v.dump();
  EXPECT_NEAR(v[0].get<double>(), x, tol) << what << " = " << v.dump();
  EXPECT_NEAR(v[1].get<double>(), y, tol) << what << " = " << v.dump();
  EXPECT_NEAR(v[2].get<double>(), z, tol) << what << " = " << v.dump();
}

/// Expects a JSON number within tol of x.
inline void expectNumber(const Json& v, double x, double tol, const std::string& what) {
  ASSERT_TRUE(v.is_number()) << what << " = " << v.dump();
  EXPECT_NEAR(v.get<double>(), x, tol) << what;
}

}  // namespace mddual::cli_test
