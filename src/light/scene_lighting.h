#pragma once
// Distant lighting as every shading command takes it: an environment map (or an SH lighting file), split
// into DISCS shaded exactly (light/disc.h: a sun, a few lamps) and the rest of the sky as SH radiance,
// windowed against ringing. docs/conventions.md, "Sun and sky".
//
// ORDER (so that `--sun none --window none` is exactly the unsplit, unwindowed lighting of earlier
// versions): discs are found in the unrotated map (sun auto) and removed; the residual is projected to
// SH; the SH and the discs are rotated by the active rotation; the window is applied last.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "light/deringing.h"
#include "light/disc.h"
#include "sh/coefficients.h"

namespace prt::light {

/// `--sun`: auto (find the dominant lights of an environment map; an SH lighting file keeps the discs it
/// carries), none (no disc: a lighting file's discs are folded into its SH), or one given disc (added to
/// the lighting; the map is then taken to hold no sun of its own and is not searched).
struct SunRequest {
  enum class Mode { automatic, none, given };
  Mode mode = Mode::automatic;
  Disc disc;  ///< when mode == given
};

/// Parses "auto", "none" or a disc's TEXT FORM (light/disc.h). Throws prt::Error("--sun: ...").
SunRequest parse_sun_request(const std::string& text);

/// Lighting split into exact discs and windowed SH, in the environment's frame after the rotation.
struct SceneLighting {
  sh::RgbCoefficients sky;   ///< SH radiance of everything but the discs
  std::vector<Disc> discs;   ///< brightest first
  WindowChoice window;       ///< applied to `sky`
  double sky_level = 0.0;    ///< the map's median luminance (sun auto on a map; 0 otherwise)
  /// Shading clamps negative channels at 0 (the residue of Monte Carlo noise and of the band limit):
  /// true unless the request was `--sun none --window none`, which keeps the unsplit result exactly.
  bool clamp_negative = true;

  /// sky + the discs' SH: the whole lighting as SH (for consumers that cannot shade discs).
  sh::RgbCoefficients total() const;
};

/// Loads `spec` (a .json SH lighting file, truncated or zero-padded to `bands`, or anything
/// load_environment accepts, projected to `bands`) as ORDER says, rotated by the active rotation
/// Ry(yaw) Rx(pitch) Rz(roll) (`yaw_pitch_roll`, degrees). Throws prt::Error("<file>: <problem>").
SceneLighting load_scene_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll,
                                  const SunRequest& sun, const WindowRequest& window, int threads = 0);

struct Environment;

/// As load_scene_lighting, for an environment already loaded. When `sky_map` is not null and discs were
/// found in the map and removed (sun auto), it receives the map the sky SH was projected from: the map
/// without them (extract_discs's residual, equirect, unrotated); otherwise it is left as it was (the map
/// itself is the sky).
SceneLighting split_environment(const Environment& environment, int bands, const glm::dvec3& yaw_pitch_roll,
                                const SunRequest& sun, const WindowRequest& window, int threads = 0,
                                Environment* sky_map = nullptr);

/// One line for a command's summary: "sun: <n> disc(s) (dir (x,y,z), radius a deg, E (r,g,b)); window W".
std::string describe_lighting(const SceneLighting& lighting);

}  // namespace prt::light
