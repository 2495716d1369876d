#include "compress/ship_defaults.h"

#include <algorithm>
#include <cmath>

namespace prt::compress {

namespace {

// K and N for `points` model points whose payload must fit in that of `budget_blocks` uncompressed
// 5-band float32 blocks (ship_defaults.h).
ShipCompression fit_ship_compression(std::uint64_t points, std::uint64_t budget_blocks, int channels, int sections, int bands) {
  ShipCompression out;
  const std::uint64_t k = points / static_cast<std::uint64_t>(kVerticesPerCluster);
  out.clusters = static_cast<int>(std::clamp<std::uint64_t>(k, 1, static_cast<std::uint64_t>(kMaxShipClusters)));
  const std::uint64_t per_direction = static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(sections) *
                                      static_cast<std::uint64_t>(bands * bands) * 2;
  const std::uint64_t budget = budget_blocks * static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(sections) *
                               static_cast<std::uint64_t>(kShipBands * kShipBands) * 4;
  const auto bytes = [&](std::uint64_t n) {
    return points * (4 + 2 * n) + static_cast<std::uint64_t>(out.clusters) * ((n + 1) * per_direction + 64);
  };
  for (int n = kMaxShipPca; n >= 1; --n)
    if (bytes(static_cast<std::uint64_t>(n)) <= budget) {
      out.pca = n;
      return out;
    }
  return out;  // N = 1: too few points to fit any
}

}  // namespace

ShipCompression ship_compression(std::uint64_t vertices, int channels, int sections, int bands) {
  return fit_ship_compression(vertices, vertices, channels, sections, bands);
}

ShipCompression ship_texel_compression(std::uint64_t points, std::uint64_t texels, int channels, int sections, int bands) {
  return fit_ship_compression(points, std::max(points, texels), channels, sections, bands);
}

sh::RgbCoefficients ship_metric_sky(int bands) {
  sh::RgbCoefficients sky(bands);
  for (int l = 0; l < bands; ++l)
    sky.values[static_cast<std::size_t>(l * (l + 1))] = glm::dvec3(std::sqrt((2.0 * l + 1.0)) / (l + 1.0));
  return sky;
}

}  // namespace prt::compress
