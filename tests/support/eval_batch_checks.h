// What the eval_batch tests share: the documented tolerances, and one batch evaluated in a crowded and in the
// padded layout. Used by test_eval_batch.cpp (the kernels as this machine builds them) and
// test_eval_batch_pieces.cpp (the kernels built once per crowded-stride piece rule).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "sh/basis.h"

namespace prt::test {

// Tolerances, as a multiple of band l's magnitude bound sqrt((2l+1)/(4 pi)) >= |Y_lm|.
// Double: rounding of the recurrence (a few ulp per step, over at most 31 steps).
constexpr double kDoubleTolerance = 1e-12;
// Float: the recurrence in float plus the input's own rounding (a float direction is unit only to
// ~6e-8). The error grows as bands^1.5: the worst over 130 000 random directions (GCC 12 with FMA,
// clang 14 without) was 5.2e-8 (1 band), 1.6e-6 (9), 5.0e-6 (16), 1.6e-5 (32), <= 9.4e-8 bands^1.5.
// (A bound linear in the band count, 3e-7 bands, held for the directions drawn here by GCC's build and
// failed for those of clang's, which drew a direction's coordinates in the other order.)
inline double float_tolerance(int bands) { return 1.5e-7 * std::pow(bands, 1.5); }

inline double band_scale(int l) { return std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)); }

// The first `count` directions as a structure of arrays of T, and eval_batch's values for them with
// out_stride = crowded and with sh::padded_stride, and how many of the bands^2 rows differ in any bit.
template <typename T>
struct TwoLayouts {
  std::vector<T> x, y, z;
  std::size_t crowded_stride = 0, padded_stride = 0;
  std::vector<T> crowded, padded;
  std::size_t differing_rows = 0;
};

template <typename T>
TwoLayouts<T> eval_in_two_layouts(int bands, std::size_t count, std::size_t crowded_stride,
                                  const std::vector<glm::dvec3>& dirs) {
  TwoLayouts<T> t;
  for (std::size_t j = 0; j < count; ++j) {
    t.x.push_back(static_cast<T>(dirs[j].x));
    t.y.push_back(static_cast<T>(dirs[j].y));
    t.z.push_back(static_cast<T>(dirs[j].z));
  }
  const std::size_t rows = static_cast<std::size_t>(bands * bands);
  t.crowded_stride = crowded_stride;
  t.padded_stride = sh::padded_stride(count, sizeof(T));
  t.crowded.resize(rows * t.crowded_stride);
  t.padded.resize(rows * t.padded_stride);
  sh::eval_batch(bands, count, t.x.data(), t.y.data(), t.z.data(), t.crowded.data(), t.crowded_stride);
  sh::eval_batch(bands, count, t.x.data(), t.y.data(), t.z.data(), t.padded.data(), t.padded_stride);
  for (std::size_t k = 0; k < rows; ++k) {
    const auto crowded_row = t.crowded.begin() + static_cast<std::ptrdiff_t>(k * t.crowded_stride);
    t.differing_rows += !std::equal(crowded_row, crowded_row + static_cast<std::ptrdiff_t>(count),
                                    t.padded.begin() + static_cast<std::ptrdiff_t>(k * t.padded_stride));
  }
  return t;
}

}  // namespace prt::test
