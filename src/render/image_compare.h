#pragma once
// Comparison of two float images (e.g. a headless render against a path-traced reference), for
// `prt compare` on EXR files. No GL: this file links only prt_image.
#include <cstddef>
#include <string>

#include "image/image.h"

namespace prt::render {

/// Differences of a test image against a reference image of the same size and channels, over every
/// channel of every pixel whose test and reference values are both finite.
struct ImageDifference {
  int width = 0, height = 0, channels = 0;
  std::size_t compared = 0;     ///< channel values compared
  std::size_t non_finite = 0;   ///< channel values skipped because one side is NaN or infinite
  double rms = 0.0;             ///< sqrt(mean (test - reference)^2)
  double reference_rms = 0.0;   ///< sqrt(mean reference^2)
  double rel_rms = 0.0;         ///< rms / reference_rms (0 if both are 0, infinity if only the reference is)
  double max_abs = 0.0;         ///< max |test - reference|
  int max_x = 0, max_y = 0;     ///< pixel of max_abs (x right, y down from the top row)
};

/// Compares; throws prt::Error("<test_name>: image is WxHxC, <reference_name> is ...") if the sizes or
/// channel counts differ. The names are only for messages.
ImageDifference compare_images(const image::Image& test, const image::Image& reference,
                               const std::string& test_name = "test", const std::string& reference_name = "reference");

/// A display image (RGB values in [0, 1], for an 8-bit PNG through image::write) of the per-pixel error
/// e = max over channels |test - reference|, scaled by `scale` (e / scale clamped to [0, 1]; scale <= 0
/// uses the largest e) and coloured by a linear ramp black (0) -> red (1/3) -> yellow (2/3) -> white (1).
/// Non-finite pixels are blue. Preconditions: equal sizes and channels (compare_images checks them).
image::Image difference_heatmap(const image::Image& test, const image::Image& reference, double scale = 0.0);

/// Reads two image files (image::read_rgb), compares them and, if heatmap_path is not empty, writes the
/// heatmap there (atomically). Throws prt::Error("<file>: <problem>").
ImageDifference compare_image_files(const std::string& test_path, const std::string& reference_path,
                                    const std::string& heatmap_path = "");

}  // namespace prt::render
