#pragma once
// SH lighting files (JSON), written by `prt light` and read by `prt shade --light`, the renderer, ...
//
// {"bands": N, "basis": "real-orthonormal-condon-shortley", "index": "l*(l+1)+m",
//  "frame": "right-handed, +Y up", "quantity": "radiance", "source": "...", "window": "...",
//  "rotation_ypr_degrees": [y, p, r], "coefficients": [[r, g, b], ... N*N entries]}
#include <string>

#include "sh/coefficients.h"

namespace prt::light {

/// Extra, descriptive fields written beside the coefficients.
struct LightFileInfo {
  std::string source;                 ///< input file or analytic description
  std::string window = "none";        ///< window applied, with its parameter
  double yaw = 0, pitch = 0, roll = 0;  ///< rotation applied, degrees
};

/// Writes the JSON file atomically. Throws prt::Error naming the file on failure.
void write_light_file(const std::string& path, const sh::RgbCoefficients& coefficients, const LightFileInfo& info);

/// Reads a file written by write_light_file (or by hand with the same keys); checks basis, index,
/// frame, bands (1..kMaxBands) and the coefficient count; throws prt::Error("<path>: <problem>").
sh::RgbCoefficients read_light_file(const std::string& path);

}  // namespace prt::light
