#pragma once
// Lighting given on the command line: an environment image or an SH lighting JSON file, split into
// exact discs (--sun) and windowed SH (--window); see light/scene_lighting.h.
#include <string>

#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>

#include "light/scene_lighting.h"
#include "sh/coefficients.h"

namespace prt::cli {

/// The --sun / --window / --window-param values of a command, unparsed.
struct LightingArguments {
  std::string sun = "auto";
  std::string window = "auto";
  double window_param = 0.0;
};

/// Adds --sun, --window and --window-param (documented once here for every command) to `cmd`.
void add_lighting_options(CLI::App* cmd, LightingArguments& arguments);

/// Parses the arguments (throws prt::Error naming the option) into requests.
light::SunRequest sun_request(const LightingArguments& arguments);
light::WindowRequest window_request(const LightingArguments& arguments);

/// light::load_scene_lighting with the parsed arguments; `glossy` selects the glossy criterion of the
/// auto window (light/deringing.h).
light::SceneLighting load_scene_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll,
                                         const LightingArguments& arguments, int threads = 0, bool glossy = false);

/// The whole lighting as SH, unsplit and unwindowed (--sun none --window none): a .json file written by
/// `prt light` (truncated or zero-padded to `bands`, its discs folded in), or anything
/// prt::light::load_environment accepts (projected to `bands`), rotated by Ry(yaw) Rx(pitch) Rz(roll)
/// (degrees, `yaw_pitch_roll`).
sh::RgbCoefficients load_unsplit_sh_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll, int threads = 0);

}  // namespace prt::cli
