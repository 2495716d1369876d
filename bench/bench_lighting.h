#pragma once
// Synthetic SH lighting for the renderer benchmarks: the values do not change the cost.
#include "sh/coefficients.h"

namespace prt::bench {

/// Coefficient i of each channel = (1, 0.8, 0.5) / (1 + i), for i < bands^2.
inline sh::RgbCoefficients synthetic_lighting(int bands) {
  sh::RgbCoefficients lighting(bands);
  for (int i = 0; i < bands * bands; ++i)
    lighting.values[static_cast<std::size_t>(i)] = glm::dvec3(1.0 / (1 + i), 0.8 / (1 + i), 0.5 / (1 + i));
  return lighting;
}

}  // namespace prt::bench
