#pragma once
// Lighting given on the command line: an environment image (projected) or an SH lighting JSON file.
#include <string>

#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::cli {

/// Loads lighting from `spec`: a .json file written by `prt light` (truncated or zero-padded to `bands`),
/// or anything prt::light::load_environment accepts (projected to `bands`). Then rotates it by the
/// active rotation Ry(yaw) Rx(pitch) Rz(roll) given in degrees in `yaw_pitch_roll`.
sh::RgbCoefficients load_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll, int threads = 0);

}  // namespace prt::cli
