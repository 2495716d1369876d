// prt probes-relight: applies a new (or rotated) environment to a probe file baked with --transfer,
// or, without --env, re-exports any probe file (plain or with transfer) into another format as it is.
#include <cstdio>

#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "cli/lighting_input.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "light/environment.h"
#include "probes/baker.h"
#include "probes/exporters.h"
#include "probes/probe_file.h"

namespace prt::cli {

namespace {

struct RelightCommandOptions {
  std::string input;
  std::string environment;
  std::string rotate;
  std::string output;
  std::string format = "prt";
  std::string scene;
  std::string probe = "sky";
  bool quiet = false;
};

void run_relight(const RelightCommandOptions& o) {
  const probes::Format format = probes::parse_format(o.format);
  if (format == probes::Format::gltf && o.scene.empty()) fail("--format gltf needs --scene (the scene to re-write)");
  if (o.environment.empty() && !o.rotate.empty()) fail("--rotate needs --env (the environment to rotate)");
  const glm::dvec3 ypr = o.rotate.empty() ? glm::dvec3(0.0) : parse_angles(o.rotate, "--rotate");
  check_outputs({o.output}, {o.input, o.environment, o.scene});
  probes::ProbeSet set = probes::read_probe_file(o.input);
  if (!o.environment.empty()) {
    if (set.transfer_bands == 0) fail_file(o.input, "has no transfer: bake it with prt probes --transfer");
    probes::relight(set, load_unsplit_sh_lighting(o.environment, set.transfer_bands, ypr));
  }
  probes::ExportOptions export_options;
  export_options.probe = o.probe;
  export_options.scene_path = o.scene;
  probes::export_probes(set, format, o.output, export_options);
  if (!o.quiet && o.environment.empty())
    std::fprintf(stderr, "prt probes-relight: %zu probes re-exported as baked -> %s (%s)\n", set.count(), o.output.c_str(),
                 probes::format_name(format));
  else if (!o.quiet)
    std::fprintf(stderr, "prt probes-relight: %zu probes relit with %s (%d bands) -> %s (%s)\n", set.count(),
                 o.environment.c_str(), set.transfer_bands, o.output.c_str(), probes::format_name(format));
}

}  // namespace

void add_probes_relight_command(CLI::App& app) {
  auto o = std::make_shared<RelightCommandOptions>();
  CLI::App* cmd = app.add_subcommand("probes-relight",
                                     "Relight a probe file baked with --transfer under a new or rotated environment, or "
                                     "(without --env) re-export any probe file into another format without re-baking");
  cmd->add_option("FILE", o->input, "Probe file (.prtprobes); with --env it must carry transfer (prt probes --transfer)")->required();
  cmd->add_option("--env", o->environment,
                  "New environment: image (see prt light) or SH lighting .json; omitted: the probes as baked");
  cmd->add_option("--rotate", o->rotate, "YAW,PITCH,ROLL degrees: rotate the environment, R = Ry Rx Rz (active)");
  cmd->add_option("-o,--output", o->output, "Output file")->required();
  cmd->add_option("--format", o->format, "prt | threejs | unity | godot | filament | gltf | bevy")->capture_default_str();
  cmd->add_option("--scene", o->scene, "gltf: the scene to re-write with the relit sky probe");
  cmd->add_option("--probe", o->probe, "filament: 'sky' or a probe index")->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "No summary");
  cmd->callback([o] { run_relight(*o); });
}

}  // namespace prt::cli
