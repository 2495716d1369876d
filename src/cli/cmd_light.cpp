// `prt light`: environment map -> SH lighting file (+ optional preview image). A thin layer: CLI11
// fills LightOptions, check_options() validates everything before any work, run_light() calls the
// light library and writes every output through AtomicFile (all or nothing).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/analytic_light_spec.h"
#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "image/image.h"
#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "light/scene_lighting.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/window.h"

namespace prt::cli {

namespace {

struct LightOptions {
  std::string environment;      ///< equirect or cross image, six faces "a,b,c,d,e,f", or "name_{face}.exr"
  int bands = 3;                ///< 1..kMaxBands
  std::string window = "auto";  ///< auto | none | hanning | lanczos | laplacian
  std::string sun = "auto";     ///< auto | none | a disc (light/disc.h)
  double window_param = 0.0;    ///< <= 0 (unset): the window's default
  std::string rotate;           ///< "YAW,PITCH,ROLL" in degrees; empty: no rotation
  int threads = 0;              ///< 0: all cores
  std::string output;           ///< SH lighting JSON
  std::string preview;          ///< optional equirect preview (.png tone-mapped, .exr/.hdr linear)
  int preview_width = 512;      ///< preview is preview_width x preview_width / 2
  double exposure = 0.0;        ///< preview exposure in stops (display formats only)
  bool window_param_given = false;
};

struct CheckedLight {
  light::WindowRequest window;
  light::SunRequest sun;
  double yaw = 0, pitch = 0, roll = 0;
};

CheckedLight check_options(const LightOptions& o) {
  CheckedLight checked;
  if (o.bands < 1 || o.bands > sh::kMaxBands)
    fail("--bands " + std::to_string(o.bands) + ": out of range 1.." + std::to_string(sh::kMaxBands));
  checked.window = light::parse_window_request(o.window, o.window_param);
  checked.sun = light::parse_sun_request(o.sun);
  if (o.window_param_given && !(o.window_param > 0.0 && std::isfinite(o.window_param))) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", o.window_param);
    fail(std::string("--window-param ") + text + ": must be a finite number > 0");
  }
  if (!o.rotate.empty()) {
    const glm::dvec3 angles = parse_angles(o.rotate, "--rotate");
    checked.yaw = angles.x;
    checked.pitch = angles.y;
    checked.roll = angles.z;
  }
  if (o.threads < 0) fail("--threads " + std::to_string(o.threads) + ": must be >= 0 (0 = all cores)");
  if (!o.preview.empty()) {
    const std::string ext = lower_extension(o.preview);
    if (!image::is_display_format(o.preview) && ext != ".exr" && ext != ".hdr")
      fail_file(o.preview, "unsupported preview format '" + ext + "' (use .png, .jpg, .exr or .hdr)");
    if (o.preview_width < 2 || o.preview_width % 2 != 0 || o.preview_width > 16384)
      fail("--preview-width " + std::to_string(o.preview_width) + ": must be even, 2..16384");
  }
  check_outputs({o.output, o.preview}, {o.environment});
  if (!std::isfinite(o.exposure)) fail("--exposure: must be finite");
  return checked;
}

std::string describe_environment(const light::Environment& env) {
  if (env.layout == light::Environment::Layout::equirect)
    return std::to_string(env.equirect.width) + "x" + std::to_string(env.equirect.height) + " equirect";
  return "cube " + std::to_string(env.faces[0].width) + "^2 x 6";
}

void run_light(const LightOptions& o) {
  const CheckedLight checked = check_options(o);
  // Claim the outputs first: a missing output folder fails here, before the (slow) work.
  AtomicFile json_file(o.output);
  std::unique_ptr<AtomicFile> preview_file;
  if (!o.preview.empty()) preview_file = std::make_unique<AtomicFile>(o.preview);

  // Analytic lights (cli/analytic_light_spec.h) are exact: rotated, never split or windowed.
  const bool analytic = is_analytic_light_spec(o.environment);
  const light::Environment env = analytic ? light::Environment{} : light::load_environment(o.environment);
  const glm::dvec3 ypr(checked.yaw, checked.pitch, checked.roll);
  const light::SceneLighting lighting =
      analytic ? analytic_scene_lighting(o.environment, o.bands, ypr)
               : light::split_environment(env, o.bands, ypr, checked.sun, checked.window, o.threads);
  const sh::RgbCoefficients& coefficients = lighting.sky;

  light::LightFileInfo info;
  info.source = o.environment;
  info.window = lighting.window.description;
  info.yaw = checked.yaw;
  info.pitch = checked.pitch;
  info.roll = checked.roll;
  info.discs = lighting.discs;
  json_file.stream() << light::format_light_file(coefficients, info);

  if (preview_file) {
    image::Image preview = light::render_equirect(coefficients, o.preview_width, o.preview_width / 2, o.threads);
    if (image::is_display_format(o.preview)) preview = image::to_display(preview, o.exposure, image::ToneMap::aces);
    image::write_file_at(preview_file->temp_path(), preview, o.preview);
  }
  json_file.commit();
  if (preview_file) preview_file->commit();
  std::printf("%s: %d bands from %s (%s)%s%s\n", o.output.c_str(), o.bands, o.environment.c_str(),
              analytic ? "analytic lights" : describe_environment(env).c_str(), preview_file ? ", preview " : "", o.preview.c_str());
  if (!lighting.discs.empty() || lighting.window.window != sh::Window::none)
    std::printf("%s: %s\n", o.output.c_str(), light::describe_lighting(lighting).c_str());
}

}  // namespace

void add_light_command(CLI::App& app) {
  auto options = std::make_shared<LightOptions>();
  CLI::App* cmd = app.add_subcommand("light", "Project an environment map to SH radiance coefficients (JSON)");
  cmd->add_option("environment", options->environment,
                  "Equirect (2:1) or cube-cross (4:3, 3:4) image, six faces 'px,nx,py,ny,pz,nz', or a "
                  "path with {face}; any float format OpenImageIO reads (.exr, .hdr, ...); or analytic lights "
                  "'directional:DX,DY,DZ:R,G,B', 'cone:DX,DY,DZ:DEGREES:R,G,B', "
                  "'hemisphere:UX,UY,UZ:R,G,B:R,G,B', 'constant:R,G,B', joined with '+'")
      ->required();
  cmd->add_option("-o,--output", options->output, "SH lighting JSON to write")->required();
  cmd->add_option("--bands", options->bands, "SH bands (l < bands), 1.." + std::to_string(sh::kMaxBands))
      ->capture_default_str();
  cmd->add_option("--window", options->window,
                  "Ringing window: auto (the least Laplacian window keeping radiance and irradiance >= 0), none, "
                  "hanning, lanczos, laplacian")
      ->capture_default_str();
  cmd->add_option("--sun", options->sun,
                  "auto (hold the sun and compact lamps out of the SH as discs), none, or a disc "
                  "DX,DY,DZ,R,G,B,RADIUS_DEG added to the file (R,G,B = irradiance at normal incidence)")
      ->capture_default_str();
  cmd->add_option_function<double>(
      "--window-param",
      [options](double v) {
        options->window_param = v;
        options->window_param_given = true;
      },
      "Window parameter (hanning/lanczos: W; laplacian: lambda); default depends on the window");
  cmd->add_option("--rotate", options->rotate,
                  "YAW,PITCH,ROLL in degrees: rotates the environment by R = Ry(yaw) Rx(pitch) Rz(roll)");
  cmd->add_option("--threads", options->threads, "Worker threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--preview", options->preview,
                  "Also write the SH reconstruction as an equirect image: .png (ACES tone map, sRGB) or .exr "
                  "(linear)");
  cmd->add_option("--preview-width", options->preview_width, "Preview width in pixels (height = width / 2)")
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposure, "Preview exposure in stops, for .png/.jpg previews")
      ->capture_default_str();
  cmd->callback([options] { run_light(*options); });
}

}  // namespace prt::cli
