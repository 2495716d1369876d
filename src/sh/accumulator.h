#pragma once
// sh::Accumulator: the weighted basis sums of sh::eval_accumulate, built from many short calls.
#include <cstddef>
#include <memory>

namespace prt::sh {

/// Projection sums sum_j w_j Y_k(d_j) (k < bands^2) over directions handed in by many calls of any
/// size. sh::eval_accumulate reduces its per-lane partial sums to bands^2 totals at the end of every
/// call, which at a few dozen directions per call costs as much as the evaluation; an Accumulator keeps
/// the partial sums (bands^2 vectors of the SIMD width, in the object) between calls and reduces them
/// once, in add_to. Use it where directions arrive in small batches (a sampler's rays per step); for
/// one large array eval_accumulate is the same speed.
///
/// Values: the same recurrence as eval_accumulate, with the same accuracy (docs/conventions.md,
/// Evaluation). Which lane a direction lands in depends on how the directions are split into calls,
/// so the totals' last bits do too: the same sequence of calls gives the same bits.
/// T is float or double. Not thread-safe; use one per thread and add their totals in a fixed order. A
/// moved-from Accumulator may only be assigned to or destroyed.
template <typename T>
class Accumulator {
 public:
  /// Precondition: 1 <= bands <= kMaxBands (sh/coefficients.h). Starts at zero.
  explicit Accumulator(int bands);
  ~Accumulator();
  Accumulator(Accumulator&&) noexcept;
  Accumulator& operator=(Accumulator&&) noexcept;
  Accumulator(const Accumulator&) = delete;
  Accumulator& operator=(const Accumulator&) = delete;

  int bands() const { return bands_; }

  /// Adds w[j] Y_k(x[j], y[j], z[j]) for j < count to the partial sums. Preconditions: unit directions
  /// (as eval_accumulate); the arrays hold count values each. count = 0 does nothing.
  void add(std::size_t count, const T* x, const T* y, const T* z, const T* w) { add_(count, x, y, z, w, lanes_); }

  /// sums[k] += the total for k < bands^2 (sums is added to, not cleared; it holds bands^2 values).
  /// The partial sums are kept: add_to may be called again after more add calls.
  void add_to(T* sums) const;

  /// Back to zero, keeping the band count.
  void clear();

 private:
  // The band count's kernel, chosen at construction rather than per call: a call of 16 directions at 3
  // bands takes about 7 ns, in which a dispatch shows.
  using AddFunction = void (*)(std::size_t, const T*, const T*, const T*, const T*, T*);

  int bands_ = 0;
  std::unique_ptr<unsigned char[]> storage_;  // bands^2 partial-sum vectors, plus alignment slack
  T* lanes_ = nullptr;                        // the partial sums: the 64-byte aligned start within storage_
  AddFunction add_ = nullptr;
};

extern template class Accumulator<float>;
extern template class Accumulator<double>;

}  // namespace prt::sh
