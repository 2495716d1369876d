// Batched SH evaluation over a structure of arrays of directions: the kernels of eval_kernels.h
// applied to one block of directions at a time (kBlockLanes<T> per kernel call: a vector, or two where a
// vector is shorter than a cache line).
//
// Memory layout matters as much as arithmetic here. Every kernel call stores one vector into each of
// the bands^2 output rows, rows out_stride apart. When out_stride * sizeof(T) is a multiple of 4 KiB
// (count = 1024 or 4096 with out_stride = count, the natural choice), all those stores fall into the
// same L1 cache set, a burst of bands^2 lines into one set of 8-12 ways: 2-3.5x slower than with a good
// stride, measured (Zen 3, Xeon). Such strides take a path that writes the same bytes in another order
// (batch_pieces: a few rows at a time along long runs of directions; batch_columns: one row at a time
// along short tiles); padded_stride() gives a stride that needs none of it.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <type_traits>
#include <utility>

#include "sh/basis.h"
#include "sh/eval_kernels.h"

namespace prt::sh {
namespace detail {
namespace {

// Stores coefficient k of one block of directions into out[k * stride + j ...].
template <typename T>
struct StridedStore {
  T* out;
  std::size_t stride;
  template <typename V>
  PRT_SH_INLINE void operator()(int k, V value) const {
    store(out + static_cast<std::size_t>(k) * stride, value);
  }
};

constexpr std::size_t kCacheLine = 64;
constexpr std::size_t kPage = 4096;  // L1 data caches of x86 (and most others) index sets within 4 KiB

// What one kernel call evaluates: one vector of directions, or two (a Pair, eval_kernels.h) where a vector is
// shorter than a cache line, so that every store fills a whole line of its row. Half-line stores into
// bands^2 rows cost 1.4x whole-line ones in a plain fill (Zen 3, AVX2, 81 rows, padded stride).
template <typename T>
using Block = std::conditional_t<(sizeof(Vec<T>) < kCacheLine), Pair<Vec<T>>, Vec<T>>;
template <typename T>
inline constexpr std::size_t kBlockLanes = sizeof(Block<T>) / sizeof(T);

// True when `rows` rows out_stride apart crowd into few cache sets, so that one vector of directions stored
// into every row is a burst of lines into one set. The row starts fall on `positions` distinct 64-byte set
// positions of a 4 KiB page (a power of two: 4 KiB over the largest power of two dividing the stride's
// bytes, at least a line). Crowded: more than 4 rows per position when they fall on 1 or 2 positions (Zen 3,
// 8-way L1: 9 rows on one position, stride = count = 1024 floats, 3.5x the padded figure; Xeon, 12-way:
// 9 rows 1.3x), or more than 12 per position on more (Xeon: 16 bands at stride 512 bytes, 32 rows per
// position, 1.4x; 9 bands there, 10 per position, as fast as padded; Zen 5, 12-way: stride = count = 256
// floats, 4 positions, 8 bands (16 rows per position) 1.5-2.2x the padded batch on the direct path, 1.05x on
// the crowded one, while at 6 bands (9 per position) the direct path is the faster).
template <typename T>
bool rows_share_cache_sets(int rows, std::size_t stride) {
  const std::size_t offset = (stride * sizeof(T)) % kPage;
  const std::size_t step = offset == 0 ? kPage : offset & (~offset + 1);  // lowest set bit
  const std::size_t positions = kPage / (step > kCacheLine ? step : kCacheLine);
  const std::size_t per_position = positions <= 2 ? 4 : 12;
  return static_cast<std::size_t>(rows) > per_position * positions;
}

// Directions to skip so that out + j is `alignment`-byte aligned (0 if out is not even T-aligned).
template <typename T>
std::size_t alignment_peel(const T* out, std::size_t alignment) {
  std::size_t misalign = reinterpret_cast<std::uintptr_t>(out) % alignment;
  if (misalign == 0 || misalign % sizeof(T) != 0) return 0;
  return (alignment - misalign) / sizeof(T);
}

// Calls block(j) for starts j of blocks of `width` directions covering [0, count), count >= width:
// j = 0, then peel (if 0 < peel < width), peel + width, ... (aligned stores from there on), each
// clamped to count - width so the last block ends exactly at count. Overlapping blocks recompute a
// few directions, with identical results (the output never aliases the input). `block` has one call
// site, so it is inlined once.
template <typename Block>
PRT_SH_INLINE void for_each_block(std::size_t count, std::size_t width, std::size_t peel, Block&& block) {
  const std::size_t last = count - width;
  std::size_t j = 0;
  std::size_t next = peel > 0 && peel < width ? peel : width;
  for (;;) {
    block(j);
    if (j >= last) break;
    j = next < last ? next : last;
    next += width;
  }
}

// for_each_block's blocks, the same starts, from the last down to 0.
template <typename Block>
PRT_SH_INLINE void for_each_block_backwards(std::size_t count, std::size_t width, std::size_t peel, Block&& block) {
  const std::size_t last = count - width;
  const std::size_t second = peel > 0 && peel < width ? peel : width;
  if (last > 0) {
    block(last);
    // The starts second + i * width below last, highest first.
    for (std::size_t i = last > second ? (last - second - 1) / width + 1 : 0; i-- > 0;) block(second + i * width);
  }
  block(0);
}

// Crowded strides, the column-step path. A tile of kColumnTileBytes of consecutive directions is evaluated
// one step (l, m) after another across the whole tile, with each block's state ((C_m, S_m) and the column's
// last two F) kept in arrays between steps, so that the stores run along one row at a time (the tile's
// lines of Y_l,m, then those of Y_l,-m) instead of down the crowded column of rows. The arithmetic is that of
// the direct path it stands in for, in the same order, on the same value type V: eval_generic's
// (kFixedForm false, V = Vec<T>) or eval_fixed's (kFixedForm true, V = Block<T>), whose step l = m + 2 is a
// polynomial in z^2 (column_value): the direct path's bits either way.
// Measured on Zen 5 (AVX-512, 1024 directions, stride = count, paired against the padded direct path;
// bench_sh_eval 'inputs placed'): 0.73-1.05x at 6-16 bands (PieceRule::columns_bands), 0.86-1.14x at 17-32
// bands (their 1.2-4 MiB of output beyond the 1 MiB L2; 0.62-0.84x with 256 directions, in L2), where staging
// the tile in an L1 scratch block and copying its rows out took 2x; two rows at a time (Y_l,m and Y_l,-m per
// block) 1.0-1.25x; tiles of 256 or 384 bytes 1.2-3.6x and of 640 bytes to 4 KiB 1.1-1.9x (the state no
// longer fits the registers: every spilled store queues behind the output's missing ones; 768 and 1024 bytes
// with x, y, z, C and S reloaded from L1 at each step, so that only F stays in registers, 1.0-1.56x). Also
// slower at 20-28 bands: prefetching the rows 1, 2 or 4 steps ahead (1.0-1.66x), the columns outermost over up to 16
// tiles with (C, S) kept in L1 (1.07-1.24x), runs of whole rows a few at a time with F and (C, S) kept in L1
// (the pieces' order for the generic recurrence: 1.45-2.4x), and the direct path (10-15x). The tile's state in a
// scratch placed 768-1024 bytes past the tile's page offset, clear of its pending stores: unchanged at 26 and 30
// bands (over the tile's offsets: 1.1x).
constexpr std::size_t kColumnTileBytes = 512;

template <typename T, typename V, bool kFixedForm>
PRT_SH_INLINE void column_tile(int bands, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  constexpr std::size_t lanes = sizeof(V) / sizeof(T), blocks = kColumnTileBytes / sizeof(V);
  const RecurrenceTables& r = kRecurrence;
  V vx[blocks], vy[blocks], vz[blocks], c[blocks] = {}, s[blocks] = {}, f1[blocks] = {}, f2[blocks] = {};
  for (std::size_t b = 0; b < blocks; ++b) {
    vx[b] = load<V>(x + b * lanes);
    vy[b] = load<V>(y + b * lanes);
    vz[b] = load<V>(z + b * lanes);
  }
  int m = 0;
  // Step (l, m) across the tile: F_l^m = value(b) per block, then the tile's lines of Y_l,m and Y_l,-m.
  auto step = [&](int l, auto&& value) PRT_SH_LAMBDA_INLINE {
    T* const plus = out + static_cast<std::size_t>(index(l, m)) * stride;
    for (std::size_t b = 0; b < blocks; ++b) {
      const V f = value(b);
      f2[b] = f1[b];
      f1[b] = f;
      store(plus + b * lanes, m == 0 ? f : f * c[b]);
    }
    if (m == 0) return;
    T* const minus = out + static_cast<std::size_t>(index(l, -m)) * stride;
    for (std::size_t b = 0; b < blocks; ++b) store(minus + b * lanes, f1[b] * s[b]);
  };
  for (; m < bands; ++m) {
    if (m == 1) {
      std::copy(vx, vx + blocks, c);
      std::copy(vy, vy + blocks, s);
    } else if (m > 1) {
      for (std::size_t b = 0; b < blocks; ++b) advance_cs(vx[b], vy[b], c[b], s[b]);
    }
    const T f_mm = static_cast<T>(r.f_mm[m]), f_m1 = static_cast<T>(r.f_m1[m]);
    step(m, [&](std::size_t) PRT_SH_LAMBDA_INLINE { return splat<V>(f_mm); });
    if (m + 1 < bands) step(m + 1, [&](std::size_t b) PRT_SH_LAMBDA_INLINE { return f_m1 * vz[b]; });
    int l = m + 2;
    if (kFixedForm && l < bands) {
      // column_value's F_{m+2}^m = p2 z^2 + p0, its constants rounded from the same double products.
      const T p2 = static_cast<T>(r.a[l][m] * r.f_m1[m]), p0 = static_cast<T>(r.b[l][m] * r.f_mm[m]);
      step(l++, [&](std::size_t b) PRT_SH_LAMBDA_INLINE { return z2_polynomial(p2, vz[b] * vz[b], p0); });
    }
    for (; l < bands; ++l) {
      const T a = static_cast<T>(r.a[l][m]), bl = static_cast<T>(r.b[l][m]);
      step(l, [&](std::size_t b) PRT_SH_LAMBDA_INLINE { return recurrence_step(a, bl, vz[b], f1[b], f2[b]); });
    }
  }
}

// eval_batch for crowded strides through column_tile, count >= the tile, tile by tile.
template <typename T, typename V, bool kFixedForm>
PRT_SH_INLINE void batch_columns(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out,
                                 std::size_t stride) {
  const std::size_t tile = kColumnTileBytes / sizeof(T);
  for_each_block(count, tile, alignment_peel(out, kCacheLine), [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
    column_tile<T, V, kFixedForm>(bands, x + j, y + j, z + j, out + j, stride);
  });
}

// Crowded strides with the band count's own kernel (up to kMaxFastBands bands): the kernel cut into pieces.
// At such strides what is slow is the order of the stores, not their number: the direct path writes bands^2
// lines into one cache set per vector of directions, while the same bytes written a few rows at a time
// along runs of directions cost about what a plain fill costs (bench_sh_eval's fill bounds; 1-4 rows at a
// time: within 10% of writing whole rows one after another, 8 rows 1.3-1.4x, all rows 2.5x; Xeon, 9 bands,
// count 1024). So the kernel's steps (eval_kernels.h) are cut into pieces of at most kPieceRows output rows,
// and each piece runs over a tile of up to kPieceTileBytes of directions, one block after another, storing
// straight into the output, before the next piece starts.
//
// A piece resumes the kernel from (C_m, S_m) of its column and the column's last two F (KernelState). Where
// they cost a few operations they are recomputed by the kernel's own arithmetic (recompute_cs, resume_column:
// the same bits); otherwise the piece before leaves them per block in a scratch stream of the tile
// (PiecePlan). Which is cheaper depends on the target, measured with 1024 directions at stride = count
// against the padded batch (docs/conventions.md):
// - AVX2 and narrower (Zen 3): recomputing all of it doubled the arithmetic per stored vector (9 bands: 2.1x
//   the direct path's time with the output in L1), 1.3-2.1x the padded batch at 4-16 bands; keeping (C, S)
//   from column 2 and F wherever a piece resumes at l >= m + 3, 1.15-1.45x (kKeepRule).
// - AVX-512 on a Xeon: recomputation measured faster, a stored F made 9 bands 1.3-1.4x slower, every extra
//   store costing about what an output store does (kRecomputeRule: (C, S) kept from 14 bands only).
// - AVX-512 on AMD Zen 5: recomputation ran 1.15-1.8x the padded batch at 7-16 bands; keeping (C, S) from
//   column 4 and F where a piece resumes at l >= m + 5 (a replay of at most two recurrence steps otherwise),
//   with input copies from 6 bands, 0.7-1.06x at 4-7, 9 and 11-16 bands and 1.15-1.2x at 8 and 10 (1.0-1.25x
//   at 8-16 with page-aligned rows and the strides timed in pairs), where keeping everything from column 2 /
//   depth 3 cost 1.05-1.3x at 4-7 bands (kKeepDeepRule). With a vector per cache line the arithmetic per
//   stored line is half AVX2's. From 6 bands on Zen 5 the column tiles above beat the pieces: 0.73-1.05x the
//   padded batch at 6-16 bands (two runs, paired), where the pieces took 0.98-1.17x; below 6 the pieces
//   (0.65-0.9x at 4-5 bands, 0.94-1.03x at 3 with piece_rows and runs_backwards below; the column tiles
//   0.92-1.14x at 4-5, 1.7x at 3).
// - The column tiles on AVX2 (an AVX2 build run on Zen 5): 2.1-3.7x the padded batch at 3-16 bands (eight
//   blocks of Pairs do not fit 16 registers), against the pieces' 1.0-1.4x. Not measured on a Xeon.
// The default follows the build's target (__znverN__: GCC and clang tuning for AMD Zen, which -march=native
// picks on any Zen); PRT_SH_PIECE_RULE (0 recompute, 1 keep deep, 2 keep) overrides it, for the tests.
struct PieceRule {
  int keep_cs_bands;       // (C, S) kept at all from this band count on
  bool keep_f;             // F kept at all
  int cs_from_column;      // (C_m, S_m) kept from column m = this on ((C_1, S_1) = (x, y) costs nothing)
  int f_from_depth;        // F_{l-1}, F_{l-2} kept where a piece resumes at l >= m + this (>= 3: before that
                           // the recurrence reads neither, and resuming at l = m + 2 replays one multiply)
  std::size_t tile_bytes;  // directions per tile, in bytes of one input stream
  int copy_inputs_bands;   // the pieces read copies of x, y, z (kCopyInputs) from this band count on
  int columns_bands;       // from this band count on column tiles (column_tile) instead of pieces
};
// 2 KiB tiles keep a tile's seven scratch streams (x, y, z, C, S and two F) at 14 KiB of L1; 4 KiB tiles were
// 1.1-1.2x slower on Zen 3 at 9-16 bands, 1 KiB within noise. On Zen 5 (48 KiB L1), keeping deep, 2 KiB
// tiles were 1.1-1.3x slower than 4 KiB at 4-10 bands and the same within noise at 13-16.
constexpr PieceRule kRecomputeRule{14, false, 2, 3, 4096, 4, kMaxFastBands + 1};
constexpr PieceRule kKeepDeepRule{1, true, 4, 5, 4096, 6, 6};
constexpr PieceRule kKeepRule{1, true, 2, 3, 2048, 4, kMaxFastBands + 1};
#if defined(PRT_SH_PIECE_RULE)
constexpr int kPieceRuleIndex = PRT_SH_PIECE_RULE;
#elif defined(__znver1__) || defined(__znver2__) || defined(__znver3__) || defined(__znver4__) || \
    defined(__znver5__)
constexpr int kPieceRuleIndex = sizeof(Vec<float>) >= 64 ? 1 : 2;
#else
constexpr int kPieceRuleIndex = sizeof(Vec<float>) >= 64 ? 0 : 2;
#endif
static_assert(0 <= kPieceRuleIndex && kPieceRuleIndex <= 2, "PRT_SH_PIECE_RULE is 0, 1 or 2");
constexpr PieceRule kPieceRule =
    kPieceRuleIndex == 0 ? kRecomputeRule : kPieceRuleIndex == 1 ? kKeepDeepRule : kKeepRule;
constexpr int kPieceRows = 4;
// Rows per piece at this band count: kPieceRows, except two pieces of 5 and 4 rows at 3 bands (instead of 4, 3
// and 2: one pass over the inputs fewer; the tile's rows and inputs stay in L1 there): 0.98-1.03x the padded
// batch against 0.97-1.05x on Zen 5 (AVX-512; inputs 1024-3072 bytes past the rows' page offset, three paired
// runs), within noise on AVX2 (an AVX2 build on Zen 5). A small gain, kept.
constexpr int piece_rows(int bands) { return bands == 3 ? 5 : kPieceRows; }
// Whether eval_batch's crowded strides run column tiles (else pieces) at this band count (count >= a tile).
constexpr bool crowded_by_columns(int bands) { return bands > kMaxFastBands || bands >= kPieceRule.columns_bands; }
constexpr std::size_t kPieceTileBytes = kPieceRule.tile_bytes;
template <int N>
inline constexpr bool kKeepsCs = N >= kPieceRule.keep_cs_bands;
// The pieces read their inputs from copies kInputShift bytes past the output rows' page offset: loads whose
// address matches a pending store's in the low 12 bits wait for it ("4K aliasing"), and a crowded stride's
// stores are pending long (slow to reach L2). Inputs at 64 bytes below the rows' offset (each load aliases
// the stores of the vector before) made 9 / 16 bands 1.2 / 1.4x the padded figure, at 0 1.2 / 1.3x, at
// 1024 1.1 / 1.2x (Xeon, count 1024); the bench's own inputs (std::vector, 32-48 bytes below) 1.2 / 1.25x;
// on Zen 3 reading the bench's inputs directly made 4-16 bands 1.35-1.8x instead of 1.15-1.4x.
constexpr std::size_t kInputShift = 1024;
// Up to 3 bands a tile's output rows and inputs fit in L1 together (9 rows of 4 KiB and 12 KiB of inputs,
// 48 KiB of L1 on the Xeon), the stores do not wait, and the copies would push it all out to L2: 3 bands
// with them took 1.14 ns per direction instead of 0.46. On Zen 5 (keeping deep) the pieces read the
// caller's inputs faster up to 5 bands wherever they lie: with the inputs' page offset swept in steps of
// 128 bytes against the rows', 0.59-0.78x the padded batch at 4 bands and 0.78-0.82x at 5, against
// 0.91-1.05x with copies; from 6 bands inputs up to 256 bytes below the rows' offset made it 1.04-1.3x.
template <int N>
inline constexpr bool kCopyInputs = N >= kPieceRule.copy_inputs_bands;

// At 3 bands, where the pieces read the caller's inputs in place, a tile whose inputs lie just below the rows'
// page offset runs its blocks backwards: going forward, the loads of the blocks just ahead match the page
// offsets of stores still pending from the blocks just written (4K aliasing); backwards they meet those of
// stores long done. Inputs 128 bytes below the rows: 1.10-1.18x -> 0.95-0.98x the padded batch on Zen 5
// (AVX-512, five paired runs each), 1.10-1.16x -> 1.05-1.07x with AVX2 (an AVX2 build on Zen 5). At 4 and 5
// bands backwards was slower (4 bands, 0.74-0.77x against 0.63-0.68x: there the output outgrows L1).
template <int N>
inline constexpr bool kMayRunBackwards = N == 3 && !kCopyInputs<N>;
constexpr std::size_t kBackwardsWindow = 512;  // bytes

// Whether a tile of the pieces runs backwards: some input's page offset lies up to kBackwardsWindow bytes below
// that of the rows (out) and none lies at or less than that above it (where backwards the loads would meet the
// pending stores instead).
template <typename T>
bool runs_backwards(const T* out, const T* x, const T* y, const T* z) {
  bool below = false, above = false;
  for (const T* in : {x, y, z}) {
    const std::size_t up = (reinterpret_cast<std::uintptr_t>(in) - reinterpret_cast<std::uintptr_t>(out)) % kPage;
    below = below || (up != 0 && kPage - up <= kBackwardsWindow);
    above = above || up < kBackwardsWindow;
  }
  return below && !above;
}

// Output rows of one kernel step: Y_l,0, or Y_l,m and Y_l,-m.
constexpr int step_rows(const KernelStep& step) { return step.m == 0 ? 1 : 2; }

// The pieces of the N-band kernel: steps [begin[p], begin[p + 1]), at most piece_rows(N) rows each.
template <int N>
struct Pieces {
  int count = 0;
  int begin[kKernelSteps<N> + 1] = {};
};
template <int N>
constexpr Pieces<N> make_pieces() {
  Pieces<N> p{};
  int e = 0;
  while (e < kKernelSteps<N>) {
    p.begin[p.count++] = e;
    int rows = 0;
    do {
      rows += step_rows(kernel_step<N>(e));
      ++e;
    } while (e < kKernelSteps<N> && rows + step_rows(kernel_step<N>(e)) <= piece_rows(N));
  }
  p.begin[p.count] = kKernelSteps<N>;
  return p;
}
template <int N>
inline constexpr Pieces<N> kPieces = make_pieces<N>();

// How piece P of the N-band kernel resumes, and what it leaves for piece P + 1.
struct PiecePlan {
  int cs_column;   // the column whose (C, S) it needs on entry; 0 if none (it starts in column 0 or 1)
  bool loads_cs;   // reads (C, S) of cs_column from the scratch instead of recomputing it
  bool stores_cs;  // leaves (C, S) of its last column there for the piece after it
  bool loads_f;    // reads F_{l-1}, F_{l-2} of its first step from the scratch instead of replaying the column
  bool stores_f;   // leaves its last two F there for the piece after it
};
template <int N>
constexpr PiecePlan plan_piece(int p) {
  const int e0 = kPieces<N>.begin[p], e1 = kPieces<N>.begin[p + 1];
  const KernelStep first = kernel_step<N>(e0), last = kernel_step<N>(e1 - 1);
  // (C, S) read: by a piece that starts inside column m >= 1, or at the start of column m >= 2 (advanced from
  // m - 1); changed: by a piece that starts column m >= 1 or crosses into a new column.
  const int cs_column = first.l > first.m ? first.m : first.m - 1;
  const bool changes_cs = (first.l == first.m && first.m >= 1) || last.m > first.m;
  const bool has_next = p + 1 < kPieces<N>.count;
  const KernelStep next = has_next ? kernel_step<N>(e1) : KernelStep{0, 0};
  PiecePlan plan{};
  plan.cs_column = cs_column >= 1 ? cs_column : 0;
  constexpr PieceRule rule = kPieceRule;
  plan.loads_cs = kKeepsCs<N> && cs_column >= rule.cs_from_column;
  plan.stores_cs = kKeepsCs<N> && has_next && changes_cs && last.m >= rule.cs_from_column;
  plan.loads_f = rule.keep_f && first.l - first.m >= rule.f_from_depth;
  plan.stores_f = rule.keep_f && has_next && next.m == last.m && next.l - next.m >= rule.f_from_depth;
  return plan;
}
template <int N, int P>
inline constexpr PiecePlan kPlan = plan_piece<N>(P);

// Whether some piece of the N-band kernel loads (C, S) (Cs) or F (else) from the scratch.
template <int N, bool Cs>
constexpr bool pieces_keep() {
  for (int p = 0; p < kPieces<N>.count; ++p)
    if (Cs ? plan_piece<N>(p).loads_cs : plan_piece<N>(p).loads_f) return true;
  return false;
}

// A tile's inputs and kept state as the pieces read them: copies of x, y, z, then (C, S) and F (the last two)
// kept per block of directions (by block, not by direction: the blocks of for_each_block overlap), in
// consecutive streams from the output rows' page offset plus kInputShift.
template <typename T>
struct TileInputs {
  const T *x, *y, *z;
  T *c, *s, *f1, *f2;
};

// Piece P over the n directions of one tile (kBlockLanes <= n), blocks of directions at the starts of
// for_each_block(n, kBlockLanes, peel). Blocks, as the direct path: with one vector per call instead, GCC
// fused the a * b - c * d of (C_2, S_2) the other way round than in the direct path's Pair code (3 bands,
// AVX2), and the crowded stride's bits differed from the padded stride's; speed was the same within noise
// (Zen 3).
template <int N, int P, typename T>
PRT_SH_INLINE void piece_pass(std::size_t n, std::size_t peel, const TileInputs<T>& in, T* out, std::size_t stride,
                              bool backwards) {
  using V = Block<T>;
  constexpr int e0 = kPieces<N>.begin[P], e1 = kPieces<N>.begin[P + 1];
  constexpr PiecePlan plan = kPlan<N, P>;
  std::size_t kept = 0;  // where in the scratch streams this block's state is (every piece visits the blocks alike)
  auto block = [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
    const V vx = load<V>(in.x + j), vy = load<V>(in.y + j), vz = load<V>(in.z + j);
    KernelState<V> st{vx, vy, vx, vy};  // what the steps read before writing is set below
    if constexpr (plan.loads_cs) {
      st.c = load<V>(in.c + kept);
      st.s = load<V>(in.s + kept);
    } else if constexpr (plan.cs_column >= 1) {
      recompute_cs<plan.cs_column>(vx, vy, st);
    }
    if constexpr (plan.loads_f) {
      st.f1 = load<V>(in.f1 + kept);
      st.f2 = load<V>(in.f2 + kept);
    } else {
      resume_column<N, e0, T>(vz, st);
    }
    StridedStore<T> put{out + j, stride};
    eval_steps<N, e0, e1, T>(vx, vy, vz, st, put);
    if constexpr (plan.stores_f) {
      store(in.f1 + kept, st.f1);
      store(in.f2 + kept, st.f2);
    }
    if constexpr (plan.stores_cs) {
      store(in.c + kept, st.c);
      store(in.s + kept, st.s);
    }
    kept += kBlockLanes<T>;
  };
  if constexpr (kMayRunBackwards<N>) {
    if (backwards) {
      for_each_block_backwards(n, kBlockLanes<T>, peel, block);
      return;
    }
  }
  for_each_block(n, kBlockLanes<T>, peel, block);
}

template <int N, typename T, int... P>
PRT_SH_INLINE void pieces_tile(std::size_t n, std::size_t peel, const TileInputs<T>& in, T* out, std::size_t stride,
                               bool backwards, std::integer_sequence<int, P...>) {
  (piece_pass<N, P, T>(n, peel, in, out, stride, backwards), ...);
}

// Directions per tile for count >= kBlockLanes: the fewest tiles of at most kPieceTileBytes of directions, of
// equal length in whole blocks (the last one ends at count, overlapping the one before by less than a
// block per tile).
template <typename T>
std::size_t pieces_tile_length(std::size_t count) {
  constexpr std::size_t lanes = kBlockLanes<T>, most = kPieceTileBytes / sizeof(T);
  const std::size_t tiles = (count + most - 1) / most;
  std::size_t tile = (count + tiles - 1) / tiles;
  tile = (tile + lanes - 1) / lanes * lanes;
  return tile < count ? tile : count;
}

// eval_batch for crowded strides, count >= kBlockLanes, tile by tile. Not inlined into batch_fixed: there it made
// the direct path's loop 1.6x slower (9 bands, 128 directions, padded stride; GCC 12).
template <int N, typename T>
PRT_SH_NOINLINE void batch_pieces(std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  constexpr auto pieces = std::make_integer_sequence<int, kPieces<N>.count>{};
  constexpr bool keep_cs = pieces_keep<N, true>(), keep_f = pieces_keep<N, false>();
  // Each stream holds a tile and a block (the peel adds one); they follow one another from the page offset of
  // the output rows plus kInputShift, within a page and the streams.
  constexpr std::size_t span = kPieceTileBytes / sizeof(T) + kBlockLanes<T>, page = kPage / sizeof(T);
  constexpr std::size_t streams = (kCopyInputs<N> ? 3 : 0) + (keep_cs ? 2 : 0) + (keep_f ? 2 : 0);
  alignas(kPage) T buffer[page + streams * span];
  const std::size_t tile = pieces_tile_length<T>(count), tiles = (count + tile - 1) / tile;
  for (std::size_t t = 0; t < tiles; ++t) {
    const std::size_t j = t * tile < count - tile ? t * tile : count - tile;
    T* next = buffer + (reinterpret_cast<std::uintptr_t>(out + j) + kInputShift) % kPage / sizeof(T);
    auto take = [&next]() {
      T* stream = next;
      next += span;
      return stream;
    };
    TileInputs<T> in{x + j, y + j, z + j, nullptr, nullptr, nullptr, nullptr};
    if constexpr (kCopyInputs<N>) {
      T *cx = take(), *cy = take(), *cz = take();
      std::memcpy(cx, x + j, tile * sizeof(T));
      std::memcpy(cy, y + j, tile * sizeof(T));
      std::memcpy(cz, z + j, tile * sizeof(T));
      in.x = cx;
      in.y = cy;
      in.z = cz;
    }
    if constexpr (keep_cs) {
      in.c = take();
      in.s = take();
    }
    if constexpr (keep_f) {
      in.f1 = take();
      in.f2 = take();
    }
    const bool backwards = kMayRunBackwards<N> && runs_backwards(out + j, in.x, in.y, in.z);
    pieces_tile<N, T>(tile, alignment_peel(out + j, kCacheLine), in, out + j, stride, backwards, pieces);
  }
}

// The direct path shared by every band count: `kernel(x, y, z, put)` evaluates one Block (kLines), vector or
// scalar of directions and stores into every row. Without kLines (the generic kernel) it takes vectors only.
template <typename T, bool kLines, typename Kernel>
PRT_SH_INLINE void run_batch(std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride,
                             Kernel&& kernel) {
  using V = Vec<T>;
  if constexpr (kLines && kBlockLanes<T> > kLanes<T>) {
    using B = Block<T>;
    if (count >= kBlockLanes<T>) {
      for_each_block(count, kBlockLanes<T>, alignment_peel(out, sizeof(B)), [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
        StridedStore<T> put{out + j, stride};
        kernel(load<B>(x + j), load<B>(y + j), load<B>(z + j), put);
      });
      return;
    }
  }
  if (count >= kLanes<T>) {
    // Line-aligned stores when the rows are (stride a multiple of the vector): no store splits.
    const std::size_t peel = alignment_peel(out, sizeof(V));
    for_each_block(count, kLanes<T>, peel, [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
      StridedStore<T> put{out + j, stride};
      kernel(load<V>(x + j), load<V>(y + j), load<V>(z + j), put);
    });
  } else {
    for (std::size_t j = 0; j < count; ++j) {
      StridedStore<T> put{out + j, stride};
      kernel(x[j], y[j], z[j], put);
    }
  }
}

template <int N, typename T>
void batch_fixed(std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  if (count >= kBlockLanes<T> && rows_share_cache_sets<T>(N * N, stride)) {
    if (crowded_by_columns(N) && count >= kColumnTileBytes / sizeof(T))
      batch_columns<T, Block<T>, true>(N, count, x, y, z, out, stride);
    else
      batch_pieces<N, T>(count, x, y, z, out, stride);
    return;
  }
  auto kernel = [](auto vx, auto vy, auto vz, StridedStore<T>& put)
                    PRT_SH_LAMBDA_INLINE { eval_fixed<N, T>(vx, vy, vz, put); };
  run_batch<T, true>(count, x, y, z, out, stride, kernel);
}

template <typename T>
void batch_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  if (count >= kColumnTileBytes / sizeof(T) && rows_share_cache_sets<T>(bands * bands, stride)) {
    batch_columns<T, Vec<T>, false>(bands, count, x, y, z, out, stride);
    return;
  }
  run_batch<T, false>(count, x, y, z, out, stride,
               [bands](auto vx, auto vy, auto vz, StridedStore<T>& put) PRT_SH_LAMBDA_INLINE {
                 eval_generic<T>(bands, vx, vy, vz, put);
               });
}

template <typename T>
using BatchFunction = void (*)(std::size_t, const T*, const T*, const T*, T*, std::size_t);

// batch_fixed<1> .. batch_fixed<kMaxFastBands>, indexed by bands - 1.
template <typename T, int... I>
constexpr auto make_fixed_table(std::integer_sequence<int, I...>) {
  return std::array<BatchFunction<T>, sizeof...(I)>{&batch_fixed<I + 1, T>...};
}

template <typename T>
void batch_dispatch(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  static constexpr auto kFixed = make_fixed_table<T>(std::make_integer_sequence<int, kMaxFastBands>{});
  if (bands >= 1 && bands <= kMaxFastBands) {
    kFixed[static_cast<std::size_t>(bands - 1)](count, x, y, z, out, stride);
  } else {
    batch_generic<T>(bands, count, x, y, z, out, stride);
  }
}

}  // namespace

void eval_batch_generic(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                        std::size_t out_stride) {
  batch_generic<float>(bands, count, x, y, z, out, out_stride);
}

void eval_batch_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                        double* out, std::size_t out_stride) {
  batch_generic<double>(bands, count, x, y, z, out, out_stride);
}

std::size_t staged_tile_directions(int bands, std::size_t count, std::size_t element_bytes) {
  if (crowded_by_columns(bands)) return kColumnTileBytes / element_bytes;
  return element_bytes == sizeof(double) ? pieces_tile_length<double>(count) : pieces_tile_length<float>(count);
}

int staged_pass_rows(int bands) { return crowded_by_columns(bands) ? 1 : piece_rows(bands); }

void eval_one_generic(int bands, float x, float y, float z, float* out) {
  auto put = [out](int k, float v) { out[k] = v; };
  eval_generic<float>(bands, x, y, z, put);
}

void eval_one_generic(int bands, double x, double y, double z, double* out) {
  auto put = [out](int k, double v) { out[k] = v; };
  eval_generic<double>(bands, x, y, z, put);
}

}  // namespace detail

std::size_t padded_stride(std::size_t count, std::size_t element_bytes) {
  // An odd number of cache lines: rows start line-aligned and step through every set of a 4 KiB page.
  const std::size_t per_line = element_bytes >= detail::kCacheLine ? 1 : detail::kCacheLine / element_bytes;
  std::size_t lines = (count + per_line - 1) / per_line;
  if (lines % 2 == 0) ++lines;
  return per_line * lines;
}

void eval_batch(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                std::size_t out_stride) {
  detail::batch_dispatch<float>(bands, count, x, y, z, out, out_stride);
}

void eval_batch(int bands, std::size_t count, const double* x, const double* y, const double* z, double* out,
                std::size_t out_stride) {
  detail::batch_dispatch<double>(bands, count, x, y, z, out, out_stride);
}

}  // namespace prt::sh
