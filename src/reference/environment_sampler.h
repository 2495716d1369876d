#pragma once
// The distant environment as the reference path tracer sees it: signed radiance per direction, and a
// piecewise-constant importance-sampling distribution over the sphere for next-event estimation.
//
// RADIANCE. L(w) = Environment::radiance(w) (light/environment.h: bilinear between texel centres,
// equirect wrapping in phi and clamping at the poles, cube faces clamped at their edges). Values are
// used with their sign: a band-limited reconstruction (band_limited_environment) rings negative, and
// the PRT product equals the integral against that signed function. load_environment already zeroed the
// negative pixels of real maps.
//
// SAMPLING DISTRIBUTION. A grid of W x H cells in equirect layout (cell (x, y) covers
// phi in 2 pi [x/W - 1/2, (x+1)/W - 1/2), theta in pi [y/H, (y+1)/H); see the equirect convention in
// light/environment.h). Each cell gets the weight f(x, y) * Omega(y), where Omega(y) is the cell's
// exact solid angle (the integral of sin(theta) over it, light::equirect_texel_solid_angle) and f is an
// estimate of the mean of |L| over the cell (mean of the absolute values of the three channels):
//   - equirect environments: the grid is the image itself and f is the exact cell average of the
//     bilinear interpolant of the per-texel |L|: sum over the 3 x 3 neighbourhood with weights
//     k(dx) k(dy), k(0) = 3/4, k(+-1) = 1/8 (x wraps, y clamps). It is positive wherever the bilinear
//     radiance can be non-zero, so bright single texels are found by both strategies.
//   - cube environments: W = 4N, H = 2N for faces of N x N, f = mean of |L| at 4 x 4 stratified points
//     of the cell.
// A cell is chosen with probability proportional to its weight (marginal over rows, then conditional
// over the row, by inverting the cumulative sums with the coordinates u.x and u.y of a point of
// [0,1)^2, searched through guide tables in O(1) expected time), and the direction is then uniform
// IN SOLID ANGLE within the cell: with t and s the fractions of u.x and u.y inside the chosen
// intervals, cos(theta) = lerp(cos(theta_top), cos(theta_bottom), t) and phi = 2 pi ((x + s) / W - 1/2).
// So the density per steradian is piecewise constant,
//   pdf(w) = f(cell of w) / sum over cells of f * Omega
// (computed from the stored cumulative tables themselves, so that it is exactly the probability with
// which the cell is drawn, divided by its solid angle), finite everywhere (also at the poles, unlike a density taken per unit (u, v) and divided by sin theta).
// The distribution only has to be roughly proportional to |L| cos: multiple importance sampling with
// cosine-weighted BSDF sampling (estimator.h) keeps the estimate unbiased wherever this pdf is 0 or poor.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "light/environment.h"

namespace prt::reference {

class EnvironmentSampler {
 public:
  /// Takes the environment (kept by value) and builds the distribution. An environment that is zero
  /// everywhere gives a sampler whose has_distribution() is false (then only BSDF sampling is used).
  explicit EnvironmentSampler(light::Environment environment);

  /// Signed radiance toward unit direction `direction` (see RADIANCE above).
  glm::dvec3 radiance(const glm::dvec3& direction) const { return environment_.radiance(direction); }

  /// False if every cell weighs 0: sample() must not be called and pdf() returns 0.
  bool has_distribution() const { return total_weight_ > 0.0; }

  struct Sample {
    glm::dvec3 direction{0.0, 1.0, 0.0};  ///< unit
    double pdf = 0.0;                     ///< per steradian, > 0
  };
  /// Maps u in [0,1)^2 to a direction with the density above; continuous in u within each cell, so
  /// stratified or low-discrepancy points stay well spread. Precondition: has_distribution().
  Sample sample(const glm::dvec2& u) const;

  /// Density per steradian of sample() at unit `direction` (0 in cells of zero weight).
  double pdf(const glm::dvec3& direction) const;

  int grid_width() const { return width_; }
  int grid_height() const { return height_; }
  const light::Environment& environment() const { return environment_; }

 private:
  light::Environment environment_;
  int width_ = 0, height_ = 0;
  double cell_density(std::size_t x, std::size_t y) const;

  std::vector<double> row_cdf_;              // height_ + 1 cumulative row weights, normalised to [0, 1]
  std::vector<float> column_cdf_;            // height_ rows of width_ + 1 cumulative weights, each normalised
  std::vector<std::uint32_t> row_guide_;     // guide table of row_cdf_ (height_ entries)
  std::vector<std::uint32_t> column_guide_;  // guide tables of the rows' cdfs (height_ * width_)
  std::vector<double> row_solid_angle_;      // height_: solid angle of one cell of each row
  std::vector<double> cos_theta_;            // height_ + 1 row boundaries: cos(pi y / H)
  double total_weight_ = 0.0;
};

/// |L| of a pixel as the distribution uses it: the mean of the absolute values of r, g, b.
double sampling_magnitude(const glm::dvec3& radiance);

}  // namespace prt::reference
