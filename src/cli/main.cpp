// prt: command-line entry point. Parses arguments with CLI11 and runs one subcommand.
// Every user-facing failure is a prt::Error: printed as one line "prt: <message>", exit status 1.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"prt: precomputed radiance transfer engine (SH lighting, transfer baking, relighting)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "prt 0.1.0");
  // Subcommands are registered here as the modules that implement them land.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "prt: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
