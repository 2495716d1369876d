#pragma once
// What each engine stores per probe, computed from prt's coefficients. Pure maths, no I/O.
//
// Notation (see docs/conventions.md and probes/<format>/README.md):
//   c_i  prt's incident-radiance coefficients (sh/basis.h: WITH the Condon-Shortley phase);
//   L_i  = cs_i c_i, the same function in the basis WITHOUT the Condon-Shortley phase (three.js,
//        Godot, Unity, Filament's polynomial form): cs = (+,-,+,-,+,-,+,-,+) for l <= 2, i.e. every
//        coefficient with odd |m| changes sign;
//   A_l  the clamped cosine's Funk-Hecke factors (pi, 2pi/3, pi/4);
//   PF_i = A_l / pi * |K_i|, |K_i| the constant of the polynomial form of Y_i
//        (0.2820948, 0.4886025 x3, 1.0925484 x2, 0.3153916, 1.0925484, 0.5462742), so that
//        E(n)/pi = sum_i PF_i L_i P_i(n) with P = (1, y, z, x, xy, yz, 3z^2-1, xz, x^2-y^2).
// Every engine here uses 3 bands (9 coefficients): a probe with more bands is truncated (bands >= 4
// carry no irradiance at l = 3 since A_3 = 0, but l = 4 adds A_4 = -pi/24 of band 4: truncation drops
// it, which is what the engines' formulas do too); a probe with fewer bands is zero-padded.
#include <array>

#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::probes {

using Sh9 = std::array<glm::dvec3, 9>;

/// cs_i for i < 9: +1 for even |m|, -1 for odd |m|.
inline constexpr std::array<double, 9> kCondonShortleySign{{1, -1, 1, -1, 1, -1, 1, -1, 1}};
/// PF_i (see above), from A_l / pi and the basis constants in double.
extern const std::array<double, 9> kIrradiancePolynomialFactor;
/// A_l of each of the 9 coefficients: pi, 2pi/3 x3, pi/4 x5.
extern const std::array<double, 9> kClampedCosineFactor;

/// The first 9 coefficients of `c` (zero-padded if c.bands < 3).
Sh9 first_nine(const sh::RgbCoefficients& c);

/// three.js SphericalHarmonics3 / LightProbe "sh": L_i (radiance, no CS phase), right-handed +Y up.
Sh9 threejs_coefficients(const sh::RgbCoefficients& c);

/// Godot 4 LightmapGIData probe_data "sh": L_i / pi, right-handed +Y up (LightmapGI node frame).
Sh9 godot_coefficients(const sh::RgbCoefficients& c);

/// Unity SphericalHarmonicsL2 (as LightProbes.bakedProbes holds it): u_i = PF_i * L'_i, where L' is the
/// lighting mirrored into Unity's left-handed frame by x -> -x (as UnityGLTF and glTFast import glTF):
/// L'_i = s_i L_i with s = (+,+,+,-,-,+,+,-,+) (x, xy and xz terms change sign). Unity's shader packs
/// SHAr..SHC from u and ShadeSH9(n') returns E(n)/pi for the mirrored normal n' = (-n.x, n.y, n.z).
Sh9 unity_coefficients(const sh::RgbCoefficients& c);
/// A position or direction in Unity's frame: (-x, y, z).
glm::dvec3 to_unity_frame(const glm::dvec3& p);

/// Filament IndirectLight::irradiance(3, sh) and cmgen's sh.txt ("irradiance, pre-scaled base"):
/// PF_i * L_i, right-handed +Y up; Filament's shader evaluates sum_i sh_i P_i(n) = E(n)/pi.
Sh9 filament_coefficients(const sh::RgbCoefficients& c);

/// glTF EXT_lights_image_based "irradianceCoefficients" as Babylon.js's loader reads them:
/// A_l * s_i * c_i (irradiance coefficients in the CS-phase basis, mirrored in x by s as in
/// unity_coefficients). Babylon's glTF loader turns the scene into its left-handed frame by x -> -x
/// but applies the light as stored, so the light is stored in that mirrored frame: Babylon's default
/// scene then shows E(n)/pi at every glTF normal n (a right-handed Babylon scene, which flips z instead,
/// shows E(Ry(180) n)/pi; see probes/gltf/README.md).
Sh9 gltf_irradiance_coefficients(const sh::RgbCoefficients& c);

/// Bevy's ambient cube (Valve's basis): E(d)/pi at the six axis normals d, ordered
/// +X, -X, +Y, -Y, +Z, -Z, computed from the 3-band truncation as
///   C(+-X) = p0 +- p3 - p6 + p8,  C(+-Y) = p0 +- p1 - p6 - p8,  C(+-Z) = p0 +- p2 + 2 p6
/// with p_i = PF_i L_i. Bevy shades sum_a n_a^2 C(sign(n_a) a): exact at the six axes; elsewhere it
/// drops the xy, yz, xz terms and replaces x by x|x| (an approximation inherent to the ambient cube).
std::array<glm::dvec3, 6> bevy_ambient_cube(const sh::RgbCoefficients& c);

/// E(n)/pi from the 3-band truncation of c (prt's own evaluation: sh::irradiance / pi), for tests and
/// for exporters that need a value at a normal.
glm::dvec3 irradiance_over_pi(const sh::RgbCoefficients& c, const glm::dvec3& normal);

}  // namespace prt::probes
