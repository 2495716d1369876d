#include "light/scene_lighting.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "light/sun_extraction.h"
#include "sh/rotation.h"

namespace prt::light {

namespace {

bool is_json(const std::string& s) {
  const std::string suffix = ".json";
  return s.size() >= suffix.size() && std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                                                 [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

void add(sh::RgbCoefficients& to, const sh::RgbCoefficients& from) {
  for (std::size_t i = 0; i < to.values.size() && i < from.values.size(); ++i) to.values[i] += from.values[i];
}

}  // namespace

SunRequest parse_sun_request(const std::string& text) {
  SunRequest request;
  if (text == "auto") return request;
  if (text == "none") {
    request.mode = SunRequest::Mode::none;
    return request;
  }
  request.mode = SunRequest::Mode::given;
  request.disc = parse_disc(text, "sun");
  return request;
}

sh::RgbCoefficients SceneLighting::total() const {
  sh::RgbCoefficients out = sky;
  add(out, discs_coefficients(sky.bands, discs));
  return out;
}

namespace {

void rotate_and_window(SceneLighting& out, int bands, const glm::dvec3& ypr, const SunRequest& sun, const WindowRequest& window) {
  out.clamp_negative = !(sun.mode == SunRequest::Mode::none && !window.automatic && window.window == sh::Window::none);
  if (ypr != glm::dvec3(0.0)) {
    const glm::dmat3 r = sh::rotation_from_yaw_pitch_roll(ypr.x, ypr.y, ypr.z);
    out.sky = sh::Rotation(bands, r).apply(out.sky);
    for (Disc& d : out.discs) d = rotated(d, r);
  }
  out.window = apply_window_request(window, out.sky);
}

}  // namespace

SceneLighting split_environment(const Environment& environment, int bands, const glm::dvec3& ypr, const SunRequest& sun,
                                const WindowRequest& window, int threads, Environment* sky_map) {
  SceneLighting out;
  if (sun.mode == SunRequest::Mode::automatic) {
    ExtractionResult extracted = extract_discs(environment, threads);
    out.discs = std::move(extracted.discs);
    out.sky_level = extracted.sky_level;
    out.sky = project(out.discs.empty() ? environment : extracted.residual, bands, threads);
    if (sky_map != nullptr && !out.discs.empty()) *sky_map = std::move(extracted.residual);
  } else {
    out.sky = project(environment, bands, threads);
    if (sun.mode == SunRequest::Mode::given) out.discs.push_back(sun.disc);
  }
  rotate_and_window(out, bands, ypr, sun, window);
  return out;
}

SceneLighting load_scene_lighting(const std::string& spec, int bands, const glm::dvec3& ypr, const SunRequest& sun,
                                  const WindowRequest& window, int threads) {
  if (!is_json(spec)) return split_environment(load_environment(spec), bands, ypr, sun, window, threads);
  SceneLighting out;
  out.sky = sh::RgbCoefficients(bands);
  const LightFile file = read_lighting_file(spec);
  const int keep = std::min(bands, file.coefficients.bands);
  for (int i = 0; i < keep * keep; ++i) out.sky.values[i] = file.coefficients.values[i];
  if (sun.mode == SunRequest::Mode::none)
    add(out.sky, discs_coefficients(bands, file.discs));
  else
    out.discs = file.discs;
  if (sun.mode == SunRequest::Mode::given) out.discs.push_back(sun.disc);
  rotate_and_window(out, bands, ypr, sun, window);
  return out;
}

std::string describe_lighting(const SceneLighting& lighting) {
  std::string text = "sun: " + std::to_string(lighting.discs.size()) + (lighting.discs.size() == 1 ? " disc" : " discs");
  for (const Disc& d : lighting.discs) {
    char item[200];
    std::snprintf(item, sizeof item, " (dir %.4f,%.4f,%.4f, radius %.3f deg, E %.4g,%.4g,%.4g)", d.direction.x, d.direction.y,
                  d.direction.z, d.angular_radius * 57.29577951308232, d.irradiance.x, d.irradiance.y, d.irradiance.z);
    text += item;
  }
  return text + "; window " + lighting.window.description;
}

}  // namespace prt::light
