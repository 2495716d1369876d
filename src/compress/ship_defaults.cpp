#include "compress/ship_defaults.h"

#include <algorithm>
#include <cmath>

namespace prt::compress {

ShipCompression ship_compression(std::uint64_t vertices, int channels, int sections, int bands) {
  ShipCompression out;
  const std::uint64_t k = vertices / static_cast<std::uint64_t>(kVerticesPerCluster);
  out.clusters = static_cast<int>(std::clamp<std::uint64_t>(k, 1, static_cast<std::uint64_t>(kMaxShipClusters)));
  const std::uint64_t per_direction = static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(sections) *
                                      static_cast<std::uint64_t>(bands * bands) * 2;
  const std::uint64_t budget = vertices * static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(sections) *
                               static_cast<std::uint64_t>(kShipBands * kShipBands) * 4;
  const auto bytes = [&](std::uint64_t n) {
    return vertices * (4 + 2 * n) + static_cast<std::uint64_t>(out.clusters) * ((n + 1) * per_direction + 64);
  };
  for (int n = kMaxShipPca; n >= 1; --n)
    if (bytes(static_cast<std::uint64_t>(n)) <= budget) {
      out.pca = n;
      return out;
    }
  return out;  // N = 1: a mesh too small to fit any
}

sh::RgbCoefficients ship_metric_sky(int bands) {
  sh::RgbCoefficients sky(bands);
  for (int l = 0; l < bands; ++l)
    sky.values[static_cast<std::size_t>(l * (l + 1))] = glm::dvec3(std::sqrt((2.0 * l + 1.0)) / (l + 1.0));
  return sky;
}

}  // namespace prt::compress
