#pragma once
// Deterministic quadratures on the sphere that integrate band-limited products exactly.
#include <vector>

#include <glm/vec3.hpp>

namespace prt::sh {

/// Gauss-Legendre rule with n >= 1 points on [-1, 1]: exact for polynomials of degree <= 2n - 1.
/// Nodes ascending and symmetric (node[n-1-i] = -node[i]); weights sum to 2. Newton iteration on
/// P_n to full double precision. Resizes `nodes` and `weights` to n.
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

/// A set of unit directions with solid-angle weights (steradians) summing to 4 pi.
struct SphereQuadrature {
  std::vector<glm::dvec3> directions;
  std::vector<double> weights;
};

/// Product rule: Gauss-Legendre in z = cos(theta) times uniform phi. Exact for every polynomial in
/// (x, y, z) of total degree <= max_degree, hence for the product of two functions band-limited to
/// n bands when max_degree >= 2 (n - 1). Uses floor(max_degree/2) + 1 nodes in z and
/// max_degree + 1 in phi (at phi_j = 2 pi (j + 1/2) / (max_degree + 1)), all of equal weight in phi:
/// (floor(max_degree/2) + 1) (max_degree + 1) directions. Precondition: max_degree >= 0.
SphereQuadrature gauss_product_quadrature(int max_degree);

/// The rule that integrates the product of a function band-limited to `bands_a` bands and one
/// band-limited to `bands_b` bands exactly: gauss_product_quadrature(bands_a + bands_b - 2).
SphereQuadrature gauss_product_quadrature_for_bands(int bands_a, int bands_b);

}  // namespace prt::sh
