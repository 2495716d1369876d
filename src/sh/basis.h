#pragma once
// Real spherical harmonics: the basis every part of prt uses.
//
// CONVENTIONS (fixed for the whole project; docs/conventions.md restates them and tests check them)
// - Real, orthonormal SH over the unit sphere: integral over S^2 of Y_i Y_j = delta_ij.
// - WITH the Condon-Shortley phase (as Sloan's papers, DirectXMath, Unreal, google/spherical-harmonics):
//     Y_lm = sqrt(2) K_lm P_l^|m|(cos theta) sin(|m| phi)  for m < 0
//     Y_l0 =         K_l0 P_l^0(cos theta)
//     Y_lm = sqrt(2) K_lm P_l^m(cos theta)  cos(m phi)     for m > 0
//   where P_l^m includes the factor (-1)^m and K_lm = sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!).
// - Directions are unit vectors (x, y, z) in the frame the coefficients live in, with
//   x = sin(theta) cos(phi), y = sin(theta) sin(phi), z = cos(theta): the polar axis is +z of that frame.
//   The basis functions are therefore fixed polynomials in (x, y, z); e.g. Y_1 = -0.4886025 y.
//   The world frame is right-handed with +Y up (glTF, three.js); the basis is NOT re-oriented to make
//   +Y the polar axis, it is simply evaluated on world directions.
// - Flat index i = l (l + 1) + m, 0 <= l < bands, -l <= m <= l.
// - "bands" n means l < n and n^2 coefficients. The word "order" is never used in public names.
// - RGB coefficient sets are arrays of n^2 glm::dvec3 (or float triples), coefficient-major.
//
// Every function here is pure maths: no I/O, no allocation in the per-direction paths.
#include <cstddef>

#include <glm/vec3.hpp>

namespace prt::sh {

/// Largest band count every SH routine in prt supports (l_max = 31). The float fast paths are
/// specialised up to kMaxFastBands and fall back to the generic recurrence beyond it.
inline constexpr int kMaxBands = 32;
inline constexpr int kMaxFastBands = 16;

/// Number of coefficients for `bands` bands: bands^2.
constexpr int coefficient_count(int bands) { return bands * bands; }

/// Flat index of (l, m): l (l + 1) + m. Preconditions: l >= 0, |m| <= l.
constexpr int index(int l, int m) { return l * (l + 1) + m; }

/// Band l of flat index i (inverse of index()).
int band_of(int i);

/// Slow, obviously-correct reference: Y_lm(dir) from the associated Legendre function and
/// trigonometric functions of theta and phi, in double. `dir` need not be normalised (it is
/// normalised here); it must be non-zero. Used by tests to check every fast path.
double eval_reference(int l, int m, const glm::dvec3& dir);

/// All bands^2 basis functions at one unit direction, by the factored polynomial recurrence.
/// Preconditions: 1 <= bands <= kMaxBands, |dir| = 1 (not checked; the basis is a polynomial and a
/// non-unit vector gives the polynomial's value, not a normalised one). `out` holds bands^2 values.
void eval(int bands, const glm::dvec3& dir, double* out);
void eval(int bands, const glm::vec3& dir, float* out);

/// Batched evaluation over many unit directions given as a structure of arrays:
/// out[k * out_stride + j] = Y_k(x[j], y[j], z[j]) for j < count, k < bands^2.
/// Preconditions: 1 <= bands <= kMaxBands, out_stride >= count (asserted), unit directions, `out` does not
/// overlap x, y, z. Entries out[k * out_stride + j] for count <= j < out_stride are not touched.
/// The fast path (bands <= kMaxFastBands) is specialised per band count and vectorised across directions.
/// Layout: out_stride = padded_stride(count, sizeof(T)) with a 64-byte aligned `out` is the layout this is
/// built for. Any other stride >= count gives the same values, but one whose byte size is a multiple of
/// 4 KiB (e.g. out_stride = count = 1024) makes the rows collide in the L1 cache: up to 10x slower.
void eval_batch(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                std::size_t out_stride);
void eval_batch(int bands, std::size_t count, const double* x, const double* y, const double* z, double* out,
                std::size_t out_stride);

/// An out_stride >= count (at most count + 2 cache lines more) for eval_batch's rows, for elements of
/// `element_bytes` (4 for float, 8 for double): an odd number of 64-byte lines, so rows stay line-aligned
/// when `out` is and spread over all cache sets.
std::size_t padded_stride(std::size_t count, std::size_t element_bytes);

}  // namespace prt::sh
