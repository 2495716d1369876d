#pragma once
// Each prt subcommand lives in its own cmd_<name>.cpp and registers itself on the root app.
#include <CLI/CLI.hpp>

namespace prt::cli {

void add_light_command(CLI::App& app);

}  // namespace prt::cli
