// Fuzz target: one run of `mddual query`, `mddual pd` and `mddual width` on
// the fuzzed bytes as their JSON Lines input (the CLI's own code: CLI11
// parsing, runJsonLines, the per-line handlers). The first byte picks pd's
// method. Every line must be answered or refused with that line's error; an
// exception other than the CLI's own exit statuses escaping is a finding.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "commands.h"
#include "fuzz_input_file.h"
#include "mddual/error.h"

namespace {

void runCommand(const std::vector<std::string>& args) {
  CLI::App app("mddual (fuzz)");
  app.require_subcommand(1);
  mddual::cli::registerQueryCommand(app);
  mddual::cli::registerPdCommand(app);
  mddual::cli::registerWidthCommand(app);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
    // Exit statuses (1: some line failed) and usage errors: answers.
  } catch (const mddual::cli::FatalError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kMethods[] = {"exact", "shallow", "approx", "brute"};
  const std::string method = kMethods[data[0] % 4];
  const std::string file = mddual::fuzz::writeInput(data + 1, size - 1, ".jsonl").string();
  runCommand({"query", "--input", file, "--output", "/dev/null"});
  runCommand({"pd", "--method", method, "--input", file, "--output", "/dev/null"});
  runCommand({"width", "--input", file, "--output", "/dev/null"});
  return 0;
}
