#pragma once
// A prebuilt SH rotation in single precision, for applying one rotation to many coefficient sets per
// frame (rendering, relighting): the blocks of a sh::Rotation rounded to float, applied with float sums.
// Accuracy: each output coefficient carries ~(2l + 1) float roundings, relative error ~1e-7 x (2l + 1)
// of the band's norm (tested against Rotation::apply in tests/sh/test_rotation.cpp). Use Rotation for
// double work, sh::rotate for a rotation applied once (build + apply in one call).
#include <vector>

#include <glm/vec3.hpp>

#include "sh/rotation.h"

namespace prt::sh {

class FloatRotation {
 public:
  FloatRotation() = default;
  /// The blocks of `rotation`, rounded to float.
  explicit FloatRotation(const Rotation& rotation);

  int bands() const { return bands_; }
  /// out = rotated in, both bands()^2 floats; in and out must not alias.
  void apply(const float* in, float* out) const;
  /// RGB sets of bands()^2 float triples (coefficient-major); in and out must not alias.
  void apply_rgb(const glm::vec3* in, glm::vec3* out) const;

 private:
  int bands_ = 0;
  std::vector<float> blocks_;  // as Rotation: band l at offset l(2l-1)(2l+1)/3, row-major
};

}  // namespace prt::sh
