// The fast SH evaluation paths (sh::eval for one direction, sh::eval_batch over a structure of arrays,
// float and double, the unrolled kernels up to kMaxFastBands and the generic recurrence beyond)
// against the slow reference sh::eval_reference, and orthonormality of the evaluated basis by an exact
// quadrature built here (Gauss-Legendre in z by Newton's method on P_n, times uniform phi).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/basis.h"
#include "sh/eval_kernels.h"

namespace sh = prt::sh;

namespace {

// Tolerances, as a multiple of band l's magnitude bound sqrt((2l+1)/(4 pi)) >= |Y_lm|.
// Double: rounding of the recurrence (a few ulp per step, over at most 31 steps).
constexpr double kDoubleTolerance = 1e-12;
// Float: the recurrence in float plus the input's own rounding (a float direction is unit only to
// ~6e-8). The error grows as bands^1.5: the worst over 130 000 random directions (GCC 12 with FMA,
// clang 14 without) was 5.2e-8 (1 band), 1.6e-6 (9), 5.0e-6 (16), 1.6e-5 (32), <= 9.4e-8 bands^1.5.
// (A bound linear in the band count, 3e-7 bands, held for the directions drawn here by GCC's build and
// failed for those of clang's, which drew a direction's coordinates in the other order.)
double float_tolerance(int bands) { return 1.5e-7 * std::pow(bands, 1.5); }

double band_scale(int l) { return std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)); }

// The poles, the axes, a few points on the equator and on coordinate planes, then random unit directions.
std::vector<glm::dvec3> test_directions(std::size_t random_count) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  // (Not points a hair off the poles: eval_reference goes through theta = acos(z), which loses about
  // half the digits there. The fast paths have no special case at the poles: their values are
  // polynomials in x, y, z.)
  std::vector<glm::dvec3> dirs = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},     {-1, 0, 0},      {0, 1, 0},
                                  {0, -1, 0}, {0.6, 0.8, 0}, {-0.8, 0, 0.6}, {0, 0.28, -0.96}, {-0.6, -0.8, 0}};
  while (dirs.size() < random_count + 10) {
    // One draw per statement: the order of a constructor's arguments is unspecified (GCC and clang differ).
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    dirs.push_back(glm::normalize(glm::dvec3(x, y, z)));
  }
  return dirs;
}

// Reference values ref[k * count + j] = Y_k(dirs[j]) for k < bands^2.
std::vector<double> reference_values(int bands, const std::vector<glm::dvec3>& dirs) {
  std::vector<double> ref(static_cast<std::size_t>(bands * bands) * dirs.size());
  for (std::size_t j = 0; j < dirs.size(); ++j)
    for (int l = 0; l < bands; ++l)
      for (int m = -l; m <= l; ++m) ref[sh::index(l, m) * dirs.size() + j] = sh::eval_reference(l, m, dirs[j]);
  return ref;
}

struct ErrorStats {
  double worst = 0;  // max over checked values of |value - ref| / band_scale(l)
  void add(double value, double ref, int l) {
    double e = std::abs(value - ref) / band_scale(l);
    worst = std::isnan(e) ? std::numeric_limits<double>::infinity() : std::max(worst, e);
  }
};

// Runs a batched path on the first `count` directions with out_stride = count + pad (or `stride` if
// given), `offset` elements past a 64-byte boundary; checks every value against the reference and that
// the padding between rows is untouched.
template <typename T, typename BatchFn>
ErrorStats check_batched(BatchFn batch, int bands, std::size_t count, std::size_t pad, const std::vector<glm::dvec3>& dirs,
                         const std::vector<double>& ref, bool& padding_intact, std::size_t offset = 0,
                         std::size_t stride = 0) {
  std::vector<T> x(count), y(count), z(count);
  for (std::size_t j = 0; j < count; ++j) {
    x[j] = static_cast<T>(dirs[j].x);
    y[j] = static_cast<T>(dirs[j].y);
    z[j] = static_cast<T>(dirs[j].z);
  }
  if (stride == 0) stride = count + pad;
  const T sentinel = T(-12345);
  std::vector<T> storage(static_cast<std::size_t>(bands * bands) * stride + 1 + 64, sentinel);
  T* out = storage.data();
  while (reinterpret_cast<std::uintptr_t>(out) % 64 != 0) ++out;
  out += offset;
  batch(bands, count, x.data(), y.data(), z.data(), out, stride);
  ErrorStats stats;
  padding_intact = out[bands * bands * stride] == sentinel && std::all_of(storage.data(), out, [&](T v) { return v == sentinel; });
  for (int k = 0; k < bands * bands; ++k) {
    for (std::size_t j = 0; j < count; ++j) stats.add(out[k * stride + j], ref[k * dirs.size() + j], sh::band_of(k));
    for (std::size_t j = count; j < stride; ++j) padding_intact = padding_intact && out[k * stride + j] == sentinel;
  }
  return stats;
}

template <typename T>
std::vector<std::size_t> batch_counts() {
  const std::size_t w = sh::detail::kLanes<T>;
  return {0, 1, 2, w - 1, w, w + 1, 2 * w + 3, 5 * w - 1, 37, 70};
}

// The float paths see the direction rounded to float; their reference is taken at that rounded
// direction (normalised by eval_reference).
std::vector<glm::dvec3> rounded_to_float(const std::vector<glm::dvec3>& dirs) {
  std::vector<glm::dvec3> out;
  for (const auto& d : dirs) out.emplace_back(glm::vec3(d));
  return out;
}

void eval_batch_fast_float(int b, std::size_t n, const float* x, const float* y, const float* z, float* o, std::size_t s) {
  sh::eval_batch(b, n, x, y, z, o, s);
}
void eval_batch_fast_double(int b, std::size_t n, const double* x, const double* y, const double* z, double* o,
                            std::size_t s) {
  sh::eval_batch(b, n, x, y, z, o, s);
}
void eval_batch_generic_float(int b, std::size_t n, const float* x, const float* y, const float* z, float* o,
                              std::size_t s) {
  sh::detail::eval_batch_generic(b, n, x, y, z, o, s);
}
void eval_batch_generic_double(int b, std::size_t n, const double* x, const double* y, const double* z, double* o,
                               std::size_t s) {
  sh::detail::eval_batch_generic(b, n, x, y, z, o, s);
}

// Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on P_n (independent of
// sh::gauss_legendre, which a later test can compare against this one).
void gauss_legendre_newton(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(n, 0.0);
  weights.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double t = std::cos(M_PI * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess, descending
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = t;  // P_0, P_1, then P_k by Bonnet's recurrence
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);  // P_n'
      double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes[n - 1 - i] = t;
    weights[n - 1 - i] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
}

}  // namespace

TEST_CASE("own Gauss-Legendre rule integrates monomials exactly", "[sh][eval]") {
  for (int n : {1, 2, 5, 16, 17}) {
    std::vector<double> nodes, weights;
    gauss_legendre_newton(n, nodes, weights);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += weights[i] * std::pow(nodes[i], p);
      double exact = (p % 2 == 1) ? 0.0 : 2.0 / (p + 1);
      REQUIRE(std::abs(sum - exact) <= 1e-14);
    }
  }
}

TEST_CASE("recurrence constants match their closed forms", "[sh][eval]") {
  const auto& r = sh::detail::kRecurrence;
  for (double v : {2.0, 3.0, 0.5, 1e-3, 63.0 / (4.0 * M_PI), 4095.0 / 3.0})
    REQUIRE(sh::detail::constexpr_sqrt(v) == Approx(std::sqrt(v)).epsilon(2.3e-16));
  for (int m = 0; m < sh::kMaxBands; ++m) {
    // F_m^m = sqrt(2) K_mm (-1)^m (2m-1)!! (no sqrt(2) for m = 0) equals Y_m,m at +x, where C_m = 1.
    double expect = sh::eval_reference(m, m, {1, 0, 0});
    REQUIRE(r.f_mm[m] == Approx(expect).epsilon(1e-14));
    REQUIRE(r.f_m1[m] == Approx(std::sqrt(2.0 * m + 3.0) * r.f_mm[m]).epsilon(1e-15));
  }
}

TEST_CASE("double paths match the reference to 1e-12 of each band's magnitude", "[sh][eval]") {
  const auto dirs = test_directions(90);
  const auto ref = reference_values(sh::kMaxBands, dirs);
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    INFO("bands " << bands);
    // Reference rows for this band count: the first bands^2 rows of the 32-band table.
    for (std::size_t count : batch_counts<double>()) {
      INFO("count " << count);
      bool intact = false;
      ErrorStats fast = check_batched<double>(eval_batch_fast_double, bands, count, 3, dirs, ref, intact);
      REQUIRE(intact);
      REQUIRE(fast.worst <= kDoubleTolerance);
      fast = check_batched<double>(eval_batch_fast_double, bands, count, 8, dirs, ref, intact, 3);  // unaligned
      REQUIRE(intact);
      REQUIRE(fast.worst <= kDoubleTolerance);
      ErrorStats generic = check_batched<double>(eval_batch_generic_double, bands, count, 0, dirs, ref, intact);
      REQUIRE(intact);
      REQUIRE(generic.worst <= kDoubleTolerance);
    }
    ErrorStats single, single_generic;
    std::vector<double> out(bands * bands);
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      sh::eval(bands, dirs[j], out.data());
      for (int k = 0; k < bands * bands; ++k) single.add(out[k], ref[k * dirs.size() + j], sh::band_of(k));
      sh::detail::eval_one_generic(bands, dirs[j].x, dirs[j].y, dirs[j].z, out.data());
      for (int k = 0; k < bands * bands; ++k) single_generic.add(out[k], ref[k * dirs.size() + j], sh::band_of(k));
    }
    REQUIRE(single.worst <= kDoubleTolerance);
    REQUIRE(single_generic.worst <= kDoubleTolerance);
  }
}

TEST_CASE("float paths match the reference to float precision", "[sh][eval]") {
  const auto dirs = rounded_to_float(test_directions(90));
  const auto ref = reference_values(sh::kMaxBands, dirs);
  double worst_ratio = 0;  // max over band counts of worst error / tolerance
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    INFO("bands " << bands);
    const double tolerance = float_tolerance(bands);
    for (std::size_t count : batch_counts<float>()) {
      INFO("count " << count);
      bool intact = false;
      ErrorStats fast = check_batched<float>(eval_batch_fast_float, bands, count, 5, dirs, ref, intact);
      REQUIRE(intact);
      REQUIRE(fast.worst <= tolerance);
      fast = check_batched<float>(eval_batch_fast_float, bands, count, 16, dirs, ref, intact, 7);  // unaligned
      REQUIRE(intact);
      REQUIRE(fast.worst <= tolerance);
      ErrorStats generic = check_batched<float>(eval_batch_generic_float, bands, count, 1, dirs, ref, intact);
      REQUIRE(intact);
      REQUIRE(generic.worst <= tolerance);
      worst_ratio = std::max({worst_ratio, fast.worst / tolerance, generic.worst / tolerance});
    }
    ErrorStats single, single_generic;
    std::vector<float> out(bands * bands);
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      glm::vec3 d(dirs[j]);
      sh::eval(bands, d, out.data());
      for (int k = 0; k < bands * bands; ++k) single.add(out[k], ref[k * dirs.size() + j], sh::band_of(k));
      sh::detail::eval_one_generic(bands, d.x, d.y, d.z, out.data());
      for (int k = 0; k < bands * bands; ++k) single_generic.add(out[k], ref[k * dirs.size() + j], sh::band_of(k));
    }
    REQUIRE(single.worst <= tolerance);
    REQUIRE(single_generic.worst <= tolerance);
  }
  // The stated tolerance is not loose by an order of magnitude.
  CHECK(worst_ratio >= 0.1);
}

TEST_CASE("any stride >= count gives the reference values, crowded ones too", "[sh][eval]") {
  // eval_batch has one path for every stride: padded_stride is its fast layout, and strides whose rows share
  // cache sets (multiples of 4 KiB: 1024 floats, 512 doubles; 128 and 256 elements) are slower but must
  // write the same values, each to its own row. Counts below one vector (the scalar path), around one and
  // several blocks, and large ones; out 64-byte aligned or not (offset 1). Directions repeat with a period
  // of 1009 (prime): a misplaced vector still shows, and the float tolerance stays the kernel's.
  auto base = test_directions(999);
  std::vector<glm::dvec3> dirs;
  for (std::size_t j = 0; j < 2500; ++j) dirs.push_back(base[j % base.size()]);
  const auto dirs_f = rounded_to_float(dirs);
  struct Case {
    std::size_t count, stride_f, stride_d;
  };
  const std::size_t lanes = sh::detail::kLanes<float>;
  const Case small[] = {{lanes - 1, 1024, 512}, {127, 128, 256}, {129, 256, 512}, {310, 1024, 512}};
  const Case large[] = {{512, 1024, 512}, {1024, 1024, 1024}, {1100, 2048, 1536}, {2500, 3072, 2560}};
  for (bool is_large : {false, true}) {
    // References for the band counts each group checks (the 32-band table of 2500 directions would take long).
    const int most_bands = is_large ? sh::kMaxFastBands : sh::kMaxBands;
    const auto ref = reference_values(most_bands, dirs);
    const auto ref_f = reference_values(most_bands, dirs_f);
    for (const Case& c : is_large ? large : small) {
      for (int bands : {2, 3, 9, 16, 17, 32}) {
        if (bands > most_bands) continue;
        for (std::size_t offset : {0, 1}) {
          INFO("bands " << bands << ", count " << c.count << ", offset " << offset);
          bool intact = false;
          ErrorStats f = check_batched<float>(eval_batch_fast_float, bands, c.count, 0, dirs_f, ref_f, intact, offset,
                                              c.stride_f);
          REQUIRE(intact);
          REQUIRE(f.worst <= float_tolerance(bands));
          ErrorStats d = check_batched<double>(eval_batch_fast_double, bands, c.count, 0, dirs, ref, intact, offset,
                                               c.stride_d);
          REQUIRE(intact);
          REQUIRE(d.worst <= kDoubleTolerance);
        }
      }
    }
  }
}

TEST_CASE("padded_stride is a nearby odd number of cache lines", "[sh][eval]") {
  for (std::size_t count : {0, 1, 15, 16, 17, 100, 1024, 4096, 4097}) {
    for (std::size_t bytes : {sizeof(float), sizeof(double)}) {
      const std::size_t stride = sh::padded_stride(count, bytes), per_line = 64 / bytes;
      INFO("count " << count << ", element bytes " << bytes);
      REQUIRE(stride >= count);
      REQUIRE(stride <= count + 2 * per_line);
      REQUIRE(stride % per_line == 0);
      REQUIRE((stride / per_line) % 2 == 1);
    }
  }
}

TEST_CASE("batched and single-direction paths agree on one direction", "[sh][eval]") {
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  for (int bands : {1, 3, 9, 16, 17, 32}) {
    std::vector<double> single(bands * bands), batched(bands * bands);
    sh::eval(bands, d, single.data());
    sh::eval_batch(bands, 1, &d.x, &d.y, &d.z, batched.data(), 1);
    for (int k = 0; k < bands * bands; ++k) REQUIRE(batched[k] == Approx(single[k]).margin(1e-14));
  }
}

TEST_CASE("the evaluated basis is orthonormal under an exact product quadrature", "[sh][eval]") {
  for (int bands = 1; bands <= sh::kMaxFastBands; ++bands) {
    // Y_i Y_j integrated over phi leaves a polynomial in z of degree <= 2 (bands - 1) once m_i = m_j
    // (the uniform phi rule with 2 bands - 1 points makes the other products vanish exactly), so
    // `bands` Gauss-Legendre nodes in z suffice.
    const int nz = bands, nphi = 2 * bands - 1;
    std::vector<double> nodes, weights;
    gauss_legendre_newton(nz, nodes, weights);
    std::vector<double> x, y, z, w;
    for (int a = 0; a < nz; ++a)
      for (int b = 0; b < nphi; ++b) {
        double phi = 2.0 * M_PI * b / nphi, s = std::sqrt(1.0 - nodes[a] * nodes[a]);
        x.push_back(s * std::cos(phi));
        y.push_back(s * std::sin(phi));
        z.push_back(nodes[a]);
        w.push_back(weights[a] * 2.0 * M_PI / nphi);
      }
    const std::size_t q = w.size();
    const int n = bands * bands;
    std::vector<double> values(static_cast<std::size_t>(n) * q);
    sh::eval_batch(bands, q, x.data(), y.data(), z.data(), values.data(), q);
    double worst = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        double g = 0;
        for (std::size_t k = 0; k < q; ++k) g += w[k] * values[i * q + k] * values[j * q + k];
        worst = std::max(worst, std::abs(g - (i == j ? 1.0 : 0.0)));
      }
    INFO("bands " << bands);
    REQUIRE(worst <= 1e-12);
  }
}
