#include "light/disc.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "core/error.h"
#include "light/limits.h"
#include "light/analytic.h"
#include "sh/sampling.h"

namespace prt::light {

namespace {

std::vector<double> parse_numbers(const std::string& text, const std::string& option, const std::string& usage) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    // Beyond 1e18 a disc's radiance and its SH overflow float coefficients (a value of 1e308 did).
    if (item.empty() || end == item.c_str() || *end != '\0' || !(std::abs(x) <= kMaxLightValue))
      fail_option(option, ": " + usage + " (numbers of magnitude at most 1e18)");
    v.push_back(x);
  }
  if ((v.size() != 5 && v.size() != 7) || text.empty() || text.back() == ',') fail_option(option, ": " + usage);
  return v;
}
}  // namespace

glm::dvec3 Disc::radiance() const {
  const double s = std::sin(angular_radius);
  return irradiance / (kPi * s * s);
}

double Disc::solid_angle() const { return 2.0 * kPi * (1.0 - std::cos(angular_radius)); }

Disc parse_disc(const std::string& text, const std::string& option) {
  const std::string usage = "expected auto, none, DX,DY,DZ,R,G,B,RADIUS_DEG or DX,DY,DZ,E,RADIUS_DEG, got '" + text + "'";
  const std::vector<double> v = parse_numbers(text, option, usage);
  Disc disc;
  const glm::dvec3 d(v[0], v[1], v[2]);
  const double length = glm::length(d);
  if (!(length > 0.0) || !std::isfinite(length)) fail_option(option, ": the direction must be finite and not zero");
  disc.direction = d / length;
  disc.irradiance = v.size() == 5 ? glm::dvec3(v[3]) : glm::dvec3(v[3], v[4], v[5]);
  for (int c = 0; c < 3; ++c)
    if (disc.irradiance[c] < 0.0) fail_option(option, ": the irradiance R,G,B must be >= 0");
  if (!(disc.irradiance.x + disc.irradiance.y + disc.irradiance.z > 0.0))
    fail_option(option, ": the irradiance must not be zero (give no disc instead)");
  const double degrees = v.back();
  if (!(degrees > 0.0 && degrees <= 45.0)) fail_option(option, ": the angular radius must lie in (0, 45] degrees");
  disc.angular_radius = degrees * kPi / 180.0;
  return disc;
}

std::string format_disc(const Disc& d) {
  char text[256];
  std::snprintf(text, sizeof text, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", d.direction.x, d.direction.y,
                d.direction.z, d.irradiance.x, d.irradiance.y, d.irradiance.z, d.angular_radius * 180.0 / kPi);
  return text;
}

sh::RgbCoefficients disc_coefficients(int bands, const Disc& disc) {
  return cone_light(bands, disc.direction, disc.angular_radius, disc.radiance());
}

sh::RgbCoefficients discs_coefficients(int bands, const std::vector<Disc>& discs) {
  sh::RgbCoefficients sum(bands);
  for (const Disc& disc : discs) {
    const sh::RgbCoefficients c = disc_coefficients(bands, disc);
    for (std::size_t i = 0; i < sum.values.size(); ++i) sum.values[i] += c.values[i];
  }
  return sum;
}

glm::dvec3 disc_direction_sample(const Disc& disc, double u0, double u1) {
  const glm::dvec3& n = disc.direction;
  glm::dvec3 t, bt;
  sh::orthonormal_basis(n, t, bt);
  const double cos_theta = 1.0 - u0 * (1.0 - std::cos(disc.angular_radius));
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double phi = 2.0 * kPi * u1;
  return glm::normalize(t * (sin_theta * std::cos(phi)) + bt * (sin_theta * std::sin(phi)) + n * cos_theta);
}

Disc rotated(const Disc& disc, const glm::dmat3& rotation) {
  Disc out = disc;
  out.direction = glm::normalize(rotation * disc.direction);
  return out;
}

}  // namespace prt::light
