#pragma once
// Float images and their files, through OpenImageIO. The only module that includes OpenImageIO.
#include <string>
#include <vector>

namespace prt::image {

/// A float image: rows from the top, channels interleaved (pixels[(y * width + x) * channels + c]).
/// Values are linear (radiance or reflectance) unless a function says otherwise.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c, 0.0f) {}
  float& at(int x, int y, int c) { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

/// Reads any file OpenImageIO reads (.exr, .hdr, .png, .tif, ...) as float, converted to linear RGB:
/// 1-channel images are replicated to 3, extra channels (alpha) dropped; 8/16-bit files carrying the
/// sRGB colour space are linearised. Throws prt::Error("<path>: <problem>") if it cannot be read.
Image read_rgb(const std::string& path);

/// Writes an image atomically (temporary file, then rename). The format follows the extension:
/// .exr (32-bit float, linear, no tone map), .hdr (RGBE), .pfm; or 8-bit .png/.jpg/.tga/.bmp, for which
/// values are treated as display values already in [0,1] (see to_display()) and quantised with
/// rounding. Throws prt::Error naming the file on any failure; never leaves a partial file.
void write(const std::string& path, const Image& image);

/// True if the extension is an 8-bit display format (png, jpg, jpeg, tga, bmp).
bool is_display_format(const std::string& path);

/// Tone maps a linear image for display: multiply by 2^exposure_stops, apply the operator, then the
/// sRGB transfer function; results in [0,1]. Operators: "clamp" (none) and "aces" (Narkowicz 2015 fit).
enum class ToneMap { clamp, aces };
Image to_display(const Image& linear, double exposure_stops, ToneMap op);

}  // namespace prt::image
