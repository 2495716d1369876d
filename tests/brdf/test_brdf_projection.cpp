// BRDF SH matrices against independent truth: Lambert against the diffuse closed form (Funk-Hecke
// irradiance), the numeric projection against the closed form, B T against brute-force integration in
// the other order (w_i inside, w_o outside, plain product rules), quadrature convergence, and the
// structure isotropy implies.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "sh/basis.h"
#include "sh/quadrature.h"
#include "sh/rotation.h"
#include "sh/zonal.h"
#include "support/random_draws.h"

using namespace prt;

namespace {

std::vector<double> random_coefficients(int bands, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  std::vector<double> c(static_cast<std::size_t>(bands * bands));
  for (double& v : c) v = gauss(rng);
  return c;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Gauss-Legendre nodes mapped to [a, b].
void gauss_on(int count, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
  sh::gauss_legendre(count, nodes, weights);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    nodes[k] = 0.5 * (a + b) + 0.5 * (b - a) * nodes[k];
    weights[k] *= 0.5 * (b - a);
  }
}

}  // namespace

TEST_CASE("Lambert's B reproduces the diffuse unshadowed result exactly", "[brdf]") {
  // World lighting L (5 bands), normal n, local frame F: T = Rot(F^T) L, O = B T, and
  // L_o(v) = sum_k O_k Y_k(F^T v) must equal albedo / pi * E(n) for every view direction v.
  std::mt19937_64 rng(1);
  for (int bands : {3, 5, 9}) {
    const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf("lambert:albedo=0.7"), bands);
    const int n = bands * bands;
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<double> lighting = random_coefficients(bands, rng);
      const glm::dvec3 normal = prt::test::random_direction(rng);
      const glm::dmat3 frame = brdf::shading_frame(normal);
      std::vector<double> local(n), out(n), y(n);
      sh::Rotation(bands, glm::transpose(frame)).apply(lighting.data(), local.data());
      brdf::apply(b, 0, local.data(), out.data());
      const double expected = 0.7 / M_PI * sh::irradiance(bands, lighting.data(), normal);
      for (int view = 0; view < 5; ++view) {
        glm::dvec3 v = prt::test::random_direction(rng);
        if (glm::dot(v, normal) < 0.0) v = -v;
        sh::eval(bands, glm::transpose(frame) * v, y.data());
        double radiance = 0.0;
        for (int k = 0; k < n; ++k) radiance += out[k] * y[k];
        REQUIRE(radiance == Approx(expected).margin(1e-6 * max_abs(lighting)));
      }
    }
  }
}

TEST_CASE("the numeric two-step projection of a constant BRDF equals the closed form", "[brdf]") {
  // Phong with exponent 0 at the limit is not constant, but f = 1/pi is: integrate Shape::lambert
  // through the generic quadrature by giving it a non-lambert entry point (blinn-phong with n = 0 is
  // the constant 8 / (8 pi) = 1 / pi for every pair of upper-hemisphere directions).
  for (int bands : {3, 6, 9}) {
    const std::vector<double> numeric = brdf::project_shape(brdf::Shape::blinn_phong, 0.0, bands);
    const std::vector<double> exact = brdf::project_shape(brdf::Shape::lambert, 0.0, bands);
    for (std::size_t i = 0; i < exact.size(); ++i) REQUIRE(numeric[i] == Approx(exact[i]).margin(1e-12));
  }
}

TEST_CASE("B couples equal m only, equally for m and -m, and has no rows with l + m odd", "[brdf]") {
  const int bands = 6, n = 36;
  for (const char* spec : {"phong:exponent=20", "blinn:exponent=50", "ggx:roughness=0.4,f0=0.5"}) {
    const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf(spec), bands);
    const double* m = b.channel(0);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j) {
        const int l = sh::band_of(k), mk = k - l * (l + 1), lj = sh::band_of(j), mj = j - lj * (lj + 1);
        const double value = m[k * n + j];
        if (mk != mj || (l + mk) % 2 != 0) REQUIRE(value == 0.0);
        if (mk > 0 && mk == mj) REQUIRE(value == m[sh::index(l, -mk) * n + sh::index(lj, -mj)]);
      }
  }
}

TEST_CASE("B T matches brute-force integration of lighting x cosine-weighted BRDF", "[brdf]") {
  // Independent order: for every w_o of a product rule over the whole SPHERE, the outgoing radiance
  // L_o(w_o) = integral over the upper hemisphere of T(w_i) fbar(w_i, w_o) cos theta_i dw_i by a rule in
  // coordinates tied to w_o (theta_i, and the azimuth psi of w_i relative to w_o's), then
  // O_k = integral L_o(w_o) Y_k(w_o) dw_o, compared with B T for random coefficients T.
  // The half-vector lobes and GGX's masking term have a corner singularity at grazing incidence in the
  // mirror azimuth (h.z and cos_i / (cos_i + cos_o) have no limit there), so both rules use panels that
  // shrink geometrically toward theta = 90 degrees and psi = 180 degrees (fixed edges, chosen here).
  const int bands = 4, n = 16;
  std::mt19937_64 rng(9);
  const std::vector<double> t = random_coefficients(bands, rng);
  const std::vector<double> offsets = {0.0, 3e-4, 3e-3, 0.03, 0.3};
  auto panels = [&](double a, double b, double singular, int per_panel, std::vector<double>& nodes, std::vector<double>& weights) {
    std::vector<double> edges = {a, b};
    for (double o : offsets) {
      if (singular - o > a) edges.push_back(singular - o);
      if (singular + o < b) edges.push_back(singular + o);
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
      // Wide panels get more pieces, so every piece is at most 0.6 wide.
      const int pieces = static_cast<int>(std::ceil((edges[e + 1] - edges[e]) / 0.6));
      for (int p = 0; p < pieces; ++p) {
        std::vector<double> pn, pw;
        gauss_on(per_panel, edges[e] + (edges[e + 1] - edges[e]) * p / pieces, edges[e] + (edges[e + 1] - edges[e]) * (p + 1) / pieces, pn, pw);
        nodes.insert(nodes.end(), pn.begin(), pn.end());
        weights.insert(weights.end(), pw.begin(), pw.end());
      }
    }
  };
  std::vector<double> theta_i, w_theta_i, psi, w_psi, theta_o, w_theta_o;
  panels(0.0, M_PI / 2, M_PI / 2, 6, theta_i, w_theta_i);
  panels(0.0, 2.0 * M_PI, M_PI, 6, psi, w_psi);
  panels(0.0, M_PI, M_PI / 2, 6, theta_o, w_theta_o);
  // L_o(theta_o, .) of an isotropic BRDF under band-limited T is a trigonometric polynomial of degree
  // < bands in phi_o, so a uniform phi_o rule with 16 > 2 (bands - 1) + (bands - 1) points is exact.
  const int phi_o_count = 16;

  for (const char* spec : {"phong:exponent=6,ks=0.8", "blinn:exponent=12,ks=0.9", "ggx:roughness=0.7,f0=0.3",
                           "ggx:roughness=0.5,f0=0.9/0.5/0.1,albedo=0.2"}) {
    const brdf::Brdf brdf_spec = brdf::parse_brdf(spec);
    const brdf::BrdfMatrix b = brdf::project(brdf_spec, bands);
    std::vector<std::vector<double>> brute(3, std::vector<double>(n, 0.0));
    std::vector<double> y(n);
    for (std::size_t a = 0; a < theta_o.size(); ++a)
      for (int c = 0; c < phi_o_count; ++c) {
        const double phi_o = 2.0 * M_PI * (c + 0.25) / phi_o_count;
        const glm::dvec3 w_o(std::sin(theta_o[a]) * std::cos(phi_o), std::sin(theta_o[a]) * std::sin(phi_o), std::cos(theta_o[a]));
        glm::dvec3 radiance(0.0);
        for (std::size_t i = 0; i < theta_i.size(); ++i)
          for (std::size_t p = 0; p < psi.size(); ++p) {
            const double phi_i = phi_o + psi[p];
            const glm::dvec3 w_i(std::sin(theta_i[i]) * std::cos(phi_i), std::sin(theta_i[i]) * std::sin(phi_i), std::cos(theta_i[i]));
            sh::eval(bands, w_i, y.data());
            double incident = 0.0;
            for (int j = 0; j < n; ++j) incident += t[j] * y[j];
            radiance += w_theta_i[i] * std::sin(theta_i[i]) * w_psi[p] * incident * brdf::eval_cosine(brdf_spec, w_i, w_o);
          }
        sh::eval(bands, w_o, y.data());
        const double w = w_theta_o[a] * std::sin(theta_o[a]) * 2.0 * M_PI / phi_o_count;
        for (int channel = 0; channel < 3; ++channel)
          for (int k = 0; k < n; ++k) brute[channel][k] += w * radiance[channel] * y[k];
      }
    for (int channel = 0; channel < 3; ++channel) {
      std::vector<double> projected(n);
      brdf::apply(b, b.channels == 3 ? channel : 0, t.data(), projected.data());
      INFO(spec << " channel " << channel);
      for (int k = 0; k < n; ++k) REQUIRE(projected[k] == Approx(brute[channel][k]).margin(1e-5 * max_abs(brute[channel])));
    }
  }
}

TEST_CASE("the graded quadrature has converged, even for sharp lobes", "[brdf]") {
  // Default rule against 12 nodes per panel on half-width panels: < 1e-7 of the largest entry for
  // typical lobes, < 2e-5 for the extreme ones (roughness 0.05, phong exponent 0 whose lobe is cut).
  brdf::ProjectionQuality fine;
  fine.nodes_per_panel = 12;
  fine.panel_scale = 0.5;
  const struct {
    brdf::Shape shape;
    double parameter, tolerance;
  } cases[] = {
      {brdf::Shape::phong, 0.0, 2e-5},           {brdf::Shape::phong, 2.0, 1e-8},    {brdf::Shape::phong, 3000.0, 1e-8},
      {brdf::Shape::blinn_phong, 20000.0, 1e-8}, {brdf::Shape::ggx_f0, 0.3, 1e-7},   {brdf::Shape::ggx_edge, 0.3, 1e-7},
      {brdf::Shape::ggx_edge, 0.05, 1e-5},
  };
  for (const auto& c : cases) {
    const int bands = 5;
    const std::vector<double> coarse = brdf::project_shape(c.shape, c.parameter, bands);
    const std::vector<double> reference = brdf::project_shape(c.shape, c.parameter, bands, fine);
    double worst = 0.0;
    for (std::size_t i = 0; i < coarse.size(); ++i) worst = std::max(worst, std::abs(coarse[i] - reference[i]));
    INFO("shape " << static_cast<int>(c.shape) << " parameter " << c.parameter << ": " << worst / max_abs(reference));
    CHECK(worst <= c.tolerance * max_abs(reference));
  }
}

TEST_CASE("reconstruction error: Lambert's is the clamped-cosine truncation, glossy lobes improve with bands", "[brdf]") {
  // Lambert: rho = albedo/pi cos+(theta_i); the w_o part is exact, so the error is the relative L2 error
  // of the truncated clamped cosine over the upper hemisphere. 3 bands: exactly 1/16 (the 17:1 property).
  const brdf::Brdf lambert = brdf::parse_brdf("lambert:albedo=0.5");
  CHECK(brdf::reconstruction_error(lambert, brdf::project(lambert, 3)) == Approx(1.0 / 16.0).epsilon(1e-6));
  const brdf::Brdf glossy = brdf::parse_brdf("phong:exponent=8");
  const double e3 = brdf::reconstruction_error(glossy, brdf::project(glossy, 3));
  const double e5 = brdf::reconstruction_error(glossy, brdf::project(glossy, 5));
  const double e9 = brdf::reconstruction_error(glossy, brdf::project(glossy, 9));
  CHECK(e3 > e5);
  CHECK(e5 > e9);
  CHECK(e9 < 0.05);
}
