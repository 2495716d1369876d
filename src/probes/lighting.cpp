#include "probes/lighting.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "light/analytic.h"
#include "light/environment.h"

namespace prt::probes {

Sun parse_sun(const std::string& text) { return light::parse_disc(text, "sun"); }

sh::RgbCoefficients sun_coefficients(int bands, const Sun& sun) { return light::disc_coefficients(bands, sun); }

glm::dvec3 sun_direction_sample(const Sun& sun, double u0, double u1) { return light::disc_direction_sample(sun, u0, u1); }

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
