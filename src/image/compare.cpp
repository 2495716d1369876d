#include "image/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace prt::image {

namespace {

std::string shape(const Image& im) {
  return std::to_string(im.width) + "x" + std::to_string(im.height) + "x" + std::to_string(im.channels);
}

bool both_finite(double a, double b) { return std::isfinite(a) && std::isfinite(b); }

double relative_floor(double reference_rms) { return std::max(0.01 * reference_rms, 1e-30); }

}  // namespace

double relative_error(double test, double reference, double reference_rms) {
  if (!both_finite(test, reference)) return std::numeric_limits<double>::quiet_NaN();
  return std::fabs(test - reference) / std::max(std::fabs(reference), relative_floor(reference_rms));
}

Difference compare_values(const float* test, const float* reference, std::size_t count) {
  Difference d;
  double squared = 0.0, reference_squared = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double a = test[i], b = reference[i];
    if (!both_finite(a, b)) {
      ++d.non_finite;
      continue;
    }
    const double difference = std::fabs(a - b);
    squared += difference * difference;
    reference_squared += b * b;
    ++d.compared;
    if (difference > d.max_abs) {
      d.max_abs = difference;
      d.max_abs_index = i;
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
  // Second pass: the floor of the relative error needs the reference's rms.
  for (std::size_t i = 0; i < count; ++i) {
    const double e = relative_error(test[i], reference[i], d.reference_rms);
    if (e > d.max_rel) {  // false for NaN
      d.max_rel = e;
      d.max_rel_index = i;
    }
  }
  return d;
}

ImageDifference compare_images(const Image& test, const Image& reference, const std::string& test_name,
                               const std::string& reference_name) {
  if (test.width != reference.width || test.height != reference.height || test.channels != reference.channels)
    fail_file(test_name, "image is " + shape(test) + ", " + reference_name + " is " + shape(reference));
  ImageDifference d;
  d.width = test.width;
  d.height = test.height;
  d.channels = test.channels;
  d.values = compare_values(test.pixels.data(), reference.pixels.data(), test.pixels.size());
  if (test.channels > 0 && test.width > 0) {
    const std::size_t abs_pixel = d.values.max_abs_index / static_cast<std::size_t>(test.channels);
    const std::size_t rel_pixel = d.values.max_rel_index / static_cast<std::size_t>(test.channels);
    d.max_abs_x = static_cast<int>(abs_pixel % static_cast<std::size_t>(test.width));
    d.max_abs_y = static_cast<int>(abs_pixel / static_cast<std::size_t>(test.width));
    d.max_rel_x = static_cast<int>(rel_pixel % static_cast<std::size_t>(test.width));
    d.max_rel_y = static_cast<int>(rel_pixel / static_cast<std::size_t>(test.width));
  }
  return d;
}

Image relative_error_heatmap(const Image& test, const Image& reference, double reference_rms, double full_scale) {
  Image out(test.width, test.height, 3);
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      double e = 0.0;
      bool finite = true;
      for (int c = 0; c < test.channels; ++c) {
        const double r = relative_error(test.at(x, y, c), reference.at(x, y, c), reference_rms);
        if (std::isnan(r)) finite = false;
        else e = std::max(e, r);
      }
      if (!finite) {
        out.at(x, y, 2) = 1.0f;
        continue;
      }
      const double t = std::min(1.0, e / full_scale);
      out.at(x, y, 0) = static_cast<float>(std::min(1.0, 3.0 * t));
      out.at(x, y, 1) = static_cast<float>(std::clamp(3.0 * t - 1.0, 0.0, 1.0));
      out.at(x, y, 2) = static_cast<float>(std::clamp(3.0 * t - 2.0, 0.0, 1.0));
    }
  }
  return out;
}

ImageDifference compare_image_files(const std::string& test_path, const std::string& reference_path,
                                    const std::string& heatmap_path) {
  const Image test = read_rgb(test_path);
  const Image reference = read_rgb(reference_path);
  const ImageDifference d = compare_images(test, reference, test_path, reference_path);
  if (!heatmap_path.empty()) write(heatmap_path, relative_error_heatmap(test, reference, d.values.reference_rms));
  return d;
}

}  // namespace prt::image
