#pragma once
// The light in a probe scene: a distant environment (sky) map, an optional sun, and emissive surfaces.
//
// SUN (`--sun DX,DY,DZ,INTENSITY,ANGULAR_RADIUS` or `--sun DX,DY,DZ,R,G,B,ANGULAR_RADIUS`): a distant
// disc of uniform radiance centred on the direction (DX,DY,DZ) (toward the sun, world frame, need not
// be unit), of angular radius ANGULAR_RADIUS in DEGREES (0 < a <= 45; the real sun is 0.265).
// INTENSITY is the IRRADIANCE the disc delivers to a surface facing it (normal incidence, unoccluded),
// in the environment's radiance units times steradians (W m^-2 when the environment is in
// W m^-2 sr^-1), per channel when R,G,B is given. The disc's radiance is therefore
//     L_sun = INTENSITY / (pi sin^2 a),
// since a uniform disc of half-angle a delivers integral cos = pi sin^2 a times its radiance at normal
// incidence. A directional light of "intensity E" in an engine (three.js, Unity, Filament with lux)
// corresponds to INTENSITY = E. The sun is NOT part of the environment image: do not pass a map that
// already contains it.
//
// EMISSION: per-vertex linear radiance leaving the front side of emissive surfaces (glTF emissiveFactor
// times KHR_materials_emissive_strength, OBJ/MTL Ke), in the environment's units.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "light/disc.h"
#include "sh/coefficients.h"

namespace prt::light {
struct Environment;
}

namespace prt::probes {

/// The sun is a light::Disc (light/disc.h; SUN above is its TEXT FORM): one type for every command.
using Sun = light::Disc;

/// light::parse_disc(text, "--sun").
Sun parse_sun(const std::string& text);

/// The sun as SH radiance coefficients: light::disc_coefficients.
sh::RgbCoefficients sun_coefficients(int bands, const Sun& sun);

/// Uniform direction in the sun's disc for u in [0,1)^2: light::disc_direction_sample.
glm::dvec3 sun_direction_sample(const Sun& sun, double u0, double u1);

/// A copy of `environment` for per-ray radiance lookups, small enough to stay in cache: an equirect
/// map is halved (2x2 box average) while wider than 512 texels, cube faces while larger than 128.
/// The bakers look up escaping (or blocked) rays in it, while the exact SH projections they add use the
/// full map; the difference only blurs detail finer than ~0.7 degrees in the Monte Carlo terms, far
/// below what 3..16 bands resolve.
light::Environment lookup_environment(const light::Environment& environment);

/// All the light of a scene. `environment` may be null for a black sky (sun and emission only).
struct SceneLight {
  const light::Environment* environment = nullptr;
  std::optional<Sun> sun;
  std::vector<glm::vec3> emission;  ///< empty or one per vertex
};

}  // namespace prt::probes
