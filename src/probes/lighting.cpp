#include "probes/lighting.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "light/analytic.h"
#include "light/environment.h"

namespace prt::probes {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

glm::dvec3 Sun::radiance() const {
  const double s = std::sin(angular_radius);
  return irradiance / (kPi * s * s);
}

double Sun::solid_angle() const { return 2.0 * kPi * (1.0 - std::cos(angular_radius)); }

Sun parse_sun(const std::string& text) {
  const std::string usage = "expected DX,DY,DZ,INTENSITY,ANGULAR_RADIUS_DEGREES or DX,DY,DZ,R,G,B,ANGULAR_RADIUS_DEGREES, got '" + text + "'";
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    // Beyond 1e18 the sun's radiance and its SH overflow float probe coefficients (a value of 1e308 did).
    if (item.empty() || end == item.c_str() || *end != '\0' || !(std::abs(x) <= 1e18))
      fail("--sun: " + usage + " (numbers of magnitude at most 1e18)");
    v.push_back(x);
  }
  if ((v.size() != 5 && v.size() != 7) || (!text.empty() && text.back() == ',')) fail("--sun: " + usage);
  Sun sun;
  const glm::dvec3 d(v[0], v[1], v[2]);
  if (!(glm::length(d) > 0.0)) fail("--sun: the direction must not be zero");
  sun.direction = glm::normalize(d);
  sun.irradiance = v.size() == 5 ? glm::dvec3(v[3]) : glm::dvec3(v[3], v[4], v[5]);
  if (sun.irradiance.x < 0.0 || sun.irradiance.y < 0.0 || sun.irradiance.z < 0.0) fail("--sun: the intensity must be >= 0");
  const double degrees = v.back();
  if (!(degrees > 0.0 && degrees <= 45.0)) fail("--sun: the angular radius must lie in (0, 45] degrees");
  sun.angular_radius = degrees * kPi / 180.0;
  return sun;
}

sh::RgbCoefficients sun_coefficients(int bands, const Sun& sun) {
  return light::cone_light(bands, sun.direction, sun.angular_radius, sun.radiance());
}

glm::dvec3 sun_direction_sample(const Sun& sun, double u0, double u1) {
  const glm::dvec3& n = sun.direction;
  // Duff et al. 2017 orthonormal basis.
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  const double cos_theta = 1.0 - u0 * (1.0 - std::cos(sun.angular_radius));
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double phi = 2.0 * kPi * u1;
  return glm::normalize(t * (sin_theta * std::cos(phi)) + bt * (sin_theta * std::sin(phi)) + n * cos_theta);
}

namespace {

image::Image halve(const image::Image& in) {
  image::Image out(in.width / 2, in.height / 2, in.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < in.channels; ++c)
        out.at(x, y, c) = 0.25f * (in.at(2 * x, 2 * y, c) + in.at(2 * x + 1, 2 * y, c) + in.at(2 * x, 2 * y + 1, c) +
                                   in.at(2 * x + 1, 2 * y + 1, c));
  return out;
}

}  // namespace

light::Environment lookup_environment(const light::Environment& environment) {
  light::Environment out = environment;
  if (out.layout == light::Environment::Layout::equirect) {
    while (out.equirect.width > 512 && out.equirect.width % 2 == 0 && out.equirect.height % 2 == 0)
      out.equirect = halve(out.equirect);
  } else {
    for (image::Image& face : out.faces)
      while (face.width > 128 && face.width % 2 == 0 && face.height % 2 == 0) face = halve(face);
  }
  return out;
}

}  // namespace prt::probes
