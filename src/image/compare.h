#pragma once
// Error statistics between a result and a reference: two images (e.g. `prt render` against
// `prt reference --image`) or any two arrays of channel values (per-vertex radiance PLYs). What
// `prt compare` prints. No GL, no mesh: links only prt_image.
//
// DEFINITIONS (over the n channel values t_i of the test and r_i of the reference where both are finite;
// values where either is NaN or infinite are counted in non_finite and left out of everything):
//   rms       = sqrt(sum (t_i - r_i)^2 / n)
//   rel_rms   = rms / sqrt(sum r_i^2 / n)   (0 if both are 0; infinity if only the reference rms is 0)
//   max_abs   = max |t_i - r_i|
//   max_rel   = max |t_i - r_i| / max(|r_i|, floor),  floor = max(0.01 * sqrt(sum r_i^2 / n), 1e-30):
//               relative error, with values darker than 1% of the reference's rms judged against that
//               1% so that near-black values (noise on a shadowed or background pixel) do not dominate.
// The reference is always the second argument.
#include <cstddef>
#include <string>

#include "image/image.h"

namespace prt::image {

struct Difference {
  std::size_t compared = 0;    ///< channel values compared (both finite)
  std::size_t non_finite = 0;  ///< channel values skipped because one side is NaN or infinite
  double rms = 0.0;
  double reference_rms = 0.0;  ///< sqrt(mean r_i^2)
  double rel_rms = 0.0;
  double max_abs = 0.0;
  double max_rel = 0.0;
  std::size_t max_abs_index = 0;  ///< index i of the value with the largest |t_i - r_i|
  std::size_t max_rel_index = 0;  ///< index i of the value with the largest relative error
};

/// The statistics above for count values of each array (e.g. interleaved channels). Preconditions:
/// both arrays hold `count` values.
Difference compare_values(const float* test, const float* reference, std::size_t count);

/// |test - reference| / max(|reference|, floor) with floor = max(0.01 reference_rms, 1e-30): the
/// relative error behind max_rel. NaN if either value is not finite.
double relative_error(double test, double reference, double reference_rms);

/// compare_values over the pixels of two images of the same size and channel count.
struct ImageDifference {
  int width = 0, height = 0, channels = 0;
  Difference values;
  int max_abs_x = 0, max_abs_y = 0;  ///< pixel of max_abs (x right, y down from the top row)
  int max_rel_x = 0, max_rel_y = 0;  ///< pixel of max_rel
};

/// Compares; throws prt::Error("<test_name>: image is WxHxC, <reference_name> is WxHxC") if the sizes
/// or channel counts differ. The names are only for messages.
ImageDifference compare_images(const Image& test, const Image& reference, const std::string& test_name = "test",
                               const std::string& reference_name = "reference");

/// Relative error of each pixel as a display image (RGB in [0, 1], for an 8-bit PNG through write()):
/// e = max over channels of relative_error(test, reference, reference_rms), mapped by t = min(e /
/// full_scale, 1) onto the ramp black (t = 0) -> red (1/3) -> yellow (2/3) -> white (t = 1); pixels
/// with a non-finite value are pure blue. `reference_rms` is ImageDifference::values.reference_rms
/// (so the floor is the one max_rel used); full_scale > 0, 0.1 = white from 10% up.
/// Preconditions: equal sizes and channels (compare_images checks them).
Image relative_error_heatmap(const Image& test, const Image& reference, double reference_rms,
                             double full_scale = 0.1);

/// Reads two image files (read_rgb), compares them and, if heatmap_path is not empty, writes
/// relative_error_heatmap (default full scale) there atomically. Throws prt::Error("<file>: <problem>").
ImageDifference compare_image_files(const std::string& test_path, const std::string& reference_path,
                                    const std::string& heatmap_path = "");

}  // namespace prt::image
