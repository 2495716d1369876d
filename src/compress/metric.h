#pragma once
// The error metric CPCA minimises: plain squared L2 of x' = G x, with G a block-diagonal linear map of a
// vertex's transfer block x (D values, the .prt payload order) chosen so that |G dx|^2 is the squared
// error that SHADING sees, averaged over all rotations of the lighting (Sloan, Hall, Hart and Snyder
// 2003, section 4: minimise the error of the exit radiance, not of the raw transfer).
//
// Rotation average. For real SH lighting L_c (colour c) rotated by a uniformly random rotation R, the
// band-l block L'_l = D^l(R) L_l has E[L'_l L'_l^T] = s_lc I with s_lc = |L_lc|^2 / (2l+1), and blocks
// of different bands are uncorrelated (Schur orthogonality of the irreducible blocks D^l). Hence
//   diffuse, shaded c = dT . L'_c:      E sum_c (dT_c . L'_c)^2 = sum_c sum_j s_(l(j),c) dT_cj^2,
//   glossy, O_c = B_c dM_c L'_c:       E sum_c |O_c|^2 = sum_c sum_j dM_c,:j^T (s_(l(j),c) B_c^T B_c) dM_c,:j,
// where dT_c / dM_c is the transfer channel that colour c uses (channel 0 for 1-channel transfer, whose
// three colours then add up) and j runs over the lighting coefficients. |O_c|^2 integrates the squared
// outgoing radiance over all view directions (SH orthonormality). So G is diagonal for diffuse (weight
// sqrt(s) per coefficient) and, for glossy, one bands_out^2 x bands_out^2 block per (channel, column j):
// the symmetric square root of A_j = sum_c s_(l(j),c) B_c^T B_c.
// Without lighting s = 1 (a flat spectrum; diffuse G = I: plain L2, exact for lighting of equal power
// in every band).
//
// Sun and sky (docs/conventions.md): shading applies the transfer T to the sky's SH L_sky and its
// bounce-only part T_b to the discs' SH L_disc (their direct light is exact and needs no transfer). With
// both sections in one point x = [T, T_b] (2D values), the shaded error is dT . L'_sky + dT_b . L'_disc
// with ONE rotation turning both, so the blocks couple the sections: per band and colour the 2 x 2
// cross spectrum s_ab = L_a,l . L_b,l / (2l+1) (a, b in {sky, disc}) replaces s, i.e. the block is
// sum_c kron(S_c, B_c^T B_c) (diffuse: B = 1). Without lighting the sections count as independent. The BRDF's null space (e.g. rows l + m odd of an isotropic B are zero, so 10 of 25
// transferred-radiance components never reach the eye at 5 bands) gets weight ~0: CPCA spends nothing
// on what no view direction sees -- so the compressed transfer is tuned to THAT BRDF (the baked one).
//
// Invertibility: every block's eigenvalues are floored at kMetricFloor times the largest eigenvalue of
// all blocks before the square root, so G is invertible and the inverse maps the fitted model back to
// transfer space; components weighted by the floor are reproduced only as well as the fit needs.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "brdf/projection.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::compress {

constexpr double kMetricFloor = 1e-6;  ///< eigenvalue floor relative to the largest (G's condition <= 1e3)

struct Metric {
  /// One block: G restricted to the values at `index` (g of them): g x g row-major forward G and inverse.
  struct Block {
    std::vector<std::uint32_t> index;
    std::vector<double> forward, inverse;
  };
  std::size_t dimension = 0;   ///< D
  bool identity = true;        ///< G = I (then blocks is empty)
  std::vector<Block> blocks;   ///< disjoint, covering [0, D) when !identity
};

/// s_lc = sum_m L_(l,m),c^2 / (2l+1) for the first `bands` bands (missing lighting bands count 0):
/// bands x 3 values at l * 3 + c.
std::vector<double> rotation_averaged_spectrum(const sh::RgbCoefficients& lighting, int bands);

/// sum_m La_(l,m),c Lb_(l,m),c / (2l+1): the cross spectrum of two lightings (a = b: the spectrum).
std::vector<double> rotation_averaged_cross_spectrum(const sh::RgbCoefficients& a, const sh::RgbCoefficients& b, int bands);

/// The lighting a metric is built for: the SH that the transfer multiplies (null: flat spectrum) and,
/// for points holding the bounce-only section too, the discs' SH that it multiplies (null: the same
/// spectrum as `sky`, uncorrelated with it).
struct MetricLighting {
  const sh::RgbCoefficients* sky = nullptr;
  const sh::RgbCoefficients* discs = nullptr;
};

/// The metric for transfer with header `h`, points of `sections` (1, or 2 = [T, T_b]) blocks of
/// h.values_per_vertex() values, under `lighting`, and for glossy the BRDF matrix at h.bands_out bands
/// the transfer is shaded with (required for glossy, ignored for diffuse). Diffuse without lighting
/// gives the identity.
Metric shaded_metric(const transfer::Header& h, int sections, const MetricLighting& lighting, const brdf::BrdfMatrix* brdf);

/// As above for glossy transfer shaded with several BRDFs (one per material, --brdf mesh): `brdfs[k]`
/// shades the share `shares[k]` of the points (shares >= 0, summing to 1), and the metric takes the
/// shares' mean of the BRDFs' products sum_k shares_k B_k^T B_k per colour, so CPCA's squared error is
/// the shaded error averaged over the points' BRDFs (exact for one BRDF; with several, the one metric
/// weighs every point by the mean, not its own BRDF). Throws prt::Error for sizes that differ.
Metric shaded_metric(const transfer::Header& h, int sections, const MetricLighting& lighting, const std::vector<brdf::BrdfMatrix>& brdfs,
                     const std::vector<double>& shares);

/// out = G x (inverse: G^-1 x) for `count` points of metric.dimension floats, point-major; computed in
/// double, in place allowed. Identity copies.
void apply_metric(const Metric& metric, const float* in, float* out, std::size_t count, bool inverse);

}  // namespace prt::compress
