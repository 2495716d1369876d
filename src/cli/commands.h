#pragma once
// Each prt subcommand lives in its own cmd_<name>.cpp and registers itself on the root app.
#include <CLI/CLI.hpp>

namespace prt::cli {

void add_light_command(CLI::App& app);
void add_bake_command(CLI::App& app);
void add_shade_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_brdf_command(CLI::App& app);
void add_probes_command(CLI::App& app);
void add_probes_relight_command(CLI::App& app);
void add_compress_command(CLI::App& app);
void add_unwrap_command(CLI::App& app);
// Built only with PRT_BUILD_GL (main.cpp registers them when PRT_WITH_GL is defined).
void add_render_command(CLI::App& app);
void add_view_command(CLI::App& app);

}  // namespace prt::cli
