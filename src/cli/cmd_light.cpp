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

#include "cli/arguments.h"
#include "cli/output_paths.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "image/image.h"
#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/window.h"

namespace prt::cli {

namespace {

struct LightOptions {
  std::string environment;      ///< equirect or cross image, six faces "a,b,c,d,e,f", or "name_{face}.exr"
  int bands = 3;                ///< 1..kMaxBands
  std::string window = "none";  ///< none | hanning | lanczos | laplacian
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
  sh::Window window = sh::Window::none;
  double yaw = 0, pitch = 0, roll = 0;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

CheckedLight check_options(const LightOptions& o) {
  CheckedLight checked;
  if (o.bands < 1 || o.bands > sh::kMaxBands)
    fail("--bands " + std::to_string(o.bands) + ": out of range 1.." + std::to_string(sh::kMaxBands));
  checked.window = sh::parse_window(o.window);
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

std::string describe_window(sh::Window window, int bands, double param) {
  if (window == sh::Window::none) return "none";
  const double used = param > 0.0 ? param : sh::default_window_param(window, bands);
  char text[64];
  std::snprintf(text, sizeof text, "(%.17g)", used);
  return std::string(sh::window_name(window)) + text;
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

  const light::Environment env = light::load_environment(o.environment);
  sh::RgbCoefficients coefficients = light::project(env, o.bands, o.threads);
  const bool rotated = checked.yaw != 0.0 || checked.pitch != 0.0 || checked.roll != 0.0;
  if (rotated) {
    const glm::dmat3 r = sh::rotation_from_yaw_pitch_roll(checked.yaw, checked.pitch, checked.roll);
    coefficients = sh::Rotation(o.bands, r).apply(coefficients);
  }
  sh::apply_window(sh::window_weights(checked.window, o.bands, o.window_param), coefficients);

  light::LightFileInfo info;
  info.source = o.environment;
  info.window = describe_window(checked.window, o.bands, o.window_param);
  info.yaw = checked.yaw;
  info.pitch = checked.pitch;
  info.roll = checked.roll;
  json_file.stream() << light::format_light_file(coefficients, info);

  if (preview_file) {
    image::Image preview = light::render_equirect(coefficients, o.preview_width, o.preview_width / 2, o.threads);
    if (image::is_display_format(o.preview)) preview = image::to_display(preview, o.exposure, image::ToneMap::aces);
    image::write_file_at(preview_file->temp_path(), preview, o.preview);
  }
  json_file.commit();
  if (preview_file) preview_file->commit();
  std::printf("%s: %d bands from %s (%s)%s%s\n", o.output.c_str(), o.bands, o.environment.c_str(),
              describe_environment(env).c_str(), preview_file ? ", preview " : "", o.preview.c_str());
}

}  // namespace

void add_light_command(CLI::App& app) {
  auto options = std::make_shared<LightOptions>();
  CLI::App* cmd = app.add_subcommand("light", "Project an environment map to SH radiance coefficients (JSON)");
  cmd->add_option("environment", options->environment,
                  "Equirect (2:1) or cube-cross (4:3, 3:4) image, six faces 'px,nx,py,ny,pz,nz', or a "
                  "path with {face}; any float format OpenImageIO reads (.exr, .hdr, ...)")
      ->required();
  cmd->add_option("-o,--output", options->output, "SH lighting JSON to write")->required();
  cmd->add_option("--bands", options->bands, "SH bands (l < bands), 1.." + std::to_string(sh::kMaxBands))
      ->capture_default_str();
  cmd->add_option("--window", options->window, "Ringing window: none, hanning, lanczos, laplacian")
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
