#include "reference/brdf_sampling.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "sh/sampling.h"

namespace prt::reference {

namespace {

glm::dvec3 upper(const glm::dvec3& v) { return glm::dvec3(v.x, v.y, std::abs(v.z)); }

// A direction at cos(angle) = c from `axis`, azimuth phi.
glm::dvec3 around(const glm::dvec3& axis, double c, double phi) {
  glm::dvec3 t, b;
  sh::orthonormal_basis(axis, t, b);
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  return glm::normalize(s * std::cos(phi) * t + s * std::sin(phi) * b + c * axis);
}

double ggx_d(double alpha, double h_z) {
  const double a2 = alpha * alpha, d = h_z * h_z * (a2 - 1.0) + 1.0;
  return a2 / (M_PI * d * d);
}

}  // namespace

LobeSampler::LobeSampler(const brdf::Brdf& brdf, double uniform_fraction) {
  double total = 0.0;
  for (const brdf::Lobe& lobe : brdf.lobes) {
    double s = (lobe.weight.r + lobe.weight.g + lobe.weight.b) / 3.0;
    if (lobe.type == brdf::LobeType::ggx) s = std::max(s, 0.25);
    if (!(s > 0.0)) continue;
    const double parameter = lobe.type == brdf::LobeType::ggx ? lobe.roughness * lobe.roughness : lobe.exponent;
    components_.push_back({lobe.type, parameter, s});
    total += s;
  }
  uniform_ = components_.empty() ? 1.0 : std::clamp(uniform_fraction, 0.0, 1.0);
  for (Component& c : components_) c.probability *= (1.0 - uniform_) / total;
}

bool LobeSampler::sample(const glm::dvec2& u_in, const glm::dvec3& view, glm::dvec3& direction) const {
  glm::dvec2 u = u_in;
  const glm::dvec3 v = upper(view);
  // Pick the component by u.x and rescale u.x to [0, 1) inside its interval.
  double start = 0.0;
  const Component* chosen = nullptr;
  for (const Component& c : components_) {
    if (u.x < start + c.probability) {
      chosen = &c;
      break;
    }
    start += c.probability;
  }
  if (!chosen && uniform_ == 0.0) {  // rounding at the top of the last interval
    chosen = &components_.back();
    start -= chosen->probability;
  }
  const double width = chosen ? chosen->probability : uniform_;
  u.x = std::clamp((u.x - start) / width, 0.0, std::nextafter(1.0, 0.0));
  if (!chosen) {
    direction = sh::square_to_sphere(u);
    return true;
  }
  switch (chosen->type) {
    case brdf::LobeType::lambert: direction = sh::square_to_hemisphere_cosine(u); return true;
    case brdf::LobeType::phong: {
      const glm::dvec3 axis(-v.x, -v.y, v.z);
      direction = around(axis, std::pow(1.0 - u.x, 1.0 / (chosen->parameter + 1.0)), 2.0 * M_PI * u.y);
      return true;
    }
    case brdf::LobeType::blinn_phong:
    case brdf::LobeType::ggx: {
      double cos_h;
      if (chosen->type == brdf::LobeType::blinn_phong) {
        cos_h = std::pow(1.0 - u.x, 1.0 / (chosen->parameter + 1.0));
      } else {
        const double t2 = chosen->parameter * chosen->parameter * u.x / (1.0 - u.x);  // tan^2(theta_h)
        cos_h = 1.0 / std::sqrt(1.0 + t2);
      }
      const glm::dvec3 h = around(glm::dvec3(0, 0, 1), cos_h, 2.0 * M_PI * u.y);
      const double v_dot_h = glm::dot(v, h);
      // Reflecting about a half vector facing away from v gives a direction whose own half vector is -h:
      // pdf() gives it no density from this strategy, so it is discarded (see the header).
      if (!(v_dot_h > 0.0)) return false;
      direction = glm::normalize(2.0 * v_dot_h * h - v);
      return true;
    }
  }
  return false;
}

double LobeSampler::pdf(const glm::dvec3& w, const glm::dvec3& view) const {
  const glm::dvec3 v = upper(view);
  double density = uniform_ * 0.25 * kInvPi;
  for (const Component& c : components_) {
    double p = 0.0;
    switch (c.type) {
      case brdf::LobeType::lambert: p = std::max(w.z, 0.0) * kInvPi; break;
      case brdf::LobeType::phong: {
        const double cos_a = -v.x * w.x - v.y * w.y + v.z * w.z;
        p = cos_a > 0.0 ? (c.parameter + 1.0) * 0.5 * kInvPi * std::pow(cos_a, c.parameter) : 0.0;
        break;
      }
      case brdf::LobeType::blinn_phong:
      case brdf::LobeType::ggx: {
        const glm::dvec3 sum = v + w;
        const double length = glm::length(sum);
        if (!(length > 0.0)) break;
        const glm::dvec3 h = sum / length;
        if (!(h.z > 0.0)) break;
        const double pdf_h = c.type == brdf::LobeType::blinn_phong
                                 ? (c.parameter + 1.0) * 0.5 * kInvPi * std::pow(h.z, c.parameter)
                                 : ggx_d(c.parameter, h.z) * h.z;
        const double v_dot_h = std::abs(glm::dot(v, h));
        if (v_dot_h > 0.0) p = pdf_h / (4.0 * v_dot_h);
        break;
      }
    }
    density += c.probability * p;
  }
  return density;
}

}  // namespace prt::reference
