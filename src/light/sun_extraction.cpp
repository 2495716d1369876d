#include "light/sun_extraction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "light/projection.h"

namespace prt::light {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr glm::dvec3 kLuminance(0.2126, 0.7152, 0.0722);

// log2(Y) histogram for the weighted median: 1/16 stop bins over [-64, 64) stops.
constexpr int kBinsPerStop = 16;
constexpr int kMinStop = -64;
constexpr int kBins = 128 * kBinsPerStop;

// The equirect grid's geometry: per-row solid angle and direction of every texel centre.
struct Grid {
  int width = 0, height = 0;
  std::vector<double> row_solid_angle;
  std::vector<double> cos_theta, sin_theta, cos_phi, sin_phi;

  explicit Grid(int w, int h) : width(w), height(h), row_solid_angle(h), cos_theta(h), sin_theta(h), cos_phi(w), sin_phi(w) {
    for (int y = 0; y < h; ++y) {
      row_solid_angle[y] = equirect_texel_solid_angle(y, w, h);
      const double theta = kPi * (y + 0.5) / h;
      cos_theta[y] = std::cos(theta);
      sin_theta[y] = std::sin(theta);
    }
    for (int x = 0; x < w; ++x) {
      const double phi = 2.0 * kPi * ((x + 0.5) / w - 0.5);
      cos_phi[x] = std::cos(phi);
      sin_phi[x] = std::sin(phi);
    }
  }
  glm::dvec3 direction(int x, int y) const {
    return {sin_theta[y] * cos_phi[x], cos_theta[y], sin_theta[y] * sin_phi[x]};
  }
  double texel_angle() const { return kPi / height; }
};

glm::dvec3 texel(const image::Image& im, int x, int y) { return {im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)}; }

// The luminance of every texel, with the map's power sum Y Omega and the solid-angle histogram of
// log2 Y, in one parallel pass over fixed chunks of rows (merged in chunk order: deterministic).
struct LuminanceField {
  std::vector<float> y;
  std::vector<double> histogram = std::vector<double>(kBins, 0.0);
  double zero_weight = 0.0, total_weight = 0.0, power = 0.0;
};

// Bin of a positive finite float: its exponent and top 4 mantissa bits, i.e. 1/16-stop steps (linear
// within each step, which is all a threshold needs).
int log_bin(float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  const int bin = static_cast<int>(bits >> 19) - (127 + kMinStop) * kBinsPerStop;
  return std::clamp(bin, 0, kBins - 1);
}

LuminanceField luminance_of(const image::Image& im, const Grid& g, int threads) {
  constexpr int kRows = 16;
  const int chunks = (im.height + kRows - 1) / kRows;
  std::vector<LuminanceField> parts(static_cast<std::size_t>(chunks));
  LuminanceField field;
  field.y.resize(static_cast<std::size_t>(im.width) * im.height);
  parallel_for(static_cast<std::size_t>(chunks), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t chunk = begin; chunk < end; ++chunk) {
      LuminanceField& part = parts[chunk];
      for (int row = static_cast<int>(chunk) * kRows; row < std::min(im.height, static_cast<int>(chunk + 1) * kRows); ++row) {
        const double omega = g.row_solid_angle[row];
        const float* p = &im.pixels[static_cast<std::size_t>(row) * im.width * im.channels];
        float* out = &field.y[static_cast<std::size_t>(row) * im.width];
        double row_sum = 0.0;
        for (int x = 0; x < im.width; ++x, p += im.channels) {
          const float v = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
          out[x] = v;
          row_sum += v;
          if (v > 0.0f) part.histogram[static_cast<std::size_t>(log_bin(v))] += omega;
          else part.zero_weight += omega;
        }
        part.power += row_sum * omega;
        part.total_weight += omega * im.width;
      }
    }
  });
  for (const LuminanceField& part : parts) {
    for (int b = 0; b < kBins; ++b) field.histogram[static_cast<std::size_t>(b)] += part.histogram[static_cast<std::size_t>(b)];
    field.zero_weight += part.zero_weight;
    field.total_weight += part.total_weight;
    field.power += part.power;
  }
  return field;
}

// The solid-angle-weighted median of the luminance, to 1/16 stop (the bin's lower edge).
double sky_level(const LuminanceField& f) {
  double seen = f.zero_weight;
  if (seen >= 0.5 * f.total_weight) return 0.0;
  for (int b = 0; b < kBins; ++b) {
    seen += f.histogram[static_cast<std::size_t>(b)];
    if (seen >= 0.5 * f.total_weight) return std::exp2(kMinStop + static_cast<double>(b) / kBinsPerStop);
  }
  return std::exp2(kMinStop + 128.0);
}

// 8-connected regions of texels above `threshold` (wrapping in phi), in scan order of their first
// texel. Only the seeds are visited: a parallel scan collects them, a flood fill groups them.
std::vector<std::vector<std::uint32_t>> bright_regions(const std::vector<float>& lum, const Grid& g, double threshold, int threads) {
  std::vector<std::vector<std::uint32_t>> row_seeds(static_cast<std::size_t>(g.height));
  parallel_for(static_cast<std::size_t>(g.height), 32, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row)
      for (int x = 0; x < g.width; ++x)
        if (lum[row * g.width + x] > threshold) row_seeds[row].push_back(static_cast<std::uint32_t>(row * g.width + x));
  });
  std::vector<std::uint32_t> seeds;
  for (const auto& r : row_seeds) seeds.insert(seeds.end(), r.begin(), r.end());
  std::vector<int> label(seeds.size(), -1);
  auto index_of = [&](std::uint32_t texel) -> std::ptrdiff_t {
    auto it = std::lower_bound(seeds.begin(), seeds.end(), texel);
    return it != seeds.end() && *it == texel ? it - seeds.begin() : -1;
  };
  std::vector<std::vector<std::uint32_t>> regions;
  std::vector<std::size_t> stack;
  for (std::size_t start = 0; start < seeds.size(); ++start) {
    if (label[start] >= 0) continue;
    const int id = static_cast<int>(regions.size());
    regions.emplace_back();
    label[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const std::uint32_t i = seeds[stack.back()];
      stack.pop_back();
      regions[static_cast<std::size_t>(id)].push_back(i);
      const int x = static_cast<int>(i % g.width), y = static_cast<int>(i / g.width);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ny = y + dy;
          if (ny < 0 || ny >= g.height || (dx == 0 && dy == 0)) continue;
          const std::ptrdiff_t k = index_of(static_cast<std::uint32_t>(ny * g.width + (x + dx + g.width) % g.width));
          if (k >= 0 && label[static_cast<std::size_t>(k)] < 0) {
            label[static_cast<std::size_t>(k)] = id;
            stack.push_back(static_cast<std::size_t>(k));
          }
        }
    }
    std::sort(regions[static_cast<std::size_t>(id)].begin(), regions[static_cast<std::size_t>(id)].end());
  }
  return regions;
}

// Texels whose centre lies within `radius` of `centre`: calls f(x, y, angle).
template <class F>
void for_texels_within(const Grid& g, const glm::dvec3& centre, double radius, F&& f) {
  const double theta_c = std::acos(std::clamp(centre.y, -1.0, 1.0));
  const double cos_radius = std::cos(radius);
  const int y0 = std::max(0, static_cast<int>(std::floor((theta_c - radius) / kPi * g.height)) - 1);
  const int y1 = std::min(g.height - 1, static_cast<int>(std::ceil((theta_c + radius) / kPi * g.height)) + 1);
  for (int y = y0; y <= y1; ++y)
    for (int x = 0; x < g.width; ++x) {
      const glm::dvec3 w = g.direction(x, y);
      const double c = glm::dot(w, centre);
      if (c >= cos_radius) f(x, y, std::acos(std::min(1.0, c)));
    }
}

struct Fit {
  Disc disc;
  std::vector<std::array<int, 2>> mask;  // texels to refill
  std::vector<glm::dvec3> fill;          // their new values
};

// Fits one region of `map` as a disc with the refill of its mask (RULE, steps 3-5). False when the
// region is not compact enough or its peak too low.
bool fit_region(const std::vector<std::uint32_t>& region, const std::vector<float>& lum, const Grid& g, double sky,
                const image::Image& map, Fit& fit) {
  float peak = 0.0f;
  for (std::uint32_t i : region) peak = std::max(peak, lum[i]);
  if (!(peak > kPeakContrast * sky)) return false;
  const double core_threshold = std::max(kSeedContrast * sky, kSeedPeakFraction * peak);
  glm::dvec3 centroid(0.0);
  for (std::uint32_t i : region)
    if (lum[i] > core_threshold) centroid += lum[i] * g.row_solid_angle[i / g.width] * g.direction(i % g.width, i / g.width);
  centroid = glm::normalize(centroid);
  double core_radius = 0.0;
  for (std::uint32_t i : region)
    if (lum[i] > core_threshold)
      core_radius = std::max(core_radius, std::acos(std::min(1.0, glm::dot(centroid, g.direction(i % g.width, i / g.width)))));
  if (core_radius > std::max(kMaxCoreRadiusDegrees * kPi / 180.0, 1.5 * g.texel_angle())) return false;

  const double mask_radius = core_radius + kMaskMarginTexels * g.texel_angle();
  const double ring_radius = mask_radius + 2.0 * g.texel_angle();
  std::vector<std::array<int, 2>>& mask = fit.mask;
  std::vector<glm::dvec3> ring_direction, ring_value;
  for_texels_within(g, centroid, ring_radius, [&](int x, int y, double angle) {
    if (angle <= mask_radius) {
      mask.push_back({x, y});
    } else {
      ring_direction.push_back(g.direction(x, y));
      ring_value.push_back(texel(map, x, y));
    }
  });
  // Fill, then measure the excess the fill removed.
  std::vector<glm::dvec3> excess(mask.size());
  for (std::size_t k = 0; k < mask.size(); ++k) {
    const glm::dvec3 w = g.direction(mask[k][0], mask[k][1]);
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (std::size_t r = 0; r < ring_direction.size(); ++r) {
      const double d2 = std::max(1e-12, 2.0 - 2.0 * glm::dot(w, ring_direction[r]));
      sum += ring_value[r] / d2;
      weight += 1.0 / d2;
    }
    fit.fill.push_back(weight > 0.0 ? sum / weight : glm::dvec3(0.0));
    excess[k] = texel(map, mask[k][0], mask[k][1]) - fit.fill.back();
  }
  glm::dvec3 axis(0.0);
  for (std::size_t k = 0; k < mask.size(); ++k)
    axis += glm::dot(excess[k], kLuminance) * g.row_solid_angle[mask[k][1]] * g.direction(mask[k][0], mask[k][1]);
  if (!(glm::length(axis) > 0.0)) return false;
  const glm::dvec3 d = glm::normalize(axis);
  glm::dvec3 irradiance(0.0);
  double moment = 0.0, weight = 0.0;
  for (std::size_t k = 0; k < mask.size(); ++k) {
    const glm::dvec3 w = g.direction(mask[k][0], mask[k][1]);
    const double omega = g.row_solid_angle[mask[k][1]];
    irradiance += excess[k] * omega * glm::dot(d, w);
    const double y = std::max(0.0, glm::dot(excess[k], kLuminance)) * omega;
    const double angle = std::acos(std::min(1.0, glm::dot(d, w)));
    moment += y * angle * angle;
    weight += y;
  }
  fit.disc.direction = d;
  fit.disc.irradiance = glm::max(irradiance, glm::dvec3(0.0));
  fit.disc.angular_radius = std::clamp(std::sqrt(2.0 * moment / std::max(weight, 1e-300)), 0.5 * g.texel_angle(), kMaxDiscRadius);
  return glm::dot(fit.disc.irradiance, kLuminance) > 0.0;
}

image::Image equirect_of_cube(const Environment& env, int threads) {
  const int n = env.faces[0].width;
  image::Image out(4 * n, 2 * n, 3);
  parallel_for(static_cast<std::size_t>(out.height), 8, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < out.width; ++x) {
        const glm::dvec3 l = env.radiance(equirect_direction((x + 0.5) / out.width, (y + 0.5) / out.height));
        for (int c = 0; c < 3; ++c) out.at(x, static_cast<int>(y), c) = static_cast<float>(l[c]);
      }
  });
  return out;
}

}  // namespace

ExtractionResult extract_discs(const Environment& environment, int threads, int max_discs) {
  ExtractionResult result;
  const bool cube = environment.layout == Environment::Layout::cube;
  const image::Image resampled = cube ? equirect_of_cube(environment, threads) : image::Image();
  const image::Image& map = cube ? resampled : environment.equirect;
  const Grid grid(map.width, map.height);
  const LuminanceField field = luminance_of(map, grid, threads);
  result.sky_level = sky_level(field);
  if (!(field.power > 0.0)) return result;

  std::vector<Fit> fits;
  for (const auto& region : bright_regions(field.y, grid, kSeedContrast * result.sky_level, threads)) {
    Fit fit;
    if (!fit_region(region, field.y, grid, result.sky_level, map, fit)) continue;
    if (glm::dot(fit.disc.irradiance, kLuminance) < kMinPowerFraction * field.power) continue;
    fits.push_back(std::move(fit));
  }
  if (fits.empty()) return result;
  std::stable_sort(fits.begin(), fits.end(), [](const Fit& a, const Fit& b) {
    return glm::dot(a.disc.irradiance, kLuminance) > glm::dot(b.disc.irradiance, kLuminance);
  });
  max_discs = std::clamp(max_discs, 1, kMaxDiscs);
  if (fits.size() > static_cast<std::size_t>(max_discs)) fits.resize(static_cast<std::size_t>(max_discs));

  result.residual.layout = Environment::Layout::equirect;
  result.residual.source = environment.source;
  result.residual.repaired = environment.repaired;
  result.residual.equirect = map;
  for (const Fit& f : fits) {
    for (std::size_t k = 0; k < f.mask.size(); ++k)
      for (int c = 0; c < 3; ++c) result.residual.equirect.at(f.mask[k][0], f.mask[k][1], c) = static_cast<float>(f.fill[k][c]);
    result.discs.push_back(f.disc);
    result.masked_texels.push_back(static_cast<int>(f.mask.size()));
  }
  return result;
}

}  // namespace prt::light
