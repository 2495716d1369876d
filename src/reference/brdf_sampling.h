#pragma once
// Importance sampling of incident directions for the glossy reference (glossy_estimator.h): a mixture
// of one strategy per BRDF lobe (brdf/brdf.h), plus optionally a uniform sphere component, in the local
// frame of a surface point (+z = normal) for a fixed outgoing (view) direction.
//
// STRATEGIES (v' = the view direction mirrored into the upper hemisphere, as fbar does; a = its mirror
// direction (-v'.x, -v'.y, v'.z)):
//   lambert      cosine-weighted hemisphere about +z:          pdf = max(w.z, 0) / pi
//   phong n      (n + 1) / (2 pi) max(a . w, 0)^n about a      (the lobe in w_i, by reciprocity)
//   blinn-phong  half vector h with pdf_h = (n + 1) / (2 pi) (h.z)^n, w = reflect(v', h),
//                pdf = pdf_h / (4 |v' . h|)
//   ggx          half vector from D: pdf_h = D(h) h.z, w = reflect(v', h), pdf = pdf_h / (4 |v' . h|)
//   uniform      1 / (4 pi) over the sphere
// Mixture probabilities: lobe k gets (1 - uniform) * s_k / sum s, with s = the mean of the lobe's
// weight (ggx: at least 0.25, since Fresnel brightens it at grazing angles). Directions may fall below
// the horizon (the reference then decides what they contribute); pdf() is the mixture's density at any
// direction, so sample() and pdf() agree exactly.
//
// The component is chosen by the first coordinate of the 2D point, which is then rescaled to [0, 1)
// within the component's interval, so stratified points stay stratified within each strategy.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "brdf/brdf.h"

namespace prt::reference {

class LobeSampler {
 public:
  /// `uniform_fraction` in [0, 1]: probability of the uniform sphere component (1 if the BRDF has no
  /// lobes).
  LobeSampler(const brdf::Brdf& brdf, double uniform_fraction);

  /// A local direction for point u in [0,1)^2 and the local view direction `view` (unit, any
  /// hemisphere). Returns false for a discarded sample (a half vector facing away from the view: the
  /// estimate counts it as zero, which keeps it unbiased because pdf() gives such directions no density
  /// from that strategy).
  bool sample(const glm::dvec2& u, const glm::dvec3& view, glm::dvec3& direction) const;
  /// Density per steradian of sample() at unit local `direction` for `view`.
  double pdf(const glm::dvec3& direction, const glm::dvec3& view) const;

 private:
  struct Component {
    brdf::LobeType type;
    double parameter;    ///< exponent or alpha = roughness^2
    double probability;
  };
  std::vector<Component> components_;
  double uniform_ = 0.0;
};

}  // namespace prt::reference
