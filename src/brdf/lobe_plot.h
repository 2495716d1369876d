#pragma once
// `prt brdf --preview`: a plot of the cosine-weighted BRDF in the plane of incidence, true against the
// SH reconstruction, drawn into an image by hand (no plotting library).
#include <vector>

#include "brdf/projection.h"
#include "image/image.h"

namespace prt::brdf {

/// Plots, for each incident angle theta_i in `incident_degrees` (w_i = (sin theta_i, 0, cos theta_i)),
/// rho(w_i, w_o) = fbar(w_i, w_o) cos theta_i (solid) and its reconstruction rho_BL from `matrix`
/// (dashed, same colour) against the signed outgoing angle x in [-90, 90] degrees of
/// w_o = (-sin x, 0, cos x): the mirror direction is at x = +theta_i, backscatter toward the light at
/// negative x. Values are the mean of the colour channels. Axes at rho = 0 and x = 0, ticks every 30
/// degrees and at 4 values of rho, labelled; a legend of incident angles in the top-left corner.
/// Returns a width x height display image (RGB, values in [0, 1], white background), for
/// prt::image::write to a .png. Preconditions: width >= 200, height >= 150.
image::Image plot_lobes(const Brdf& brdf, const BrdfMatrix& matrix, const std::vector<double>& incident_degrees,
                        int width = 960, int height = 540);

}  // namespace prt::brdf
