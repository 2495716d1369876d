#pragma once
// Exact rotation of SH coefficient vectors, for any band count.
//
// Rotations are ACTIVE: rotating a function f by R gives f'(d) = f(R^-1 d). Matrices use column
// vectors (d' = R d), as GLM does. A rotated coefficient vector is c'_(l,m) = sum_k B^l_(m,k) c_(l,k),
// with one (2l+1)x(2l+1) orthogonal block B^l per band (SH rotation never mixes bands).
// Band 1 (coefficients ordered y, z, x up to the sign of Y_1,+-1) is R conjugated by a fixed signed
// permutation; higher bands follow from the Ivanic-Ruedenberg recursion (J. Phys. Chem. 1996,
// with the 1998 errata) in double. A closed-form float fast path covers low band counts.
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sh/basis.h"
#include "sh/coefficients.h"

namespace prt::sh {

/// The CLI's rotation convention: R = Ry(yaw) * Rx(pitch) * Rz(roll), angles in degrees, each a
/// right-handed rotation about the world axis (+Y up). Applied to the environment (active).
glm::dmat3 rotation_from_yaw_pitch_roll(double yaw_degrees, double pitch_degrees, double roll_degrees);

/// Per-band rotation blocks for one 3D rotation, in double.
class Rotation {
 public:
  Rotation() = default;
  /// Builds blocks for bands 0..bands-1 of the active rotation `r`.
  /// Preconditions: 1 <= bands <= kMaxBands; r orthonormal with det +1 to ~1e-6 (it is
  /// re-orthonormalised, so small drift is tolerated).
  Rotation(int bands, const glm::dmat3& r);

  int bands() const { return bands_; }
  /// Block of band l (0 <= l < bands()): (2l+1)^2 doubles, row-major, so that
  /// out[index(l, m)] = sum_k block(l)[(m + l) * (2l + 1) + (k + l)] * in[index(l, k)].
  const double* block(int l) const;

  /// out = rotated in, both bands()^2 long. in and out must not alias.
  void apply(const double* in, double* out) const;
  void apply(const float* in, float* out) const;
  /// RGB sets (bands must match bands()): each channel rotated by the same blocks.
  RgbCoefficients apply(const RgbCoefficients& in) const;

  /// The rotation by r^-1 (the transposed blocks).
  Rotation inverse() const;

 private:
  int bands_ = 0;
  std::vector<double> blocks_;    // bands concatenated, band l at offset l(2l-1)(2l+1)/3
  std::vector<std::size_t> offsets_;
};

/// Fast path: rotates `in` (bands^2 floats) by the active rotation r into `out` in one call
/// (build + apply), with closed forms for low bands and Rotation beyond. in and out must not alias.
/// Precondition: 1 <= bands <= kMaxBands.
void rotate(int bands, const glm::mat3& r, const float* in, float* out);

/// Fast path for RGB sets stored as bands^2 float triples (coefficient-major), e.g. GPU uploads.
void rotate_rgb(int bands, const glm::mat3& r, const glm::vec3* in, glm::vec3* out);

}  // namespace prt::sh
