#pragma once
// The strongly directional sky of the glossy reference tests (test_glossy_reference.cpp,
// test_glossy_materials.cpp).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "light/environment.h"

namespace prt::test {

// Sky gradient, a bright broad lobe (a low sun) and a coloured horizon band: strongly directional.
inline light::Environment directional_sky() {
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.6, 0.7, 0.4));
  light::Environment env;
  env.layout = light::Environment::Layout::equirect;
  env.equirect = image::Image(256, 128, 3);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / 256.0, (y + 0.5) / 128.0);
      const double lobe = std::pow(std::max(0.0, glm::dot(d, sun)), 8.0);
      const double horizon = std::exp(-8.0 * d.y * d.y);
      const glm::dvec3 v(0.25 + 0.3 * std::max(d.y, 0.0) + 4.0 * lobe + 0.4 * horizon, 0.3 + 0.35 * std::max(d.y, 0.0) + 3.0 * lobe,
                         0.45 + 0.5 * std::max(d.y, 0.0) + 1.5 * lobe);
      for (int c = 0; c < 3; ++c) env.equirect.at(x, y, c) = static_cast<float>(v[c]);
    }
  env.source = "synthetic sky";
  return env;
}

}  // namespace prt::test
