// prt render: one relit frame rendered headless (OpenGL through EGL) and written as PNG or EXR.
#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/view_arguments.h"
#include "mesh/mesh.h"
#include "cli/commands.h"
#include "core/error.h"
#include "image/image.h"
#include "render/headless_render.h"

namespace prt::cli {

namespace {

struct RenderCommandOptions {
  std::string mesh_path, transfer_path, env, tone_map = "aces", output, brdf;
  int scene = mesh::kDefaultScene;
  ViewArguments view = {"", "", "auto", "1024x1024", "", 0.0, 0};
  bool quiet = false;
};

void run_render(const RenderCommandOptions& o) {
  check_outputs({o.output}, {o.mesh_path, o.transfer_path, o.env, o.brdf});
  render::RenderOptions options;
  options.mesh_path = o.mesh_path;
  options.scene = o.scene;
  options.transfer_path = o.transfer_path;
  options.environment = o.env;
  options.output = o.output;
  apply_view_arguments(o.view, options);
  options.tone_map = parse_tone_map(o.tone_map);
  options.quiet = o.quiet;
  options.brdf = o.brdf;
  render::render_to_file(options);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render the relit mesh headless (OpenGL 4.5 through EGL; no display needed) to PNG or EXR");
  cmd->add_option("MESH", options->mesh_path, "The mesh the transfer was baked for")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("TRANSFER", options->transfer_path, "Transfer file (.prt, or .cprt compressed): diffuse, or glossy (view-dependent); a lightmap .prt (prt bake --lightmap) is sampled per pixel")->required();
  cmd->add_option("--env", options->env,
                  "Environment image (equirect 2:1, cross, or six faces; projected to the transfer's bands) or SH "
                  "lighting .json")
      ->required();
  cmd->add_option("--rotate", options->view.rotate, "YAW,PITCH,ROLL degrees: rotate the environment by Ry Rx Rz");
  cmd->add_option("--object-rotate", options->view.object_rotate,
                  "YAW,PITCH,ROLL degrees: rotate the object about its bounds centre");
  cmd->add_option("--camera", options->view.camera,
                  "AZ,EL,DIST or auto: orbit about the bounds centre (degrees, degrees, mesh units; DIST may be auto). "
                  "AZ=0,EL=0 looks from +Z toward -Z")
      ->capture_default_str();
  cmd->add_option("--size", options->view.size, "WxH pixels")->capture_default_str();
  cmd->add_option("--exposure", options->view.exposure, "Exposure in stops (PNG only)")->capture_default_str();
  cmd->add_option("--tone-map", options->tone_map, "aces (Narkowicz 2015) or clamp (PNG only)")->capture_default_str();
  cmd->add_option("--background", options->view.background,
                  "env (the image), sh (its SH reconstruction) or black, the first two with the shaded discs drawn in place of the map's own; default env, sh for a .json");
  cmd->add_option("--bands", options->view.bands, "Use only the first K bands of the transfer (0 = all)");
  cmd->add_option("--brdf", options->brdf,
                  "Glossy transfer: the BRDF SPEC to shade with (default: the one recorded in the transfer at bake time)");
  add_sun_window_options(cmd, options->view);
  cmd->add_flag("-q,--quiet", options->quiet, "No summary line on stderr");
  cmd->add_option("-o,--output", options->output, "Output .png (tone mapped, sRGB) or .exr (linear radiance)")
      ->required();
  cmd->callback([options] { run_render(*options); });
}

}  // namespace prt::cli
