// Entry point of the `mddual` command-line tool: builds the CLI11 app, lets
// each subcommand register itself, and maps exceptions to exit statuses (see
// commands.h). Nothing here knows about any particular subcommand's options.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "commands.h"

namespace {

/// The subcommands' names, "query, demo, ...".
std::string subcommandNames(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

/// CLI11 answers a first argument that names no subcommand with "A
/// subcommand is required" (or "arguments were not expected"): name it and
/// list the subcommands instead. Returns the exit status (2, a usage error),
/// or -1 when the first argument is a subcommand or an option.
int unknownSubcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return -1;
  const std::string name = argv[1];
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->check_name(name)) return -1;
  }
  std::string shown = name;
  constexpr std::size_t kMaxShown = 200;  // bytes of a user string quoted in a message
  if (shown.size() > kMaxShown) shown = shown.substr(0, kMaxShown) + "... (" + std::to_string(name.size()) + " bytes)";
  std::cerr << "mddual: unknown subcommand '" << shown << "' (subcommands: " << subcommandNames(app)
            << "; mddual --help describes them)\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  CLI::App app{"mddual: exact minimum directional distance (MDD-DUAL) between convex polytopes", "mddual"};
  app.require_subcommand(1);
  mddual::cli::registerQueryCommand(app);
  mddual::cli::registerDemoCommand(app);
  mddual::cli::registerPdCommand(app);
  mddual::cli::registerWidthCommand(app);
  mddual::cli::registerDistanceCommand(app);
#ifdef MDDUAL_CLI_WITH_BENCH
  mddual::cli::registerBenchCommand(app);
#endif
  const int unknown = unknownSubcommand(app, argc, argv);
  if (unknown >= 0) return unknown;
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a subcommand's exit status (1), silently
  } catch (const CLI::ParseError& e) {
    // Usage errors (unknown option, missing value, bad --method) print
    // CLI11's message and exit with 2, the status of every other bad input;
    // --help prints the help and exits with 0.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const mddual::cli::FatalError& e) {
    std::cout.flush();
    std::cerr << "mddual: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cout.flush();
    std::cerr << "mddual: unexpected error: " << e.what() << '\n';
    return 2;
  } catch (...) {
    std::cout.flush();
    std::cerr << "mddual: unexpected error (unknown exception)\n";
    return 2;
  }
  return 0;
}
