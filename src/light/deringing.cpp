#include "light/deringing.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace prt::light {

WindowRequest parse_window_request(const std::string& name, double param) {
  WindowRequest request;
  if (name == "auto") return request;
  request.automatic = false;
  try {
    request.window = sh::parse_window(name);
  } catch (const Error&) {
    fail_option("window", ": unknown window '" + name + "' (expected auto, none, hanning, lanczos or laplacian)");
  }
  if (!std::isfinite(param)) fail_option("window_param", ": must be finite");
  request.param = param;
  return request;
}

WindowChoice apply_window_request(const WindowRequest& request, sh::RgbCoefficients& lighting) {
  WindowChoice choice;
  if (!request.automatic) {  // automatic: no window (the shading clamps; see the header)
    choice.window = request.window;
    choice.param = request.window == sh::Window::none ? 0.0
                   : request.param > 0.0                ? request.param
                                                        : sh::default_window_param(request.window, lighting.bands);
  }
  if (choice.window == sh::Window::none) return choice;
  sh::apply_window(sh::window_weights(choice.window, lighting.bands, choice.param), lighting);
  char text[64];
  std::snprintf(text, sizeof text, "(%.17g)", choice.param);
  choice.description = std::string(sh::window_name(choice.window)) + text;
  return choice;
}

}  // namespace prt::light
