#include "brdf/projection.h"

#include <algorithm>
#include <cmath>

#include "brdf/graded_rule.h"
#include "core/error.h"
#include "sh/basis.h"
#include "sh/quadrature.h"
#include "sh/zonal.h"

namespace prt::brdf {

namespace detail {

Rule1D graded_rule(double a, double b, double center, double first_width, double max_width, int nodes_per_panel,
                   const std::vector<double>& breaks) {
  // Panel edges: center, then center +- first_width 2^k on each side until a and b are reached.
  std::vector<double> edges{center};
  for (double x : breaks)
    if (x > a && x < b) edges.push_back(x);
  for (double width = first_width, edge = center; edge < b; width *= 2.0) {
    edge = std::min(b, edge + width);
    edges.push_back(edge);
  }
  for (double width = first_width, edge = center; edge > a; width *= 2.0) {
    edge = std::max(a, edge - width);
    edges.push_back(edge);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  std::vector<double> gauss_nodes, gauss_weights;
  sh::gauss_legendre(nodes_per_panel, gauss_nodes, gauss_weights);
  Rule1D rule;
  for (std::size_t p = 0; p + 1 < edges.size(); ++p) {
    const double lo = edges[p], hi = edges[p + 1];
    if (!(hi > lo)) continue;
    const int pieces = static_cast<int>(std::ceil((hi - lo) / max_width - 1e-9));
    const double piece = (hi - lo) / std::max(1, pieces);
    for (int s = 0; s < std::max(1, pieces); ++s) {
      const double mid = lo + (s + 0.5) * piece, half = 0.5 * piece;
      for (int g = 0; g < nodes_per_panel; ++g) {
        rule.nodes.push_back(mid + half * gauss_nodes[g]);
        rule.weights.push_back(half * gauss_weights[g]);
      }
    }
  }
  return rule;
}

double basis_panel_width(int bands) { return std::min(0.5, 3.0 / bands); }

}  // namespace detail

namespace {

using detail::graded_rule;
using detail::Rule1D;

// Ybar_lm(theta) = Y_lm(sin theta, 0, cos theta) for m >= 0 (the cos(m phi) factor is 1 at phi = 0).
void basis_at_phi0(int bands, double theta, double* out) {
  sh::eval(bands, glm::dvec3(std::sin(theta), 0.0, std::cos(theta)), out);
}

// First panel width toward grazing incidence: the GGX masking term varies like
// cos_i / (cos_i + cos_o) near the corner theta_i = theta_o = pi/2, which has no length scale.
constexpr double kGrazingWidth = 1e-3;

// The theta_o rule for one theta_i: graded around the mirror direction's polar angle theta_i, with
// first panels no wider than the distance of theta_i from the horizon (the corner above).
// For phong, a panel edge also where the lobe's cut circle r . w_o = 0 first reaches theta_o.
Rule1D theta_o_rule_for(Shape shape, double theta_i, double width, double scale, double max_width, int q) {
  const double to_horizon = std::max(M_PI / 2 - theta_i, 1e-9);
  std::vector<double> breaks;
  if (shape == Shape::phong) breaks.push_back(M_PI / 2 - theta_i);
  return graded_rule(0.0, M_PI / 2, std::min(theta_i, M_PI / 2), scale * std::min(0.25 * width, to_horizon), max_width, q,
                     breaks);
}

// Azimuth in (0, pi) where phong's cut circle r . w_o = 0 crosses the circle of polar angle theta_o
// (r . w_o = cos_i cos_o - sin_i sin_o cos(phi)), or -1 if it does not: the lobe max(r . w_o, 0)^n has a
// kink there (a jump for n = 0), which a panel edge keeps out of the Gauss rules.
double phong_cut(double theta_i, double theta_o) {
  const double denominator = std::sin(theta_i) * std::sin(theta_o);
  if (!(denominator > 0.0)) return -1.0;
  const double c = std::cos(theta_i) * std::cos(theta_o) / denominator;
  return std::abs(c) < 1.0 ? std::acos(c) : -1.0;
}

// The phi rule on [0, pi] for one theta_i, graded toward the mirror azimuth pi. A lobe of angular
// width w around the mirror direction spans about w cos(theta_i) / sin(theta_i) in phi: the
// half-vector lobes (blinn-phong, ggx) are compressed across the plane of incidence by w_i . h.
Rule1D phi_rule_for(double theta_i, double width, double scale, double max_width, int q, double cut = -1.0) {
  const double span = width * std::cos(theta_i) / std::max(std::sin(theta_i), 1e-9);
  const double first = std::min(M_PI, scale * std::max(0.25 * span, 1e-9));
  return graded_rule(0.0, M_PI, M_PI, first, max_width, q, cut > 0.0 ? std::vector<double>{cut} : std::vector<double>{});
}

std::vector<double> project_lambert(int bands) {
  const int n = bands * bands;
  std::vector<double> b(static_cast<std::size_t>(n) * n, 0.0);
  for (int l = 0; l < bands; ++l) b[sh::index(l, 0)] = std::sqrt(4.0 * M_PI) * sh::clamped_cosine_zonal(l) / M_PI;
  return b;
}

}  // namespace

std::vector<double> project_shape(Shape shape, double parameter, int bands, const ProjectionQuality& quality) {
  if (shape == Shape::lambert) return project_lambert(bands);
  const int n = bands * bands;
  const int q = std::max(2, quality.nodes_per_panel);
  const double scale = quality.panel_scale;
  const double max_width = scale * detail::basis_panel_width(bands);
  const double width = std::max(lobe_width(shape, parameter), 1e-6);

  // blocks[m][l][l'] = b^m_(l,l') for l, l' >= m (stored dense bands x bands per m).
  std::vector<double> blocks(static_cast<std::size_t>(bands) * bands * bands, 0.0);
  auto block = [&](int m, int l, int lp) -> double& { return blocks[(static_cast<std::size_t>(m) * bands + l) * bands + lp]; };

  const Rule1D theta_i_rule = graded_rule(0.0, M_PI / 2, M_PI / 2, scale * std::min(0.5 * width, kGrazingWidth), max_width, q);
  std::vector<double> y(static_cast<std::size_t>(n)), y_i(static_cast<std::size_t>(n));
  std::vector<double> f_m(static_cast<std::size_t>(bands)), h(static_cast<std::size_t>(n));
  Rule1D cut_phi_rule;
  for (std::size_t a = 0; a < theta_i_rule.nodes.size(); ++a) {
    const double theta_i = theta_i_rule.nodes[a];
    const glm::dvec3 w_i(std::sin(theta_i), 0.0, std::cos(theta_i));
    const Rule1D theta_o_rule = theta_o_rule_for(shape, theta_i, width, scale, max_width, q);
    const Rule1D shared_phi_rule = phi_rule_for(theta_i, width, scale, max_width, q);

    // Step 1: h_lm(theta_i), the projection over w_o (upper hemisphere, folded by the mirror).
    std::fill(h.begin(), h.end(), 0.0);
    for (std::size_t b = 0; b < theta_o_rule.nodes.size(); ++b) {
      const double theta_o = theta_o_rule.nodes[b], sin_o = std::sin(theta_o), cos_o = std::cos(theta_o);
      const double cut = shape == Shape::phong ? phong_cut(theta_i, theta_o) : -1.0;
      const Rule1D& phi_rule = cut > 0.0 ? (cut_phi_rule = phi_rule_for(theta_i, width, scale, max_width, q, cut)) : shared_phi_rule;
      std::fill(f_m.begin(), f_m.end(), 0.0);
      for (std::size_t c = 0; c < phi_rule.nodes.size(); ++c) {
        const double phi = phi_rule.nodes[c], cos_phi = std::cos(phi);
        const glm::dvec3 w_o(sin_o * cos_phi, sin_o * std::sin(phi), cos_o);
        // 2 x: the integral over phi in [0, pi] stands for [0, 2 pi] (fbar is even in phi).
        const double f = 2.0 * phi_rule.weights[c] * eval_shape(shape, parameter, w_i, w_o);
        // cos(m phi) by the Chebyshev recurrence cos(m phi) = 2 cos(phi) cos((m-1) phi) - cos((m-2) phi).
        double previous = 1.0, current = cos_phi;
        f_m[0] += f;
        for (int m = 1; m < bands; ++m) {
          f_m[m] += f * current;
          const double next = 2.0 * cos_phi * current - previous;
          previous = current;
          current = next;
        }
      }
      basis_at_phi0(bands, theta_o, y.data());
      const double weight = 2.0 * theta_o_rule.weights[b] * sin_o;  // 2 x: the mirrored lower hemisphere
      for (int l = 0; l < bands; ++l)
        for (int m = l % 2; m <= l; m += 2) h[sh::index(l, m)] += weight * y[sh::index(l, m)] * f_m[m];
    }

    // Step 2: accumulate the projection over w_i.
    basis_at_phi0(bands, theta_i, y_i.data());
    const double weight_i = theta_i_rule.weights[a] * std::cos(theta_i) * std::sin(theta_i);
    for (int m = 0; m < bands; ++m) {
      const double c_m = m == 0 ? 2.0 * M_PI : M_PI;
      for (int l = m; l < bands; l += 2) {
        const double hl = c_m * weight_i * h[sh::index(l, m)];
        for (int lp = m; lp < bands; ++lp) block(m, l, lp) += hl * y_i[sh::index(lp, m)];
      }
    }
  }

  std::vector<double> out(static_cast<std::size_t>(n) * n, 0.0);
  for (int m = 0; m < bands; ++m)
    for (int l = m; l < bands; ++l)
      for (int lp = m; lp < bands; ++lp) {
        const double value = block(m, l, lp);
        out[static_cast<std::size_t>(sh::index(l, m)) * n + sh::index(lp, m)] = value;
        if (m > 0) out[static_cast<std::size_t>(sh::index(l, -m)) * n + sh::index(lp, -m)] = value;
      }
  return out;
}

BrdfMatrix project(const Brdf& brdf, int bands, const ProjectionQuality& quality) {
  if (brdf.empty()) fail("brdf: empty BRDF (no lobes)");
  if (bands < 1 || bands > sh::kMaxBands)
    fail_option("bands", " " + std::to_string(bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
  BrdfMatrix out;
  out.bands = bands;
  out.channels = brdf.is_grey() ? 1 : 3;
  out.spec = to_spec(brdf);
  const std::size_t nn = static_cast<std::size_t>(bands) * bands * bands * bands;
  out.values.assign(nn * out.channels, 0.0);
  for (const Term& term : terms(brdf)) {
    const std::vector<double> shape = project_shape(term.shape, term.parameter, bands, quality);
    for (int c = 0; c < out.channels; ++c) {
      const double weight = term.weight[c];
      if (weight == 0.0) continue;
      double* dst = out.values.data() + c * nn;
      for (std::size_t i = 0; i < nn; ++i) dst[i] += weight * shape[i];
    }
  }
  return out;
}

void apply(const BrdfMatrix& matrix, int channel, const double* in, double* out) {
  const int n = matrix.coefficients();
  const double* b = matrix.channel(channel);
  for (int k = 0; k < n; ++k) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += b[static_cast<std::size_t>(k) * n + j] * in[j];
    out[k] = sum;
  }
}

glm::dvec3 reconstruct(const BrdfMatrix& matrix, const glm::dvec3& w_i, const glm::dvec3& w_o) {
  const int n = matrix.coefficients();
  double y_i[sh::kMaxBands * sh::kMaxBands], y_o[sh::kMaxBands * sh::kMaxBands];
  sh::eval(matrix.bands, w_i, y_i);
  sh::eval(matrix.bands, w_o, y_o);
  glm::dvec3 out(0.0);
  for (int c = 0; c < matrix.channels; ++c) {
    const double* b = matrix.channel(c);
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      if (y_o[k] == 0.0) continue;
      double row = 0.0;
      for (int j = 0; j < n; ++j) row += b[static_cast<std::size_t>(k) * n + j] * y_i[j];
      sum += y_o[k] * row;
    }
    out[c] = sum;
  }
  if (matrix.channels == 1) out = glm::dvec3(out[0]);
  return out;
}

double reconstruction_error(const Brdf& brdf, const BrdfMatrix& matrix) {
  const int bands = matrix.bands, n = matrix.coefficients();
  const std::vector<Term> all_terms = terms(brdf);
  double width = M_PI;
  for (const Term& t : all_terms) width = std::min(width, lobe_width(t.shape, t.parameter));
  const double max_width = detail::basis_panel_width(bands);
  const int q = 8;
  const Rule1D theta_i_rule = graded_rule(0.0, M_PI / 2, M_PI / 2, 0.5 * width, max_width, q);
  std::vector<double> y_i(static_cast<std::size_t>(n)), y_o(static_cast<std::size_t>(n));
  std::vector<double> b_y(static_cast<std::size_t>(n) * 3);
  double error2 = 0.0, norm2 = 0.0;
  for (std::size_t a = 0; a < theta_i_rule.nodes.size(); ++a) {
    const double theta_i = theta_i_rule.nodes[a];
    const glm::dvec3 w_i(std::sin(theta_i), 0.0, std::cos(theta_i));
    sh::eval(bands, w_i, y_i.data());
    for (int c = 0; c < 3; ++c) {
      const double* b = matrix.for_colour(c);
      for (int k = 0; k < n; ++k) {
        double row = 0.0;
        for (int j = 0; j < n; ++j) row += b[static_cast<std::size_t>(k) * n + j] * y_i[j];
        b_y[c * n + k] = row;
      }
    }
    const Rule1D theta_o_rule = theta_o_rule_for(Shape::lambert, theta_i, width, 1.0, max_width, q);
    const Rule1D phi_rule = phi_rule_for(theta_i, width, 1.0, max_width, q);
    for (std::size_t b = 0; b < theta_o_rule.nodes.size(); ++b) {
      const double theta_o = theta_o_rule.nodes[b];
      for (std::size_t c = 0; c < phi_rule.nodes.size(); ++c) {
        const double phi = phi_rule.nodes[c];
        const glm::dvec3 w_o(std::sin(theta_o) * std::cos(phi), std::sin(theta_o) * std::sin(phi), std::cos(theta_o));
        const double weight = theta_i_rule.weights[a] * std::sin(theta_i) * theta_o_rule.weights[b] * std::sin(theta_o) *
                              phi_rule.weights[c];
        sh::eval(bands, w_o, y_o.data());
        const glm::dvec3 truth = eval_cosine(brdf, w_i, w_o);
        for (int ch = 0; ch < 3; ++ch) {
          double recon = 0.0;
          for (int k = 0; k < n; ++k) recon += y_o[k] * b_y[ch * n + k];
          error2 += weight * (recon - truth[ch]) * (recon - truth[ch]);
          norm2 += weight * truth[ch] * truth[ch];
        }
      }
    }
  }
  return norm2 > 0.0 ? std::sqrt(error2 / norm2) : 0.0;
}

}  // namespace prt::brdf
