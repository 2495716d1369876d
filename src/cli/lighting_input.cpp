#include "cli/lighting_input.h"

#include <algorithm>

#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "sh/rotation.h"

namespace prt::cli {

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                                                 [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}
}  // namespace

sh::RgbCoefficients load_lighting(const std::string& spec, int bands, const glm::dvec3& ypr, int threads) {
  sh::RgbCoefficients lighting(bands);
  if (ends_with(spec, ".json")) {
    sh::RgbCoefficients file = light::read_light_file(spec);
    for (int i = 0; i < std::min(bands, file.bands) * std::min(bands, file.bands); ++i) lighting.values[i] = file.values[i];
  } else {
    lighting = light::project(light::load_environment(spec), bands, threads);
  }
  if (ypr != glm::dvec3(0.0)) {
    sh::Rotation rotation(bands, sh::rotation_from_yaw_pitch_roll(ypr.x, ypr.y, ypr.z));
    lighting = rotation.apply(lighting);
  }
  return lighting;
}

}  // namespace prt::cli
