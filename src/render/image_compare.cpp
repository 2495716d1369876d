#include "render/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace prt::render {

namespace {

std::string shape(const image::Image& im) {
  return std::to_string(im.width) + "x" + std::to_string(im.height) + "x" + std::to_string(im.channels);
}

}  // namespace

ImageDifference compare_images(const image::Image& test, const image::Image& reference, const std::string& test_name,
                               const std::string& reference_name) {
  if (test.width != reference.width || test.height != reference.height || test.channels != reference.channels)
    fail_file(test_name, "image is " + shape(test) + ", " + reference_name + " is " + shape(reference));
  ImageDifference d;
  d.width = test.width;
  d.height = test.height;
  d.channels = test.channels;
  double squared = 0.0, reference_squared = 0.0;
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      for (int c = 0; c < test.channels; ++c) {
        const double a = test.at(x, y, c), b = reference.at(x, y, c);
        if (!std::isfinite(a) || !std::isfinite(b)) {
          ++d.non_finite;
          continue;
        }
        const double difference = std::fabs(a - b);
        squared += difference * difference;
        reference_squared += b * b;
        ++d.compared;
        if (difference > d.max_abs) {
          d.max_abs = difference;
          d.max_x = x;
          d.max_y = y;
        }
      }
    }
  }
  if (d.compared > 0) {
    d.rms = std::sqrt(squared / static_cast<double>(d.compared));
    d.reference_rms = std::sqrt(reference_squared / static_cast<double>(d.compared));
  }
  if (d.reference_rms > 0.0) {
    d.rel_rms = d.rms / d.reference_rms;
  } else {
    d.rel_rms = d.rms > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  return d;
}

image::Image difference_heatmap(const image::Image& test, const image::Image& reference, double scale) {
  image::Image out(test.width, test.height, 3);
  std::vector<double> error(static_cast<std::size_t>(test.width) * test.height, 0.0);
  double largest = 0.0;
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      double e = 0.0;
      for (int c = 0; c < test.channels; ++c) {
        const double difference = std::fabs(static_cast<double>(test.at(x, y, c)) - reference.at(x, y, c));
        e = std::isfinite(difference) && std::isfinite(e) ? std::max(e, difference)
                                                          : std::numeric_limits<double>::quiet_NaN();
      }
      error[static_cast<std::size_t>(y) * test.width + x] = e;
      if (std::isfinite(e)) largest = std::max(largest, e);
    }
  }
  if (scale <= 0.0) scale = largest;
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      const double e = error[static_cast<std::size_t>(y) * test.width + x];
      if (!std::isfinite(e)) {
        out.at(x, y, 2) = 1.0f;
        continue;
      }
      const double t = scale > 0.0 ? std::min(1.0, e / scale) : 0.0;
      out.at(x, y, 0) = static_cast<float>(std::min(1.0, 3.0 * t));
      out.at(x, y, 1) = static_cast<float>(std::clamp(3.0 * t - 1.0, 0.0, 1.0));
      out.at(x, y, 2) = static_cast<float>(std::clamp(3.0 * t - 2.0, 0.0, 1.0));
    }
  }
  return out;
}

ImageDifference compare_image_files(const std::string& test_path, const std::string& reference_path,
                                    const std::string& heatmap_path) {
  const image::Image test = image::read_rgb(test_path);
  const image::Image reference = image::read_rgb(reference_path);
  const ImageDifference d = compare_images(test, reference, test_path, reference_path);
  if (!heatmap_path.empty()) image::write(heatmap_path, difference_heatmap(test, reference));
  return d;
}

}  // namespace prt::render
