#include "sh/quadrature.h"

#include <algorithm>
#include <cmath>

namespace prt::sh {

namespace {

// P_n(x) and P_n'(x) (from P_(n-1)) by the three-term recurrence; |x| < 1.
void legendre_and_derivative(int n, double x, double& value, double& derivative) {
  double p_prev = 1.0, p = x;  // P_0, P_1
  for (int k = 1; k < n; ++k) {
    const double p_next = ((2.0 * k + 1.0) * x * p - k * p_prev) / (k + 1.0);
    p_prev = p;
    p = p_next;
  }
  value = p;
  derivative = n * (x * p - p_prev) / (x * x - 1.0);
}

}  // namespace

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  // Roots of P_n come in +- pairs: find the non-negative half, mirror the rest.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Tricomi's initial guess for the i-th largest root, then Newton on P_n (quadratic convergence;
    // the cap only guards against a step that rounds back and forth in the last ulp).
    double x = 2 * i + 1 == n ? 0.0 : std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double value = 0.0, derivative = 1.0;
    for (int iteration = 0; iteration < 100 && 2 * i + 1 != n; ++iteration) {
      legendre_and_derivative(n, x, value, derivative);
      const double step = value / derivative;
      x -= step;
      if (std::abs(step) <= 1e-15) break;  // the next step would be below rounding
    }
    legendre_and_derivative(n, x, value, derivative);
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    nodes[static_cast<std::size_t>(i)] = -x;
    nodes[static_cast<std::size_t>(n - 1 - i)] = x;
    weights[static_cast<std::size_t>(i)] = weight;
    weights[static_cast<std::size_t>(n - 1 - i)] = weight;
  }
}

SphereQuadrature gauss_product_quadrature(int max_degree) {
  // z-part: the polynomial part in z has degree <= max_degree, and GL with k nodes is exact up to
  // 2k - 1. phi-part: uniform phi with N points sums e^{i j phi} exactly for |j| < N, and a monomial
  // of degree d has phi-frequencies <= d. Monomials with odd x,y-degree carry an odd power of
  // sin(theta) (not a polynomial in z) but their phi-sum is exactly zero.
  const int z_count = max_degree / 2 + 1;
  const int phi_count = max_degree + 1;
  std::vector<double> z_nodes, z_weights;
  gauss_legendre(z_count, z_nodes, z_weights);
  SphereQuadrature q;
  q.directions.reserve(static_cast<std::size_t>(z_count) * phi_count);
  q.weights.reserve(q.directions.capacity());
  const double phi_weight = 2.0 * M_PI / phi_count;
  for (int i = 0; i < z_count; ++i) {
    const double z = z_nodes[static_cast<std::size_t>(i)];
    const double r = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
    for (int j = 0; j < phi_count; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / phi_count;
      q.directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
      q.weights.push_back(z_weights[static_cast<std::size_t>(i)] * phi_weight);
    }
  }
  return q;
}

SphereQuadrature gauss_product_quadrature_for_bands(int bands_a, int bands_b) {
  return gauss_product_quadrature(bands_a + bands_b - 2);
}

}  // namespace prt::sh
