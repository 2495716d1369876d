#pragma once
// The SH matrix of a cosine-weighted BRDF (Sloan, Kautz and Snyder 2002; Kautz, Sloan and Snyder 2002).
//
// DEFINITION. In the local frame (normal = +z; brdf.h), for `bands` bands (n = bands^2 coefficients):
//   B_kj = integral over w_i in S^2 and w_o in S^2 of fbar(w_i, w_o) max(cos theta_i, 0) Y_j(w_i) Y_k(w_o),
// with fbar the BRDF mirrored below the horizon (brdf.h). If T_j are the SH coefficients (local frame)
// of the radiance arriving at a surface point, the outgoing radiance coefficients are O = B T, and the
// radiance leaving toward a view direction v (local, upper hemisphere) is
//   L_o(v) = sum_k O_k Y_k(v) = sum_kj B_kj T_j Y_k(v),
// which equals the SH projection over w_o of integral T(w_i) fbar(w_i, w_o) max(cos theta_i, 0) dw_i
// for T band-limited to `bands`. The band-limited BRDF rho_BL(w_i, w_o) = sum_kj B_kj Y_j(w_i) Y_k(w_o)
// is what prt's glossy PRT actually uses (reconstruct() evaluates it).
//
// LAYOUT. values[c * n * n + k * n + j] = B_kj of colour channel c: channel-major, then row-major with
// row k = OUTGOING coefficient and column j = INCIDENT coefficient, flat SH index l(l+1)+m (sh/basis.h).
//
// STRUCTURE (isotropy). fbar max(cos theta_i, 0) is invariant under rotations about z and under the
// mirror y -> -y, so B_(l,m),(l',m') = 0 unless m = m', and the entries for m and -m are equal:
// B is n_m blocks b^m (l, l' >= |m|). fbar is even in w_o.z, so rows with l + m odd are zero.
//
// METHOD (the two-step projection, using the symmetry). With w_i = (sin theta_i, 0, cos theta_i):
//   1. fixed w_i: F_m(theta_o) = integral over phi of fbar cos(m phi) dphi, then
//      h_lm(theta_i) = (1 + (-1)^(l+m)) integral_0^(pi/2) F_m(theta_o) Ybar_lm(theta_o) sin theta_o dtheta_o,
//      the w_o-projection (Ybar_lm(theta) = Y_lm at phi = 0; the mirror folds the lower hemisphere);
//   2. b^m_(l,l') = c_m integral_0^(pi/2) h_lm(theta_i) Ybar_l'm(theta_i) cos theta_i sin theta_i dtheta_i,
//      c_0 = 2 pi, c_m = pi (m > 0): the w_i-projection (phi_i by the rotation symmetry).
// Each integral is composite Gauss-Legendre on panels GRADED toward the lobe: theta_o around theta_i
// (the mirror direction), phi toward pi, theta_i toward grazing, starting from a fraction of
// lobe_width() and doubling up to a cap that resolves the basis (about 3 / bands radians); grazing
// incidence gets panels down to 1e-3 rad and an azimuth grading scaled by cos(theta_i), because the
// half-vector lobes and GGX's masking term have a corner singularity there (h.z and
// cos_i / (cos_i + cos_o) have no limit at theta_i = theta_o = 90 degrees, mirror azimuth); phong gets
// panel edges at its cut circle r . w_o = 0. Converged (tests/brdf): 12 nodes per panel on half-width
// panels change B by < 1e-8 of its largest entry for phong (n >= 2), blinn-phong and ggx with
// roughness >= 0.3, < 1e-5 for roughness 0.05 and < 2e-5 for phong n = 0 (a lobe with a jump).
// Lambert is exact in closed form: B_(0,0),(l,0) = sqrt(4 pi) z_l / pi (z_l the clamped-cosine zonal
// coefficients), every other entry 0. Cost at 5 bands: about 10-60 ms per shape, lambert free.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"

namespace prt::brdf {

/// The SH matrix of a BRDF (see the top of this header for the layout).
struct BrdfMatrix {
  int bands = 0;
  int channels = 1;            ///< 1 if the BRDF is grey, else 3 (RGB)
  std::vector<double> values;  ///< channels * bands^4 doubles
  std::string spec;            ///< to_spec() of the BRDF it was projected from

  int coefficients() const { return bands * bands; }
  /// Channel c's n x n matrix (c < channels).
  const double* channel(int c) const { return values.data() + static_cast<std::size_t>(c) * coefficients() * coefficients(); }
  /// The channel used for colour channel c (0..2): c for RGB matrices, 0 for grey ones.
  const double* for_colour(int c) const { return channel(channels == 3 ? c : 0); }
};

/// Quadrature resolution; the defaults converge (see METHOD). Larger values are for tests.
struct ProjectionQuality {
  int nodes_per_panel = 8;    ///< Gauss-Legendre nodes per panel, >= 2
  double panel_scale = 1.0;   ///< multiplies every panel width (0.5: about twice as many panels)
};

/// B of one scalar shape (n x n, row-major [out][in]). Preconditions: 1 <= bands <= sh::kMaxBands,
/// parameter in the shape's range (brdf.h).
std::vector<double> project_shape(Shape shape, double parameter, int bands, const ProjectionQuality& quality = {});

/// B of a BRDF: per channel, the sum over terms(brdf) of weight * project_shape. Throws prt::Error
/// for an empty BRDF or bands outside 1..sh::kMaxBands.
BrdfMatrix project(const Brdf& brdf, int bands, const ProjectionQuality& quality = {});

/// out = B in for channel `channel` (n doubles each; in and out must not alias).
void apply(const BrdfMatrix& matrix, int channel, const double* in, double* out);

/// The band-limited cosine-weighted BRDF rho_BL(w_i, w_o) = sum_kj B_kj Y_j(w_i) Y_k(w_o) per colour
/// channel (grey matrices give three equal values). Unit vectors in the local frame, any hemisphere.
glm::dvec3 reconstruct(const BrdfMatrix& matrix, const glm::dvec3& w_i, const glm::dvec3& w_o);

/// Relative L2 error of the reconstruction over the pair of upper hemispheres:
///   sqrt( sum_c integral (rho_BL,c - fbar_c cos theta_i)^2 / sum_c integral (fbar_c cos theta_i)^2 ),
/// both integrals over w_i, w_o with z > 0 (graded quadrature as in project()).
double reconstruction_error(const Brdf& brdf, const BrdfMatrix& matrix);

}  // namespace prt::brdf
