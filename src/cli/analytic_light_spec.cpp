#include "cli/analytic_light_spec.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "cli/arguments.h"
#include "core/error.h"
#include "light/analytic.h"
#include "sh/rotation.h"

namespace prt::cli {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::stringstream ss(text);
  while (std::getline(ss, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

double parse_degrees(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || !(v > 0.0 && v <= 180.0))
    fail("expected a half-angle in degrees in (0, 180], got '" + text + "'");
  return v;
}

sh::RgbCoefficients one_term(const std::string& term, int bands) {
  const std::vector<std::string> f = split(term, ':');
  const std::string& kind = f.empty() ? term : f[0];
  auto expect_fields = [&](std::size_t n, const char* form) {
    if (f.size() != n) fail(std::string("expected ") + form);
  };
  auto triple = [&](std::size_t i, const char* what) { return parse_triple(f[i], "'" + f[i] + "'", what); };
  if (kind == "directional") {
    expect_fields(3, "directional:DX,DY,DZ:R,G,B");
    return light::directional_light(bands, triple(1, "a direction DX,DY,DZ"), triple(2, "a colour R,G,B"));
  }
  if (kind == "cone") {
    expect_fields(4, "cone:DX,DY,DZ:DEGREES:R,G,B");
    return light::cone_light(bands, triple(1, "a direction DX,DY,DZ"), parse_degrees(f[2]) * M_PI / 180.0,
                             triple(3, "a radiance R,G,B"));
  }
  if (kind == "hemisphere") {
    expect_fields(4, "hemisphere:UX,UY,UZ:SKY_R,G,B:GROUND_R,G,B");
    return light::hemisphere_light(bands, triple(1, "an up direction UX,UY,UZ"), triple(2, "a sky radiance R,G,B"),
                                   triple(3, "a ground radiance R,G,B"));
  }
  if (kind == "constant") {
    expect_fields(2, "constant:R,G,B");
    return light::constant_light(bands, triple(1, "a radiance R,G,B"));
  }
  fail("unknown analytic light '" + kind + "' (expected directional, cone, hemisphere or constant)");
}

}  // namespace

bool is_analytic_light_spec(const std::string& text) {
  for (const char* prefix : {"directional:", "cone:", "hemisphere:", "constant:"})
    if (text.rfind(prefix, 0) == 0) return true;
  return false;
}

sh::RgbCoefficients analytic_light_coefficients(const std::string& spec, int bands) {
  sh::RgbCoefficients sum(bands);
  for (const std::string& term : split(spec, '+')) {
    sh::RgbCoefficients c;
    try {
      c = one_term(term, bands);
    } catch (const Error& e) {
      fail_file(term, e.what());
    }
    for (std::size_t i = 0; i < sum.values.size(); ++i) sum.values[i] += c.values[i];
  }
  return sum;
}

light::SceneLighting analytic_scene_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll) {
  light::SceneLighting out;
  out.sky = analytic_light_coefficients(spec, bands);
  if (yaw_pitch_roll != glm::dvec3(0.0))
    out.sky = sh::Rotation(bands, sh::rotation_from_yaw_pitch_roll(yaw_pitch_roll.x, yaw_pitch_roll.y, yaw_pitch_roll.z)).apply(out.sky);
  return out;
}

}  // namespace prt::cli
