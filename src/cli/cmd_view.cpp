// prt view: the interactive relighting viewer (GLFW window, Dear ImGui panel).
#include "cli/arguments.h"
#include "cli/view_arguments.h"
#include "mesh/mesh.h"
#include "cli/commands.h"
#include "core/error.h"
#include "render/viewer.h"

namespace prt::cli {

namespace {

struct ViewCommandOptions {
  std::string mesh_path, screenshot, brdf;
  int scene = mesh::kDefaultScene;
  std::vector<std::string> transfer_paths, environments;
  ViewArguments view = {"", "", "auto", "1280x800", "", 0.0, 0};
  int frames = 0;
};

void run_view(const ViewCommandOptions& o) {
  render::ViewerOptions options;
  options.mesh_path = o.mesh_path;
  options.scene = o.scene;
  options.transfer_paths = o.transfer_paths;
  options.brdf = o.brdf;
  options.environments = o.environments;
  apply_view_arguments(o.view, options);
  if (o.frames < 0) fail("--frames: must be positive");
  options.frames = o.frames;
  options.screenshot = o.screenshot;
  render::run_viewer(options);
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<ViewCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Interactive relighting viewer: drag orbits, Shift+drag rotates the lighting, scroll zooms, H for help");
  cmd->add_option("MESH", options->mesh_path, "The mesh the transfers were baked for")->required();
  add_scene_option(cmd, options->scene);
  cmd->add_option("TRANSFER", options->transfer_paths, "One or more transfer files (.prt, or .cprt compressed; diffuse or glossy; lightmaps sampled per pixel; either file of a mixed pair "
                 "draws the pair); keys 1-9 switch")
      ->required();
  cmd->add_option("--env", options->environments,
                  "Environment image or SH lighting .json; repeat for several (E switches), or drop files on the window")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--rotate", options->view.rotate, "Initial YAW,PITCH,ROLL degrees of the environment");
  cmd->add_option("--object-rotate", options->view.object_rotate, "Initial YAW,PITCH,ROLL degrees of the object");
  cmd->add_option("--camera", options->view.camera, "Initial AZ,EL,DIST or auto (as prt render)")->capture_default_str();
  cmd->add_option("--size", options->view.size, "Window size WxH")->capture_default_str();
  cmd->add_option("--exposure", options->view.exposure, "Initial exposure in stops")->capture_default_str();
  cmd->add_option("--background", options->view.background, "Initial background: env, sh or black");
  cmd->add_option("--bands", options->view.bands, "Initial band truncation (0 = all)");
  cmd->add_option("--brdf", options->brdf,
                  "Glossy transfers: the BRDF SPEC to shade with (default: each one's BRDF recorded at bake time); "
                  "the panel edits it live, G toggles its diffuse lobes only");
  add_sun_window_options(cmd, options->view);
  cmd->add_option("--frames", options->frames, "Render N frames and exit (scripted runs)");
  cmd->add_option("--screenshot", options->screenshot,
                  "With --frames: save the last frame here (.png tone mapped, .exr linear)");
  cmd->callback([options] { run_view(*options); });
}

}  // namespace prt::cli
