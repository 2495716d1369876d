#pragma once
// Internal to prt_brdf: composite Gauss-Legendre rules on panels graded toward a point, for
// integrands with a sharp feature (a BRDF lobe) on top of a smooth one (the SH basis).
#include <vector>

namespace prt::brdf::detail {

struct Rule1D {
  std::vector<double> nodes, weights;
};

/// Panels on [a, b] whose edges are center +- first_width * 2^k (k = 0, 1, ...) and the `breaks`
/// inside (a, b) (known kinks of the integrand), each panel at most max_width wide (wider ones are
/// split evenly), clipped to [a, b]; `nodes_per_panel` Gauss-Legendre nodes on each.
/// Preconditions: a < b, a <= center <= b, 0 < first_width, 0 < max_width.
Rule1D graded_rule(double a, double b, double center, double first_width, double max_width, int nodes_per_panel,
                   const std::vector<double>& breaks = {});

/// The largest panel width that resolves the SH basis of `bands` bands with 8-node panels.
double basis_panel_width(int bands);

}  // namespace prt::brdf::detail
