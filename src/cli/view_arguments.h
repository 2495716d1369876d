#pragma once
// The scene-view options that prt render and prt view share (camera, size, rotations, exposure,
// background, band truncation), kept as typed and checked in one place.
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/arguments.h"
#include "core/error.h"
#include "light/scene_lighting.h"
#include "render/renderer.h"

namespace prt::cli {

struct ViewArguments {
  std::string rotate, object_rotate, camera = "auto", size, background;
  double exposure = 0.0;
  int bands = 0;
  std::string sun = "auto", window = "auto";
  double window_param = 0.0;
};

/// Adds --sun, --window and --window-param (the lighting split of light::load_scene_lighting) to `cmd`.
inline void add_sun_window_options(CLI::App* cmd, ViewArguments& a) {
  cmd->add_option("--sun", a.sun,
                  "auto (find the environment's sun and shade it exactly, with shadow maps), none, or a disc "
                  "DX,DY,DZ,R,G,B,RADIUS_DEG (R,G,B: irradiance at normal incidence)")
      ->capture_default_str();
  cmd->add_option("--window", a.window, "SH window of the sky: auto (least non-negative), none, hanning, lanczos, laplacian")
      ->capture_default_str();
  cmd->add_option("--window-param", a.window_param, "The window's parameter (<= 0: its default)");
}

/// Parses and checks `a` into the same-named fields of render::RenderOptions or render::ViewerOptions.
/// Throws prt::Error with the option's name for a malformed or out-of-range value.
template <class Options>
void apply_view_arguments(const ViewArguments& a, Options& options) {
  if (!a.rotate.empty()) options.rotate = parse_angles(a.rotate, "--rotate");
  if (!a.object_rotate.empty()) options.object_rotate = parse_angles(a.object_rotate, "--object-rotate");
  options.camera = render::parse_camera(a.camera);
  render::parse_size(a.size, options.width, options.height);
  if (!std::isfinite(a.exposure)) fail("--exposure: must be a finite number of stops");
  options.exposure = a.exposure;
  if (!a.background.empty()) options.background = render::parse_background(a.background);
  if (a.bands < 0) fail("--bands: must be at least 1 (0 = all of the transfer's bands)");
  options.bands = a.bands;
  options.sun = light::parse_sun_request(a.sun);
  options.window = light::parse_window_request(a.window, a.window_param);
}

}  // namespace prt::cli
