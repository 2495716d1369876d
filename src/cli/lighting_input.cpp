#include "cli/lighting_input.h"

namespace prt::cli {

void add_lighting_options(CLI::App* cmd, LightingArguments& a) {
  cmd->add_option("--sun", a.sun,
                  "auto (find the sun and compact lamps in the map and shade them exactly), none, or a disc "
                  "DX,DY,DZ,R,G,B,RADIUS_DEG (R,G,B = irradiance at normal incidence; added to the map)")
      ->capture_default_str();
  cmd->add_option("--window", a.window,
                  "SH ringing window of the sky: auto (the least Laplacian window keeping radiance and irradiance "
                  ">= 0), none, hanning, lanczos, laplacian")
      ->capture_default_str();
  cmd->add_option("--window-param", a.window_param, "Window parameter (hanning/lanczos: W; laplacian: lambda); default depends on the window");
}

light::SunRequest sun_request(const LightingArguments& a) { return light::parse_sun_request(a.sun); }

light::WindowRequest window_request(const LightingArguments& a) { return light::parse_window_request(a.window, a.window_param); }

light::SceneLighting load_scene_lighting(const std::string& spec, int bands, const glm::dvec3& ypr, const LightingArguments& a,
                                         int threads, bool glossy) {
  light::WindowRequest window = window_request(a);
  window.radiance = glossy;
  return light::load_scene_lighting(spec, bands, ypr, sun_request(a), window, threads);
}

sh::RgbCoefficients load_unsplit_sh_lighting(const std::string& spec, int bands, const glm::dvec3& ypr, int threads) {
  light::SunRequest none;
  none.mode = light::SunRequest::Mode::none;
  return light::load_scene_lighting(spec, bands, ypr, none, light::parse_window_request("none"), threads).sky;
}

}  // namespace prt::cli
