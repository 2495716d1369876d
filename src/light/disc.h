#pragma once
// Distant discs: a sun (or a few compact lamps) held out of the SH lighting and shaded exactly.
//
// A DISC is a cap of uniform radiance about a unit direction d (toward the light, world frame, +Y up)
// with angular radius a (radians). It is specified by its IRRADIANCE AT NORMAL INCIDENCE E per channel:
// the irradiance it delivers, unoccluded, to a surface facing it, in the environment's radiance units
// times steradians (W m^-2 for an environment in W m^-2 sr^-1; what engines call a directional
// light's intensity). A uniform cap of half-angle a gives  integral_cap (d . w) dw = pi sin^2 a, so
//     L_disc = E / (pi sin^2 a)                               (its radiance),
// and a surface with normal n sees  integral_cap max(n . w, 0) dw = pi sin^2(a) (n . d)  exactly while
// the whole cap is above its horizon (n . d >= sin a): irradiance E (n . d).
//
// TEXT FORM (`--sun` on prt light, shade, render, view, probes; docs/conventions.md, "Sun and sky"):
//   DX,DY,DZ,R,G,B,RADIUS_DEG   (or DX,DY,DZ,E,RADIUS_DEG for a grey disc)
// direction need not be unit; R,G,B = E >= 0 per channel, not all zero; 0 < RADIUS_DEG <= 45.
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::light {

struct Disc {
  glm::dvec3 direction{0.0, 1.0, 0.0};  ///< unit, toward the light, world frame
  glm::dvec3 irradiance{0.0};           ///< E per channel: irradiance at normal incidence, >= 0
  double angular_radius = 0.0;          ///< radians, in (0, pi/4]

  /// L = E / (pi sin^2 a): the disc's uniform radiance.
  glm::dvec3 radiance() const;
  /// 2 pi (1 - cos a), steradians.
  double solid_angle() const;
};

/// Largest angular radius a disc may have: 45 degrees, in radians.
inline constexpr double kMaxDiscRadius = 0.78539816339744831;

/// Parses the TEXT FORM. Throws prt::OptionError(option, ": ...") for a wrong count, a non-finite value, a
/// zero direction, a negative or all-zero irradiance, or a radius outside (0, 45] degrees; `option` names
/// the field the text came from.
Disc parse_disc(const std::string& text, const std::string& option = "sun");

/// The TEXT FORM of `disc` (17 significant digits; parse_disc reads it back exactly up to rounding of
/// the normalised direction).
std::string format_disc(const Disc& disc);

/// The disc's exact SH radiance coefficients (the projection of the uniform cap, light::cone_light).
sh::RgbCoefficients disc_coefficients(int bands, const Disc& disc);

/// Sum of disc_coefficients over `discs` (zero coefficients for none).
sh::RgbCoefficients discs_coefficients(int bands, const std::vector<Disc>& discs);

/// A direction in the disc for u in [0,1)^2, uniform in solid angle (cos theta uniform in [cos a, 1],
/// phi = 2 pi u1 about d, in sh::orthonormal_basis(d), Duff et al. 2017).
glm::dvec3 disc_direction_sample(const Disc& disc, double u0, double u1);

/// The disc under the active rotation `rotation` (the direction is rotated; E and a are unchanged).
Disc rotated(const Disc& disc, const glm::dmat3& rotation);

}  // namespace prt::light
