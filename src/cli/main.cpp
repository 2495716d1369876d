// prt: command-line entry point. Parses arguments with CLI11 and runs one subcommand.
// Every user-facing failure is a prt::Error: printed as one line "prt: <message>", exit status 1.
// Under mpirun (docs/distributed.md) a rank that fails alone ends the whole job (dist::finish_after_error).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "dist/context.h"

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
  prt::cli::add_unwrap_command(app);
#ifdef PRT_WITH_GL
  prt::cli::add_render_command(app);
  prt::cli::add_view_command(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // CLI11 prints two lines and exits with its own codes (104-109); prt's rule is one line, status 1.
    std::fprintf(stderr, "prt: %s (see prt --help)\n", prt::Error(e.what()).what());
    return prt::dist::finish_after_error(1, false);
  } catch (const prt::OptionError& e) {
    // A library names the field of its options struct; the user typed the flag.
    const std::string file = e.file().empty() ? "" : e.file() + ": ";
    std::fprintf(stderr, "prt: %s%s%s\n", file.c_str(), prt::cli::flag_of_field(e.field()).c_str(), e.rest().c_str());
    return prt::dist::finish_after_error(1, false);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "prt: %s\n", e.what());
    return prt::dist::finish_after_error(1, dynamic_cast<const prt::dist::CollectiveError*>(&e) != nullptr);
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the operating system refuses (a component longer than NAME_MAX, ...): a user error.
    std::fprintf(stderr, "prt: %s: %s\n", e.path1().c_str(), e.code().message().c_str());
    return prt::dist::finish_after_error(1, false);
  } catch (const nlohmann::json::exception& e) {
    // A JSON value of the wrong type that a reader did not check itself: still one line, status 1.
    const std::string what = e.what();  // "[json.exception.type_error.302] type must be ..."
    std::fprintf(stderr, "prt: malformed JSON input: %s\n", what.substr(what.find(']') + 2).c_str());
    return prt::dist::finish_after_error(1, false);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "prt: out of memory\n");
    return prt::dist::finish_after_error(1, false);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt: internal error: %s\n", e.what());
    return prt::dist::finish_after_error(2, false);
  }
  return prt::dist::finish(0);
}
