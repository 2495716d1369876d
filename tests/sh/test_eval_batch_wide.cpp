// eval_batch as AVX-512 builds compile it, on any machine: this test is built with its own copy of the SH
// kernels compiled with 64-byte vectors (PRT_SH_VECTOR_BYTES=64; GCC splits them into the machine's own
// registers). With such vectors the crowded-stride pieces recompute their resume state instead of keeping
// it in L1 (eval_batch.cpp, kRecomputeState), a variant the main SH tests exercise only on AVX-512 machines.
// Checked: the pieces give the direct path's bits, and both the reference values (sh::eval_reference,
// through theta and phi: another algorithm than the kernels' recurrence in z).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "sh/basis.h"
#include "sh/eval_kernels.h"
#include "support/random_draws.h"

namespace sh = prt::sh;

namespace {

// The largest |value - reference| over rows k and directions j, in units of band l's magnitude bound
// sqrt((2l+1)/(4 pi)), and whether padded and crowded layouts agree bit for bit.
struct Outcome {
  double worst = 0.0;
  std::size_t differing_rows = 0;
};

template <typename T>
Outcome run(int bands, std::size_t count, std::size_t crowded, const std::vector<glm::dvec3>& dirs) {
  std::vector<T> x(count), y(count), z(count);
  for (std::size_t j = 0; j < count; ++j) {
    x[j] = static_cast<T>(dirs[j].x);
    y[j] = static_cast<T>(dirs[j].y);
    z[j] = static_cast<T>(dirs[j].z);
  }
  const std::size_t rows = static_cast<std::size_t>(bands * bands), padded = sh::padded_stride(count, sizeof(T));
  std::vector<T> a(rows * crowded), b(rows * padded);
  sh::eval_batch(bands, count, x.data(), y.data(), z.data(), a.data(), crowded);
  sh::eval_batch(bands, count, x.data(), y.data(), z.data(), b.data(), padded);
  Outcome out;
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const std::size_t k = static_cast<std::size_t>(sh::index(l, m));
      out.differing_rows += !std::equal(a.begin() + k * crowded, a.begin() + k * crowded + count, b.begin() + k * padded);
      for (std::size_t j = 0; j < count; ++j) {
        const glm::dvec3 d(static_cast<double>(x[j]), static_cast<double>(y[j]), static_cast<double>(z[j]));
        const double error = std::abs(static_cast<double>(b[k * padded + j]) - sh::eval_reference(l, m, d));
        out.worst = std::max(out.worst, error / std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)));
      }
    }
  return out;
}

}  // namespace

TEST_CASE("64-byte vectors: crowded strides give the direct path's bits and the reference values", "[sh][eval]") {
  REQUIRE(sizeof(sh::detail::Vec<float>) == 64);
  std::mt19937_64 rng(11);
  std::vector<glm::dvec3> dirs;
  for (int j = 0; j < 1100; ++j) dirs.push_back(prt::test::random_direction(rng));
  // Counts within one tile and over several (tiles of 4 KiB of directions with these vectors), strides of
  // 4 KiB multiples (every row on one cache-set position).
  for (int bands = 1; bands <= sh::kMaxFastBands; ++bands)
    for (std::size_t count : {32, 100, 1024, 1100})
      for (std::size_t crowded : {std::size_t{1024}, std::size_t{2048}}) {
        if (crowded < count) continue;
        INFO("bands " << bands << ", count " << count << ", stride " << crowded);
        const Outcome f = run<float>(bands, count, crowded, dirs);
        CHECK(f.differing_rows == 0);
        // The documented float accuracy, 1.5e-7 x bands^1.5, with the float inputs' own rounding included.
        CHECK(f.worst <= 1.5e-7 * std::pow(bands, 1.5));
        const Outcome d = run<double>(bands, count, crowded, dirs);
        CHECK(d.differing_rows == 0);
        CHECK(d.worst <= 1e-12);
      }
}
