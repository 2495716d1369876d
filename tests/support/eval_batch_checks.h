// What the eval_batch tests share: the documented tolerances, and one batch evaluated in a crowded and in the
// padded layout. Used by test_eval_batch.cpp (the kernels as this machine builds them) and
// test_eval_batch_pieces.cpp (the kernels built once per crowded-stride piece rule).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
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

// The first `count` directions as a structure of arrays of T (x, y, z), and eval_batch's values for them with
// out_stride = crowded and with sh::padded_stride, and how many of the bands^2 rows differ in any bit. Without
// a Placement the inputs and the crowded rows lie where std::vector puts them.
template <typename T>
struct TwoLayouts {
  TwoLayouts() = default;
  TwoLayouts(const TwoLayouts&) = delete;  // x, y, z and crowded point into the storages
  TwoLayouts(TwoLayouts&&) = default;
  std::vector<T> input_storage, crowded_storage;
  const T *x = nullptr, *y = nullptr, *z = nullptr;
  std::size_t crowded_stride = 0, padded_stride = 0;
  const T* crowded = nullptr;
  std::vector<T> padded;
  std::size_t differing_rows = 0;
};

// Where eval_in_two_layouts puts the crowded rows and the inputs: the rows `rows_offset` bytes past a page
// boundary, x, y and z each at a page offset `inputs_below` bytes below the rows' (inputs just below the rows
// make the crowded path's pieces run their blocks backwards at 3 bands, eval_batch.cpp). Both multiples of
// sizeof(T), rows_offset below 4096 and inputs_below at most 4096.
struct Placement {
  std::size_t rows_offset = 0;
  std::size_t inputs_below = 0;
};

// The first element of `storage` at or after its start whose address is a multiple of 4 KiB.
template <typename T>
T* page_start(std::vector<T>& storage) {
  constexpr std::size_t page = 4096;
  const std::size_t misalign = reinterpret_cast<std::uintptr_t>(storage.data()) % page;
  return storage.data() + (misalign == 0 ? 0 : (page - misalign) / sizeof(T));
}

template <typename T>
TwoLayouts<T> eval_in_two_layouts(int bands, std::size_t count, std::size_t crowded_stride,
                                  const std::vector<glm::dvec3>& dirs, const Placement* placement = nullptr) {
  constexpr std::size_t page = 4096 / sizeof(T);
  TwoLayouts<T> t;
  const std::size_t span = (count + 2 * page - 1) / page * page;
  t.input_storage.resize(3 * span + 2 * page);
  T* x = t.input_storage.data();
  if (placement)
    x = page_start(t.input_storage) + (4096 + placement->rows_offset - placement->inputs_below) / sizeof(T);
  T *y = x + span, *z = y + span;
  for (std::size_t j = 0; j < count; ++j) {
    x[j] = static_cast<T>(dirs[j].x);
    y[j] = static_cast<T>(dirs[j].y);
    z[j] = static_cast<T>(dirs[j].z);
  }
  t.x = x;
  t.y = y;
  t.z = z;
  const std::size_t rows = static_cast<std::size_t>(bands * bands);
  t.crowded_stride = crowded_stride;
  t.padded_stride = sh::padded_stride(count, sizeof(T));
  t.crowded_storage.resize(rows * t.crowded_stride + 2 * page);
  T* crowded = t.crowded_storage.data();
  if (placement) crowded = page_start(t.crowded_storage) + placement->rows_offset / sizeof(T);
  t.crowded = crowded;
  t.padded.resize(rows * t.padded_stride);
  sh::eval_batch(bands, count, x, y, z, crowded, t.crowded_stride);
  sh::eval_batch(bands, count, x, y, z, t.padded.data(), t.padded_stride);
  for (std::size_t k = 0; k < rows; ++k) {
    const T* crowded_row = crowded + k * t.crowded_stride;
    t.differing_rows += !std::equal(crowded_row, crowded_row + count,
                                    t.padded.begin() + static_cast<std::ptrdiff_t>(k * t.padded_stride));
  }
  return t;
}

}  // namespace prt::test
