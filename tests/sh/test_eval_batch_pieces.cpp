// eval_batch's crowded-stride pieces under each of their rules, on any machine: each test_sh_pieces_* executable
// is built with its own copy of the SH kernels, compiled with PRT_SH_VECTOR_BYTES-wide vectors (GCC splits
// wider ones into the machine's own registers) and the piece rule PRT_SH_PIECE_RULE (eval_batch.cpp: 0
// recomputes the resume state, as on a Xeon with AVX-512; 1 keeps (C, S) from column 4 and deep F, as on
// Zen 5, where from 6 bands column tiles replace the pieces; 2 keeps both from column 2, as with AVX2). The
// main SH tests exercise only the machine's own rule.
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
#include "support/eval_batch_checks.h"
#include "support/random_draws.h"

namespace sh = prt::sh;

namespace {

// The largest |value - reference| over rows and directions of the padded layout, in units of band l's
// magnitude bound.
template <typename T>
double worst_error(int bands, std::size_t count, const prt::test::TwoLayouts<T>& t) {
  double worst = 0.0;
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const std::size_t k = static_cast<std::size_t>(sh::index(l, m));
      for (std::size_t j = 0; j < count; ++j) {
        const glm::dvec3 d(static_cast<double>(t.x[j]), static_cast<double>(t.y[j]), static_cast<double>(t.z[j]));
        const double value = static_cast<double>(t.padded[k * t.padded_stride + j]);
        const double error = std::abs(value - sh::eval_reference(l, m, d));
        worst = std::max(worst, error / prt::test::band_scale(l));
      }
    }
  return worst;
}

}  // namespace

TEST_CASE("crowded strides give the direct path's bits and the reference values under this build's piece rule",
          "[sh][eval]") {
  REQUIRE(sizeof(sh::detail::Vec<float>) == PRT_SH_VECTOR_BYTES);
  std::mt19937_64 rng(11);
  std::vector<glm::dvec3> dirs;
  for (int j = 0; j < 1100; ++j) dirs.push_back(prt::test::random_direction(rng));
  // Counts within one tile and over several (tiles of 2 or 4 KiB of directions), strides of 4 KiB multiples
  // (every row on one cache-set position).
  // Beyond kMaxFastBands (17 and 24 bands) the generic recurrence's column tiles, with this build's vectors.
  std::vector<int> band_counts;
  for (int bands = 1; bands <= sh::kMaxFastBands; ++bands) band_counts.push_back(bands);
  band_counts.push_back(17);
  band_counts.push_back(24);
  for (int bands : band_counts)
    for (std::size_t count : {32, 100, 1024, 1100})
      for (std::size_t crowded : {std::size_t{1024}, std::size_t{2048}}) {
        if (crowded < count) continue;
        INFO("bands " << bands << ", count " << count << ", stride " << crowded);
        const auto f = prt::test::eval_in_two_layouts<float>(bands, count, crowded, dirs);
        CHECK(f.differing_rows == 0);
        CHECK(worst_error(bands, count, f) <= prt::test::float_tolerance(bands));
        const auto d = prt::test::eval_in_two_layouts<double>(bands, count, crowded, dirs);
        CHECK(d.differing_rows == 0);
        CHECK(worst_error(bands, count, d) <= prt::test::kDoubleTolerance);
      }
  // The inputs just below the rows' page offset (the 3-band pieces run backwards) and elsewhere, 1-5 bands.
  for (int bands = 1; bands <= 5; ++bands)
    for (std::size_t count : {100, 1024, 1100})
      for (std::size_t inputs_below : {0, 128, 512, 3968}) {
        INFO("bands " << bands << ", count " << count << ", inputs " << inputs_below << " bytes below the rows");
        const prt::test::Placement placement{16, inputs_below};
        CHECK(prt::test::eval_in_two_layouts<float>(bands, count, 2048, dirs, &placement).differing_rows == 0);
        CHECK(prt::test::eval_in_two_layouts<double>(bands, count, 2048, dirs, &placement).differing_rows == 0);
      }
}
