// prt: command-line entry point. Parses arguments with CLI11 and runs one subcommand.
// Every user-facing failure is a prt::Error: printed as one line "prt: <message>", exit status 1.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"

int main(int argc, char** argv) {
  prt::install_cleanup_signal_handlers();
  CLI::App app{"prt: precomputed radiance transfer engine (SH lighting, transfer baking, relighting)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "prt 0.1.0");
  // Subcommands are registered here as the modules that implement them land.
  prt::cli::add_bake_command(app);
  prt::cli::add_shade_command(app);
  prt::cli::add_info_command(app);
  prt::cli::add_compare_command(app);
  prt::cli::add_reference_command(app);
  prt::cli::add_light_command(app);
  prt::cli::add_brdf_command(app);
  prt::cli::add_probes_command(app);
  prt::cli::add_probes_relight_command(app);
  prt::cli::add_compress_command(app);
#ifdef PRT_WITH_GL
  prt::cli::add_render_command(app);
  prt::cli::add_view_command(app);
#endif
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
