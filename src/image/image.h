#pragma once
// Float images and their files, through OpenImageIO. The only module that includes OpenImageIO, and
// only in its backend module libprt_image_oiio.so, loaded on first use (see backend.h).
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

/// "WxH": an image's size as messages print it.
inline std::string size_text(const Image& im) { return std::to_string(im.width) + "x" + std::to_string(im.height); }

/// Reads any file OpenImageIO reads (.exr, .hdr, .png, .tif, ...) as float, converted to linear RGB:
/// 1-channel images are replicated to 3, extra channels (alpha) dropped; 8/16-bit integer files are
/// linearised with the sRGB curve unless OpenImageIO reports a linear colour space for them. Values
/// are returned as stored (no clamping: NaN, Inf and negatives pass through). Only the first
/// subimage is read. Throws prt::Error("<path>: <problem>") if the file is missing or cannot be read.
Image read_rgb(const std::string& path);

/// Writes an image atomically (temporary file, then rename). The format follows the extension:
/// .exr (32-bit float, linear, no tone map), .hdr (RGBE), .pfm; or 8-bit .png/.jpg/.tga/.bmp, for which
/// values are treated as display values already in [0,1] (see to_display()) and quantised with
/// rounding. Throws prt::Error naming the file on any failure; never leaves a partial file.
void write(const std::string& path, const Image& image);

/// Writes `image` directly to `file` (NOT atomically), the format chosen from `reported_path`'s
/// extension as write() does; errors name `reported_path`. For callers that stage several outputs
/// through their own prt::AtomicFile objects (file = AtomicFile::temp_path(), which keeps the extension)
/// and commit them together.
void write_file_at(const std::string& file, const Image& image, const std::string& reported_path);

/// True if the extension (any case) is an 8-bit display format (png, jpg, jpeg, tga, bmp).
bool is_display_format(const std::string& path);

/// Tone maps a linear image for display: x = value * 2^exposure_stops (negative and NaN values become
/// 0), then the operator, then clamping to [0,1] and the sRGB transfer function (IEC 61966-2-1:
/// 12.92 x below 0.0031308, else 1.055 x^(1/2.4) - 0.055). Operators: "clamp" (identity) and "aces",
/// Narkowicz's 2015 fit of the ACES filmic curve, x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
enum class ToneMap { clamp, aces };
Image to_display(const Image& linear, double exposure_stops, ToneMap op);

}  // namespace prt::image
