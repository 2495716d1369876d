// sh::eval_accumulate (evaluation fused with weighted accumulation, rescaled recurrence) against sums
// built here from the slow reference sh::eval_reference, and the projection of the basis functions
// themselves under an exact product quadrature (the identity sum_q w_q Y_i(d_q) Y_k(d_q) = delta_ik).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/accumulator.h"
#include "sh/basis.h"
#include "sh/eval_kernels.h"
#include "sh/quadrature.h"

namespace sh = prt::sh;

namespace {

double band_scale(int l) { return std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)); }

struct Samples {
  std::vector<glm::dvec3> dirs;
  std::vector<double> weights;
};

// Random unit directions (rounded to float, so float and double see the same ones) and weights in [-1, 2].
Samples random_samples(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1.0, 2.0);
  Samples s;
  for (std::size_t j = 0; j < count; ++j) {
    // Unit in double after rounding to float: the double path sees unit vectors, the float one the same
    // vector to float precision.
    // (Drawn one statement each: the order of a constructor's arguments is unspecified, and GCC and clang
    // draw them in opposite orders.)
    const double dx = normal(rng), dy = normal(rng), dz = normal(rng);
    glm::vec3 d(glm::normalize(glm::dvec3(dx, dy, dz)));
    s.dirs.push_back(glm::normalize(glm::dvec3(d)));
    s.weights.push_back(static_cast<float>(uniform(rng)));
  }
  return s;
}

// Worst |sum_k - reference_k| / (band_scale(l) sum_j |w_j|) over k, with the sums started at `start`.
template <typename T, typename Accumulate>
double worst_error(Accumulate accumulate, int bands, const Samples& s, double start) {
  const std::size_t count = s.dirs.size();
  std::vector<T> x(count), y(count), z(count), w(count);
  double weight_sum = 0;
  for (std::size_t j = 0; j < count; ++j) {
    x[j] = static_cast<T>(s.dirs[j].x);
    y[j] = static_cast<T>(s.dirs[j].y);
    z[j] = static_cast<T>(s.dirs[j].z);
    w[j] = static_cast<T>(s.weights[j]);
    weight_sum += std::abs(s.weights[j]);
  }
  const int n = bands * bands;
  std::vector<T> sums(static_cast<std::size_t>(n), static_cast<T>(start));
  accumulate(bands, count, x.data(), y.data(), z.data(), w.data(), sums.data());
  double worst = 0;
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      double reference = start;
      for (std::size_t j = 0; j < count; ++j) reference += s.weights[j] * sh::eval_reference(l, m, s.dirs[j]);
      const double error = std::abs(static_cast<double>(sums[sh::index(l, m)]) - reference) /
                           (band_scale(l) * std::max(weight_sum, 1.0));
      worst = std::isnan(error) ? INFINITY : std::max(worst, error);
    }
  return worst;
}

template <typename T>
void fast(int b, std::size_t n, const T* x, const T* y, const T* z, const T* w, T* s) {
  sh::eval_accumulate(b, n, x, y, z, w, s);
}
// sh::Accumulator fed the directions in calls of the sizes `calls` (cycled), then its totals added to s.
std::vector<std::size_t> g_calls;
template <typename T>
void streamed(int b, std::size_t n, const T* x, const T* y, const T* z, const T* w, T* s) {
  sh::Accumulator<T> acc(b);
  for (std::size_t j = 0, c = 0; j < n; ++c) {
    const std::size_t size = std::min(g_calls[c % g_calls.size()], n - j);
    acc.add(size, x + j, y + j, z + j, w + j);
    j += size;
  }
  acc.add_to(s);
}
template <typename T>
void generic(int b, std::size_t n, const T* x, const T* y, const T* z, const T* w, T* s) {
  sh::detail::eval_accumulate_generic(b, n, x, y, z, w, s);
}

}  // namespace

TEST_CASE("eval_accumulate adds the weighted basis sums of the reference, any count", "[sh][eval]") {
  // Counts around the vectors of directions the kernel takes (kLanes of float and of double): fewer than one
  // (copied into a zero-padded vector), odd and even numbers of vectors (the first step takes one or two),
  // whole or with a partial last vector (overlapping the one before, its overlapped lanes weighted zero).
  // The sums start at 0.25 (they are added to, not overwritten).
  const std::size_t lanes = sh::detail::kLanes<float>, dlanes = sh::detail::kLanes<double>;
  const std::vector<std::size_t> counts = {0,         1,         lanes - 1,     lanes,     lanes + 1, 2 * lanes - 1,
                                           2 * lanes, 2 * lanes + 1, 3 * lanes, 5 * lanes + 3, dlanes + 1, 3 * dlanes - 1,
                                           200};
  // Relative to band_scale(l) sum_j |w_j|: double, rounding of 31 recurrence steps and of the sums;
  // float, the float recurrence (<= 9.4e-8 bands^1.5 measured, as eval_batch) plus the float sums.
  // Measured worst (GCC 12, AVX2): double 2.5e-15, float 0.22 of its bound.
  const double double_tolerance = 1e-14;
  double worst_float_ratio = 0;
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    const double float_tolerance = 1.5e-7 * std::pow(bands, 1.5) + 1e-7;
    for (std::size_t count : counts) {
      INFO("bands " << bands << ", count " << count);
      const Samples s = random_samples(count, 100 + static_cast<unsigned>(bands));
      const double ef = worst_error<float>(fast<float>, bands, s, 0.25);
      const double ed = worst_error<double>(fast<double>, bands, s, 0.25);
      REQUIRE(ef <= float_tolerance);
      REQUIRE(ed <= double_tolerance);
      REQUIRE(worst_error<float>(generic<float>, bands, s, 0.25) <= float_tolerance);
      REQUIRE(worst_error<double>(generic<double>, bands, s, 0.25) <= double_tolerance);
      worst_float_ratio = std::max(worst_float_ratio, ef / float_tolerance);
    }
  }
  // The float tolerance is not loose by an order of magnitude.
  CHECK(worst_float_ratio >= 0.1);
}

TEST_CASE("eval_accumulate projects the basis onto itself: the identity under an exact quadrature", "[sh][eval]") {
  // Weights w_q Y_i(d_q) (Y_i from eval_reference, w_q the product rule's, exact for degree 2 (bands - 1)):
  // the sums are delta_ik.
  for (int bands : {1, 2, 3, 5, 9, 16}) {
    const sh::SphereQuadrature q = sh::gauss_product_quadrature_for_bands(bands, bands);
    std::vector<double> x, y, z;
    for (const glm::dvec3& d : q.directions) {
      x.push_back(d.x);
      y.push_back(d.y);
      z.push_back(d.z);
    }
    for (int i : {0, bands * bands / 2, bands * bands - 1}) {
      const int li = sh::band_of(i), mi = i - li * (li + 1);
      std::vector<double> w;
      for (std::size_t k = 0; k < q.directions.size(); ++k)
        w.push_back(q.weights[k] * sh::eval_reference(li, mi, q.directions[k]));
      std::vector<double> sums(static_cast<std::size_t>(bands * bands), 0.0);
      sh::eval_accumulate(bands, w.size(), x.data(), y.data(), z.data(), w.data(), sums.data());
      for (int k = 0; k < bands * bands; ++k) {
        INFO("bands " << bands << ", i " << i << ", k " << k);
        REQUIRE(std::abs(sums[k] - (k == i ? 1.0 : 0.0)) <= 1e-12);
      }
    }
  }
}

TEST_CASE("Accumulator: many short calls give the reference's weighted basis sums", "[sh][eval]") {
  // The same truth and tolerances as eval_accumulate's test: sums over eval_reference in double. Call sizes
  // around a vector of directions (partial, whole, one and two vectors with a partial one) and empty calls.
  const std::size_t lanes = sh::detail::kLanes<float>;
  const std::vector<std::vector<std::size_t>> call_sets = {
      {1}, {16}, {lanes - 1, 0, lanes + 1, 3, 2 * lanes + 5}, {64, 7}};
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    const double float_tolerance = 1.5e-7 * std::pow(bands, 1.5) + 1e-7;
    const Samples s = random_samples(333, 700 + static_cast<unsigned>(bands));
    for (const std::vector<std::size_t>& calls : call_sets) {
      INFO("bands " << bands << ", first call " << calls[0]);
      g_calls = calls;
      REQUIRE(worst_error<float>(streamed<float>, bands, s, 0.25) <= float_tolerance);
      REQUIRE(worst_error<double>(streamed<double>, bands, s, 0.25) <= 1e-14);
    }
  }
}

TEST_CASE("Accumulator: totals kept across add_to, cleared by clear, the same bits for the same calls", "[sh][eval]") {
  const int bands = 9, n = bands * bands;
  const Samples s = random_samples(100, 5);
  std::vector<float> x, y, z, w;
  for (std::size_t j = 0; j < s.dirs.size(); ++j) {
    x.push_back(static_cast<float>(s.dirs[j].x));
    y.push_back(static_cast<float>(s.dirs[j].y));
    z.push_back(static_cast<float>(s.dirs[j].z));
    w.push_back(static_cast<float>(s.weights[j]));
  }
  auto run = [&](sh::Accumulator<float>& acc) {
    for (std::size_t j = 0; j < x.size(); j += 10) acc.add(10, &x[j], &y[j], &z[j], &w[j]);
  };
  sh::Accumulator<float> a(bands), b(bands);
  run(a);
  run(b);
  std::vector<float> once(n, 0.0f), twice(n, 0.0f), again(n, 0.0f);
  a.add_to(once.data());
  a.add_to(twice.data());
  a.add_to(twice.data());
  b.add_to(again.data());
  for (int k = 0; k < n; ++k) {
    REQUIRE(twice[k] == once[k] + once[k]);  // add_to adds, and leaves the partial sums as they were
    REQUIRE(std::memcmp(&again[k], &once[k], sizeof(float)) == 0);
  }
  // The totals are eval_accumulate's over the same directions, to float rounding of a 100-term sum.
  std::vector<float> direct(n, 0.0f);
  sh::eval_accumulate(bands, x.size(), x.data(), y.data(), z.data(), w.data(), direct.data());
  for (int k = 0; k < n; ++k) REQUIRE(std::abs(once[k] - direct[k]) <= 1e-5f * 100);
  a.clear();
  std::vector<float> cleared(n, 1.0f);
  a.add_to(cleared.data());
  for (int k = 0; k < n; ++k) REQUIRE(cleared[k] == 1.0f);
  sh::Accumulator<float> moved(std::move(b));
  std::vector<float> after_move(n, 0.0f);
  moved.add_to(after_move.data());
  REQUIRE(after_move == once);
}
