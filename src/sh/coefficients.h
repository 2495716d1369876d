#pragma once
// Containers for SH coefficient sets. Layout and basis: see sh/basis.h (flat index l(l+1)+m,
// real orthonormal, Condon-Shortley phase).
#include <vector>

#include <glm/vec3.hpp>

namespace prt::sh {

/// RGB SH coefficients: `values` holds bands^2 triples (r, g, b), coefficient-major.
/// Units are those of the function projected: radiance (W sr^-1 m^-2, or the image's own units)
/// unless a name says irradiance.
struct RgbCoefficients {
  int bands = 0;
  std::vector<glm::dvec3> values;

  RgbCoefficients() = default;
  /// bands^2 zero coefficients. Precondition: 1 <= bands <= kMaxBands.
  explicit RgbCoefficients(int bands_) : bands(bands_), values(static_cast<std::size_t>(bands_ * bands_), glm::dvec3(0.0)) {}
  /// The first `keep` bands (keep <= bands): SH truncation.
  RgbCoefficients truncated(int keep) const {
    RgbCoefficients out(keep);
    for (int i = 0; i < keep * keep; ++i) out.values[i] = values[i];
    return out;
  }
};

}  // namespace prt::sh
