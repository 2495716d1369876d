#pragma once
// SH lighting files (JSON), written by `prt light` and read by `prt shade --light`, the renderer, ...
//
// FORMAT (UTF-8 JSON object; keys in this order when written, any order when read):
//   "bands": N                          integer 1..32 (sh::kMaxBands); N^2 coefficients follow
//   "basis": "real-orthonormal-condon-shortley"   required, exactly this string (sh/basis.h)
//   "index": "l*(l+1)+m"                required, exactly this string
//   "frame": "right-handed, +Y up"      required, exactly this string: world directions, the basis
//                                       evaluated on them as in sh/basis.h (polar axis +Z)
//   "quantity": "radiance"              optional when read; if present it must be "radiance"
//   "source": "..."                     optional, descriptive: input file or analytic description
//   "window": "none" | "hanning(W)" | "lanczos(W)" | "laplacian(lambda)"   optional, descriptive:
//                                       window already applied to the coefficients, with its parameter
//   "rotation_ypr_degrees": [y, p, r]   optional, descriptive: rotation already applied
//                                       (R = Ry(y) Rx(p) Rz(r), active)
//   "discs": [{"direction": [x, y, z], "irradiance": [r, g, b], "angular_radius_degrees": a,
//              "radiance": [r, g, b]}, ...]   optional: lights held out of the coefficients and shaded
//                                       exactly (light/disc.h); "radiance" is descriptive (E / (pi sin^2 a))
//   "coefficients": [[r, g, b], ...]    required, exactly N^2 triples of finite numbers, coefficient-major
//                                       in flat index order; linear radiance in the source image's units
//                                       (c_0 = 2 sqrt(pi) L for constant radiance L)
// Numbers are written with 17 significant digits or the shortest form that reads back identically.
#include <string>
#include <vector>

#include "light/disc.h"
#include "sh/coefficients.h"

namespace prt::light {

/// Extra, descriptive fields written beside the coefficients.
struct LightFileInfo {
  std::string source;                 ///< input file or analytic description
  std::string window = "none";        ///< window applied, with its parameter, e.g. "hanning(4)"
  double yaw = 0, pitch = 0, roll = 0;  ///< rotation applied, degrees
  std::vector<Disc> discs;            ///< held out of the coefficients (light/disc.h); written only if any
};

/// A lighting file's content: the SH part and the discs shaded exactly beside it.
struct LightFile {
  sh::RgbCoefficients coefficients;  ///< the SH radiance (with discs: the residual sky only)
  std::vector<Disc> discs;           ///< empty when the file has no "discs"
  std::string window = "none";       ///< the descriptive "window" entry
};

/// The file's text (see FORMAT). Throws prt::Error if the set is inconsistent (bands outside
/// 1..kMaxBands, values.size() != bands^2) or a coefficient is not finite.
std::string format_light_file(const sh::RgbCoefficients& coefficients, const LightFileInfo& info);

/// Writes the JSON file atomically. Throws prt::Error naming the file on failure.
void write_light_file(const std::string& path, const sh::RgbCoefficients& coefficients, const LightFileInfo& info);

/// Reads a file written by write_light_file (or by hand with the same keys); checks basis, index,
/// frame, quantity (if present), bands (1..kMaxBands) and the coefficient count and values; throws
/// prt::Error("<path>: <problem>") with a one-line problem.
sh::RgbCoefficients read_light_file(const std::string& path);

/// As read_light_file, with the optional "discs" (each checked: finite non-zero direction, irradiance
/// >= 0 and not all zero, radius in (0, 45] degrees) and the window entry.
LightFile read_lighting_file(const std::string& path);

}  // namespace prt::light
