#include "brdf/brdf.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace prt::brdf {

bool Brdf::is_grey() const {
  for (const Lobe& lobe : lobes)
    if (lobe.weight.r != lobe.weight.g || lobe.weight.r != lobe.weight.b) return false;
  return true;
}

bool lambert_weight(const Brdf& brdf, bool fresnel_mix, glm::dvec3& sum) {
  sum = glm::dvec3(0.0);
  bool any = false;
  for (const Lobe& lobe : brdf.lobes)
    if (lobe.type == LobeType::lambert && lobe.fresnel_mix == fresnel_mix) {
      sum += lobe.weight;
      any = true;
    }
  return any;
}

std::vector<Term> terms(const Brdf& brdf) {
  std::vector<Term> out;
  for (const bool fresnel : {false, true}) {
    glm::dvec3 lambert;
    if (lambert_weight(brdf, fresnel, lambert)) out.push_back({fresnel ? Shape::lambert_fresnel : Shape::lambert, 0.0, lambert});
  }
  for (const Lobe& lobe : brdf.lobes) {
    switch (lobe.type) {
      case LobeType::lambert: break;
      case LobeType::phong: out.push_back({Shape::phong, lobe.exponent, lobe.weight}); break;
      case LobeType::blinn_phong: out.push_back({Shape::blinn_phong, lobe.exponent, lobe.weight}); break;
      case LobeType::ggx:
        out.push_back({Shape::ggx_f0, lobe.roughness, lobe.weight});
        out.push_back({Shape::ggx_edge, lobe.roughness, glm::dvec3(1.0)});
        break;
    }
  }
  return out;
}

namespace {

// max(x, 0)^n with 0^0 = 0 below the cut (the lobe is clipped where x <= 0).
double clipped_power(double x, double n) { return x > 0.0 ? std::pow(x, n) : 0.0; }

// Schlick's (1 - w_i . h)^5 for the half vector h of w_i and w_o; 0 when w_o = -w_i.
double schlick_weight(const glm::dvec3& w_i, const glm::dvec3& w_o) {
  const glm::dvec3 sum = w_i + w_o;
  const double length = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
  if (!(length > 0.0)) return 0.0;
  const double one_minus = std::max(0.0, 1.0 - std::min(1.0, glm::dot(w_i, sum / length)));
  return one_minus * one_minus * one_minus * one_minus * one_minus;
}

// The dielectric F0 of glTF's fresnel_mix (ior 1.5: ((1.5 - 1) / (1.5 + 1))^2).
constexpr double kDielectricF0 = 0.04;

}  // namespace

double eval_shape(Shape shape, double parameter, const glm::dvec3& w_i, const glm::dvec3& w_o_signed) {
  const glm::dvec3 w_o(w_o_signed.x, w_o_signed.y, std::abs(w_o_signed.z));  // the mirror extension fbar
  switch (shape) {
    case Shape::lambert: return 1.0 / M_PI;
    case Shape::lambert_fresnel: return (1.0 - kDielectricF0) * (1.0 - schlick_weight(w_i, w_o)) / M_PI;
    case Shape::phong: {
      const double r_dot_o = -w_i.x * w_o.x - w_i.y * w_o.y + w_i.z * w_o.z;
      return (parameter + 2.0) / (2.0 * M_PI) * clipped_power(r_dot_o, parameter);
    }
    case Shape::blinn_phong: {
      const glm::dvec3 sum = w_i + w_o;
      const double length = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
      if (!(length > 0.0)) return 0.0;  // w_o = -w_i cannot happen for two upper-hemisphere directions
      const double h_z = std::min(1.0, sum.z / length);
      return (parameter + 8.0) / (8.0 * M_PI) * std::pow(h_z, parameter);
    }
    case Shape::ggx_f0:
    case Shape::ggx_edge: {
      const double alpha = parameter * parameter, alpha2 = alpha * alpha;
      const glm::dvec3 sum = w_i + w_o;
      const double length = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
      if (!(length > 0.0)) return 0.0;
      const glm::dvec3 h = sum / length;
      const double denominator = h.z * h.z * (alpha2 - 1.0) + 1.0;
      const double d = alpha2 / (M_PI * denominator * denominator);
      const double cos_i = std::max(w_i.z, 0.0), cos_o = std::max(w_o.z, 0.0);
      const double lambda_sum = cos_o * std::sqrt(cos_i * cos_i * (1.0 - alpha2) + alpha2) +
                                cos_i * std::sqrt(cos_o * cos_o * (1.0 - alpha2) + alpha2);
      if (!(lambda_sum > 0.0)) return 0.0;  // both directions on the horizon
      const double v = 0.5 / lambda_sum;
      const double s = schlick_weight(w_i, w_o);
      return d * v * (shape == Shape::ggx_f0 ? 1.0 - s : s);
    }
  }
  return 0.0;
}

glm::dvec3 eval(const Brdf& brdf, const glm::dvec3& w_i, const glm::dvec3& w_o) {
  glm::dvec3 sum(0.0);
  for (const Lobe& lobe : brdf.lobes) {
    switch (lobe.type) {
      case LobeType::lambert:
        sum += lobe.weight * eval_shape(lobe.fresnel_mix ? Shape::lambert_fresnel : Shape::lambert, 0.0, w_i, w_o);
        break;
      case LobeType::phong: sum += lobe.weight * eval_shape(Shape::phong, lobe.exponent, w_i, w_o); break;
      case LobeType::blinn_phong: sum += lobe.weight * eval_shape(Shape::blinn_phong, lobe.exponent, w_i, w_o); break;
      case LobeType::ggx: {
        const double base = eval_shape(Shape::ggx_f0, lobe.roughness, w_i, w_o);
        const double edge = eval_shape(Shape::ggx_edge, lobe.roughness, w_i, w_o);
        sum += lobe.weight * base + glm::dvec3(edge);
        break;
      }
    }
  }
  return sum;
}

glm::dvec3 eval_cosine(const Brdf& brdf, const glm::dvec3& w_i, const glm::dvec3& w_o) {
  if (!(w_i.z > 0.0)) return glm::dvec3(0.0);
  return eval(brdf, w_i, w_o) * w_i.z;
}

double lobe_width(Shape shape, double parameter) {
  switch (shape) {
    case Shape::lambert:
    case Shape::lambert_fresnel: return M_PI;
    case Shape::phong: return 1.0 / std::sqrt(parameter + 1.0);
    case Shape::blinn_phong: return 2.0 / std::sqrt(parameter + 1.0);
    case Shape::ggx_f0:
    case Shape::ggx_edge: return 2.0 * parameter * parameter;
  }
  return M_PI;
}

}  // namespace prt::brdf
