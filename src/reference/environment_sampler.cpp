#include "reference/environment_sampler.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "light/projection.h"

namespace prt::reference {

namespace {


// Cell averages of the bilinear interpolant of per-texel magnitudes: the average of a 1D hat-function
// interpolant over one texel is 3/4 of its own value plus 1/8 of each neighbour's.
std::vector<double> equirect_cell_means(const image::Image& image) {
  const int w = image.width, h = image.height;
  std::vector<double> magnitude(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      magnitude[static_cast<std::size_t>(y) * w + x] =
          sampling_magnitude({image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
  static constexpr double k[3] = {0.125, 0.75, 0.125};
  std::vector<double> mean(magnitude.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int dy = -1; dy <= 1; ++dy) {
        const int yy = std::clamp(y + dy, 0, h - 1);
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = (x + dx + w) % w;
          sum += k[dy + 1] * k[dx + 1] * magnitude[static_cast<std::size_t>(yy) * w + xx];
        }
      }
      mean[static_cast<std::size_t>(y) * w + x] = sum;
    }
  return mean;
}

// Cell means of |L| by 4 x 4 stratified point samples (cube maps, whose texels do not align with the grid).
std::vector<double> sampled_cell_means(const light::Environment& environment, int w, int h) {
  std::vector<double> mean(static_cast<std::size_t>(w) * h, 0.0);
  constexpr int kSub = 4;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const double u = (x + (i + 0.5) / kSub) / w, v = (y + (j + 0.5) / kSub) / h;
          sum += sampling_magnitude(environment.radiance(light::equirect_direction(u, v)));
        }
      mean[static_cast<std::size_t>(y) * w + x] = sum / (kSub * kSub);
    }
  return mean;
}

// Guide table of a normalised cumulative array cdf[0..n] (cdf[0] = 0, cdf[n] = 1): guide[k] is the
// interval i (cdf[i] <= k/n < cdf[i+1]) holding k/n, so that a search for u starts at guide[floor(u n)]
// and ends by guide[floor(u n) + 1] (the classic "guide table" method; Devroye 1986, III.2.4).
template <typename T>
void build_guide(const T* cdf, std::size_t n, std::uint32_t* guide) {
  std::size_t i = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(n);
    while (i + 1 < n && !(cdf[i + 1] > u)) ++i;
    guide[k] = static_cast<std::uint32_t>(i);
  }
}

// Index i of the interval [cdf[i], cdf[i+1]) holding u in [0, 1) (never an empty one), found from the guide table by a
// binary search between two guide entries, and u's fraction within the interval.
template <typename T>
std::size_t invert_cdf(const T* cdf, const std::uint32_t* guide, std::size_t n, double u, double& fraction) {
  const std::size_t k = std::min(static_cast<std::size_t>(u * static_cast<double>(n)), n - 1);
  const std::size_t lo = guide[k];
  const std::size_t hi = k + 1 < n ? guide[k + 1] : n - 1;
  // The answer lies in [lo, hi]: the last i in that range with cdf[i] <= u.
  const T* upper = std::upper_bound(cdf + lo + 1, cdf + hi + 1, u, [](double a, T b) { return a < static_cast<double>(b); });
  const std::size_t i = static_cast<std::size_t>(upper - cdf) - 1;  // cdf[i] <= u < cdf[i + 1]: not empty
  const double width = static_cast<double>(cdf[i + 1]) - static_cast<double>(cdf[i]);
  fraction = width > 0.0 ? std::clamp((u - static_cast<double>(cdf[i])) / width, 0.0, 1.0) : 0.5;
  return i;
}

}  // namespace

double sampling_magnitude(const glm::dvec3& radiance) {
  return (std::abs(radiance.x) + std::abs(radiance.y) + std::abs(radiance.z)) / 3.0;
}

EnvironmentSampler::EnvironmentSampler(light::Environment environment) : environment_(std::move(environment)) {
  std::vector<double> mean;
  if (environment_.layout == light::Environment::Layout::equirect) {
    width_ = environment_.equirect.width;
    height_ = environment_.equirect.height;
    mean = equirect_cell_means(environment_.equirect);
  } else {
    height_ = 2 * environment_.faces[0].width;
    width_ = 2 * height_;
    mean = sampled_cell_means(environment_, width_, height_);
  }
  cos_theta_.resize(static_cast<std::size_t>(height_) + 1);
  for (int y = 0; y <= height_; ++y) cos_theta_[y] = std::cos(kPi * y / height_);
  cos_theta_[0] = 1.0;
  cos_theta_[height_] = -1.0;

  // Compute cumulative weights: per row f * Omega summed over columns (then normalised and stored as
  // float: half the memory, so the tables stay in cache), and the rows' totals summed over rows.
  const std::size_t w = static_cast<std::size_t>(width_), h = static_cast<std::size_t>(height_);
  column_cdf_.assign(h * (w + 1), 0.0f);
  row_cdf_.assign(h + 1, 0.0);
  row_solid_angle_.resize(h);
  std::vector<double> cumulative(w + 1, 0.0);
  for (std::size_t y = 0; y < h; ++y) {
    row_solid_angle_[y] = light::equirect_texel_solid_angle(static_cast<int>(y), width_, height_);
    for (std::size_t x = 0; x < w; ++x) cumulative[x + 1] = cumulative[x] + mean[y * w + x] * row_solid_angle_[y];
    float* cdf = column_cdf_.data() + y * (w + 1);
    if (cumulative[w] > 0.0) {
      for (std::size_t x = 1; x < w; ++x) cdf[x] = static_cast<float>(cumulative[x] / cumulative[w]);
      cdf[w] = 1.0f;
    }
    row_cdf_[y + 1] = row_cdf_[y] + cumulative[w];
  }
  total_weight_ = row_cdf_[h];
  if (!(total_weight_ > 0.0) || !std::isfinite(total_weight_)) {
    total_weight_ = 0.0;
    return;
  }
  for (std::size_t y = 1; y < h; ++y) row_cdf_[y] /= total_weight_;
  row_cdf_[h] = 1.0;
  row_guide_.resize(h);
  build_guide(row_cdf_.data(), h, row_guide_.data());
  column_guide_.assign(h * w, 0u);
  for (std::size_t y = 0; y < h; ++y)
    if (row_cdf_[y + 1] > row_cdf_[y]) build_guide(column_cdf_.data() + y * (w + 1), w, column_guide_.data() + y * w);
}

double EnvironmentSampler::cell_density(std::size_t x, std::size_t y) const {
  // Exactly the probability with which sample() picks the cell (the widths of its two intervals in the
  // stored tables), over the cell's solid angle: sampling and pdf() can never disagree.
  const float* cdf = column_cdf_.data() + y * (static_cast<std::size_t>(width_) + 1);
  const double column = static_cast<double>(cdf[x + 1]) - static_cast<double>(cdf[x]);
  return (row_cdf_[y + 1] - row_cdf_[y]) * column / row_solid_angle_[y];
}

EnvironmentSampler::Sample EnvironmentSampler::sample(const glm::dvec2& u) const {
  double t = 0.0, s = 0.0;
  const std::size_t y = invert_cdf(row_cdf_.data(), row_guide_.data(), static_cast<std::size_t>(height_), u.x, t);
  const std::size_t w = static_cast<std::size_t>(width_);
  const std::size_t x = invert_cdf(column_cdf_.data() + y * (w + 1), column_guide_.data() + y * w, w, u.y, s);
  // Uniform in solid angle within the cell: linear in cos(theta) and in phi.
  const double cos_theta = std::clamp(cos_theta_[y] + (cos_theta_[y + 1] - cos_theta_[y]) * t, -1.0, 1.0);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double phi = 2.0 * kPi * ((static_cast<double>(x) + s) / width_ - 0.5);
  Sample out;
  out.direction = glm::dvec3(sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi));
  out.pdf = cell_density(x, y);
  return out;
}

double EnvironmentSampler::pdf(const glm::dvec3& direction) const {
  if (total_weight_ <= 0.0) return 0.0;
  double u = 0.0, v = 0.0;
  light::equirect_uv(direction, u, v);
  const int x = std::clamp(static_cast<int>(u * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(v * height_), 0, height_ - 1);
  return cell_density(static_cast<std::size_t>(x), static_cast<std::size_t>(y));
}

}  // namespace prt::reference
