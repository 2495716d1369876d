#include "light/sun_extraction.h"

#include <algorithm>
#include <array>
#include <cmath>

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

std::vector<float> luminance_of(const image::Image& im, int threads) {
  std::vector<float> y(static_cast<std::size_t>(im.width) * im.height);
  parallel_for(static_cast<std::size_t>(im.height), 16, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row)
      for (int x = 0; x < im.width; ++x) {
        const std::size_t i = row * im.width + x;
        y[i] = static_cast<float>(glm::dot(texel(im, x, static_cast<int>(row)), kLuminance));
      }
  });
  return y;
}

// The solid-angle-weighted median of the luminance, to 1/16 stop (bin centre, geometric).
double sky_level(const std::vector<float>& lum, const Grid& g) {
  std::vector<double> histogram(kBins, 0.0);
  double zero_weight = 0.0, total = 0.0;
  for (int y = 0; y < g.height; ++y) {
    const double omega = g.row_solid_angle[y];
    for (int x = 0; x < g.width; ++x) {
      const float v = lum[static_cast<std::size_t>(y) * g.width + x];
      total += omega;
      if (!(v > 0.0f)) {
        zero_weight += omega;
        continue;
      }
      const int bin = std::clamp(static_cast<int>(std::floor((std::log2(v) - kMinStop) * kBinsPerStop)), 0, kBins - 1);
      histogram[bin] += omega;
    }
  }
  double seen = zero_weight;
  if (seen >= 0.5 * total) return 0.0;
  for (int b = 0; b < kBins; ++b) {
    seen += histogram[b];
    if (seen >= 0.5 * total) return std::exp2(kMinStop + (b + 0.5) / kBinsPerStop);
  }
  return std::exp2(kMinStop + 128.0);
}

// 8-connected regions of texels above `threshold` (wrapping in phi), in scan order of their first texel.
std::vector<std::vector<std::uint32_t>> bright_regions(const std::vector<float>& lum, const Grid& g, double threshold) {
  std::vector<int> label(lum.size(), -1);
  std::vector<std::vector<std::uint32_t>> regions;
  std::vector<std::uint32_t> stack;
  for (std::size_t start = 0; start < lum.size(); ++start) {
    if (!(lum[start] > threshold) || label[start] >= 0) continue;
    const int id = static_cast<int>(regions.size());
    regions.emplace_back();
    label[start] = id;
    stack.assign(1, static_cast<std::uint32_t>(start));
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      regions[id].push_back(i);
      const int x = static_cast<int>(i % g.width), y = static_cast<int>(i / g.width);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ny = y + dy;
          if (ny < 0 || ny >= g.height || (dx == 0 && dy == 0)) continue;
          const int nx = (x + dx + g.width) % g.width;
          const std::size_t j = static_cast<std::size_t>(ny) * g.width + nx;
          if (lum[j] > threshold && label[j] < 0) {
            label[j] = id;
            stack.push_back(static_cast<std::uint32_t>(j));
          }
        }
    }
    std::sort(regions[id].begin(), regions[id].end());
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
  result.residual = environment;
  if (environment.layout == Environment::Layout::cube) {
    result.residual.layout = Environment::Layout::equirect;
    result.residual.equirect = equirect_of_cube(environment, threads);
    result.residual.faces = {};
  }
  image::Image& map = result.residual.equirect;
  const Grid grid(map.width, map.height);
  const std::vector<float> lum = luminance_of(map, threads);
  result.sky_level = sky_level(lum, grid);
  double total_power = 0.0;
  for (int y = 0; y < grid.height; ++y) {
    double row = 0.0;
    for (int x = 0; x < grid.width; ++x) row += lum[static_cast<std::size_t>(y) * grid.width + x];
    total_power += row * grid.row_solid_angle[y];
  }
  if (!(total_power > 0.0)) return result;

  std::vector<Fit> fits;
  for (const auto& region : bright_regions(lum, grid, kSeedContrast * result.sky_level)) {
    Fit fit;
    if (!fit_region(region, lum, grid, result.sky_level, map, fit)) continue;
    if (glm::dot(fit.disc.irradiance, kLuminance) < kMinPowerFraction * total_power) continue;
    fits.push_back(std::move(fit));
  }
  std::stable_sort(fits.begin(), fits.end(), [](const Fit& a, const Fit& b) {
    return glm::dot(a.disc.irradiance, kLuminance) > glm::dot(b.disc.irradiance, kLuminance);
  });
  max_discs = std::clamp(max_discs, 1, kMaxDiscs);
  if (fits.size() > static_cast<std::size_t>(max_discs)) fits.resize(static_cast<std::size_t>(max_discs));
  for (const Fit& f : fits) {
    for (std::size_t k = 0; k < f.mask.size(); ++k)
      for (int c = 0; c < 3; ++c) map.at(f.mask[k][0], f.mask[k][1], c) = static_cast<float>(f.fill[k][c]);
    result.discs.push_back(f.disc);
    result.masked_texels.push_back(static_cast<int>(f.mask.size()));
  }
  return result;
}

}  // namespace prt::light
