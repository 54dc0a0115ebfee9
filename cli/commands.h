// Subcommands of the `mddual` tool. Each one lives in its own file and adds
// itself to the app with a register*Command() function called from main.cpp.
//
// Exit-status convention, shared by every subcommand:
//   0  success;
//   1  the command ran to the end but some input lines failed or some answers
//      disagreed (the callback throws CLI::RuntimeError(1));
//   2  the command could not run: a usage error (unknown option or
//      subcommand, missing or bad value: CLI11's message), bad input,
//      unreadable or unwritable file, unexpected exception (the callback
//      throws FatalError, main prints "mddual: <what>").
#pragma once

#include <stdexcept>

namespace CLI {
class App;
}  // namespace CLI

namespace mddual::cli {

/// A failure that stops the whole command: main prints "mddual: " + what() on
/// standard error and exits with status 2.
class FatalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `mddual query`: MDD, TOI and intersection of point-set hulls read as JSON Lines.
void registerQueryCommand(CLI::App& app);

/// `mddual demo`: a few generated scenes answered by MDD-DUAL and by brute force.
void registerDemoCommand(CLI::App& app);

/// `mddual pd`: penetration depth (exact, shallow, approximate, polyhedral metric) per JSON line.
void registerPdCommand(CLI::App& app);

/// `mddual width`: width of a polytope per JSON line.
void registerWidthCommand(CLI::App& app);

/// `mddual distance`: separation distance (or minus the penetration depth) per JSON line.
void registerDistanceCommand(CLI::App& app);

/// `mddual bench` and `mddual bench-report`: the OMPL benchmark of a config with
/// MDD-DUAL's and FCL's checkers (built with the planning layer only,
/// MDDUAL_CLI_WITH_BENCH).
void registerBenchCommand(CLI::App& app);

}  // namespace mddual::cli
