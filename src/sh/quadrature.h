#pragma once
// Deterministic quadratures on the sphere that integrate band-limited products exactly.
#include <vector>

#include <glm/vec3.hpp>

namespace prt::sh {

/// Gauss-Legendre rule with n >= 1 points on [-1, 1]: exact for polynomials of degree <= 2n - 1.
/// Nodes ascending; weights sum to 2. Newton iteration to full double precision.
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

/// A set of unit directions with solid-angle weights (steradians) summing to 4 pi.
struct SphereQuadrature {
  std::vector<glm::dvec3> directions;
  std::vector<double> weights;
};

/// Product rule: Gauss-Legendre in z = cos(theta) times uniform phi. Exact for every polynomial in
/// (x, y, z) of total degree <= max_degree, hence for the product of two functions band-limited to
/// n bands when max_degree >= 2 (n - 1). Uses floor(max_degree/2) + 1 nodes in z and
/// max_degree + 1 in phi.
SphereQuadrature gauss_product_quadrature(int max_degree);

}  // namespace prt::sh
