// Entry point of the `mddual` command-line tool: builds the CLI11 app, lets
// each subcommand register itself, and maps exceptions to exit statuses (see
// commands.h). Nothing here knows about any particular subcommand's options.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "commands.h"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  CLI::App app{"mddual: exact minimum directional distance (MDD-DUAL) between convex polytopes", "mddual"};
  app.require_subcommand(1);
  mddual::cli::registerQueryCommand(app);
  mddual::cli::registerDemoCommand(app);
  mddual::cli::registerPdCommand(app);
  mddual::cli::registerWidthCommand(app);
#ifdef MDDUAL_CLI_WITH_BENCH
  mddual::cli::registerBenchCommand(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Usage errors print CLI11's message; CLI::RuntimeError carries a
    // subcommand's exit status silently.
    return app.exit(e);
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
