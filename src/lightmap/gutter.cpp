#include "lightmap/gutter.h"

#include <algorithm>

#include "transfer/transfer_file.h"

namespace prt::lightmap {

namespace {

// Calls f(neighbour texel) for the up to 8 neighbours of texel (i, j).
template <class F>
void for_each_neighbour(int i, int j, int width, int height, F f) {
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int x = i + di, y = j + dj;
      if ((di == 0 && dj == 0) || x < 0 || y < 0 || x >= width || y >= height) continue;
      f(std::size_t(x) + std::size_t(y) * std::size_t(width));
    }
}

}  // namespace

std::vector<std::vector<std::uint32_t>> grow_gutter(std::vector<std::uint8_t>& coverage, int width, int height, int passes) {
  // round[t]: the round in which texel t was filled (0: covered), so a texel filled in round r reads
  // only neighbours of rounds < r.
  std::vector<std::vector<std::uint32_t>> rounds;
  std::vector<std::uint8_t> filled(coverage.size());
  for (std::size_t t = 0; t < coverage.size(); ++t) filled[t] = coverage[t] != transfer::kTexelEmpty;
  for (int r = 0; r < passes; ++r) {
    std::vector<std::uint32_t> grown;
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const std::size_t t = std::size_t(i) + std::size_t(j) * std::size_t(width);
        if (filled[t]) continue;
        bool any = false;
        for_each_neighbour(i, j, width, height, [&](std::size_t n) { any = any || filled[n]; });
        if (any) grown.push_back(std::uint32_t(t));
      }
    if (grown.empty()) break;
    for (std::uint32_t t : grown) {
      filled[t] = 1;
      coverage[t] = transfer::kTexelGutter;
    }
    rounds.push_back(std::move(grown));
  }
  return rounds;
}

std::vector<std::vector<std::uint32_t>> gutter_rounds(const std::vector<std::uint8_t>& coverage, int width, int height, int passes) {
  std::vector<std::uint8_t> covered(coverage.size());
  for (std::size_t t = 0; t < coverage.size(); ++t) covered[t] = coverage[t] == transfer::kTexelCovered ? 1 : 0;
  std::vector<std::vector<std::uint32_t>> rounds = grow_gutter(covered, width, height, passes), kept;
  // Keep the texels marked gutter (all of them, for the file's own gutter count), rounds in order.
  for (std::vector<std::uint32_t>& round : rounds) {
    std::vector<std::uint32_t> part;
    for (std::uint32_t t : round)
      if (coverage[t] == transfer::kTexelGutter) part.push_back(t);
    if (part.empty()) break;
    kept.push_back(std::move(part));
  }
  return kept;
}

void fill_gutter(std::vector<float>& values, std::size_t stride, const std::vector<std::uint8_t>& coverage,
                 const std::vector<std::vector<std::uint32_t>>& rounds, int width, int height) {
  std::vector<std::uint8_t> filled(coverage.size());
  for (std::size_t t = 0; t < coverage.size(); ++t) filled[t] = coverage[t] == transfer::kTexelCovered;
  std::vector<double> sum(stride);
  for (const std::vector<std::uint32_t>& round : rounds) {
    for (std::uint32_t t : round) {
      std::fill(sum.begin(), sum.end(), 0.0);
      int count = 0;
      for_each_neighbour(int(t % std::uint32_t(width)), int(t / std::uint32_t(width)), width, height, [&](std::size_t n) {
        if (!filled[n]) return;
        ++count;
        for (std::size_t k = 0; k < stride; ++k) sum[k] += values[n * stride + k];
      });
      for (std::size_t k = 0; k < stride; ++k) values[std::size_t(t) * stride + k] = float(sum[k] / count);
    }
    for (std::uint32_t t : round) filled[t] = 1;
  }
}

}  // namespace prt::lightmap
