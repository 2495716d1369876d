// The OpenImageIO backend module (libprt_image_oiio.so): see backend.h for why it is separate.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/text.h"
#include "image/backend.h"

namespace prt::image::backend {

namespace {

// Integer-encoded files are display-referred unless they say otherwise: OpenImageIO reports
// "oiio:ColorSpace" as "sRGB" for PNG/JPEG, and "Linear" only where the file declares it.
bool is_srgb_encoded(const OIIO::ImageSpec& spec) {
  if (spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
      spec.format.basetype == OIIO::TypeDesc::DOUBLE)
    return false;
  return to_lower(spec.get_string_attribute("oiio:ColorSpace")).find("linear") == std::string::npos;
}

/// Sends what the codec libraries print on stderr themselves (libpng's "libpng error: ..." lines,
/// libtiff's warnings) into a pipe while it lives; text() gives the first 200 bytes back as one line,
/// so prt can fold them into its own "prt: <file>: <problem>" line instead of leaving an unprefixed
/// one. The pipe is non-blocking: what does not fit in it (64 KiB on Linux) is dropped, never waited
/// for. A pipe rather than a temporary file: no file system work per image (the fuzz target reads
/// hundreds of images a second).
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    if (pipe2(pipe_, O_NONBLOCK | O_CLOEXEC) != 0) pipe_[0] = pipe_[1] = -1;
    saved_ = pipe_[1] >= 0 ? dup(STDERR_FILENO) : -1;
    if (saved_ >= 0 && dup2(pipe_[1], STDERR_FILENO) < 0) {
      close(saved_);
      saved_ = -1;
    }
  }
  ~StderrCapture() {
    restore();
    for (int fd : pipe_)
      if (fd >= 0) close(fd);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  /// Restores stderr and returns what was captured, as one line (at most 200 characters).
  std::string text() {
    restore();
    if (pipe_[0] < 0) return "";
    char buffer[200];
    const ssize_t n = read(pipe_[0], buffer, sizeof buffer);
    return n > 0 ? one_line(std::string(buffer, static_cast<std::size_t>(n))) : "";
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    saved_ = -1;
    std::clearerr(stderr);  // a write refused by the full pipe must not mark stderr as failed
  }
  int pipe_[2] = {-1, -1};
  int saved_ = -1;
};

/// The problem text with what the codec printed, if anything, appended.
std::string with_codec_text(const std::string& problem, StderrCapture& capture) {
  const std::string printed = capture.text();
  return printed.empty() ? problem : problem + " (" + printed + ")";
}

// Decodes the first subimage as width x height x nchannels interleaved floats into `out`. Scanline
// files with one sample format are read in that (native) format, a band of rows of at most 4 MiB at a
// time, and converted here: asked for float directly, OpenImageIO 2.4's read_scanlines allocates a
// conversion buffer of 64 MiB of rows on every call, whatever the image's size (imageinput.cpp, "Split
// into reasonable chunks"). Tiled files and files with per-channel formats take read_image's path.
bool decode_as_float(OIIO::ImageInput& input, const OIIO::ImageSpec& spec, float* out) {
  if (spec.tile_width > 0 || !spec.channelformats.empty())
    return input.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out);
  const OIIO::TypeDesc native = spec.format;
  const int y0 = spec.y, y1 = spec.y + spec.height;
  if (native == OIIO::TypeDesc::FLOAT)
    return input.read_scanlines(0, 0, y0, y1, spec.z, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, out);
  const std::size_t row_values = static_cast<std::size_t>(spec.width) * spec.nchannels;
  const std::size_t row_bytes = row_values * native.size();
  constexpr std::size_t kBandBytes = std::size_t(4) << 20;
  const int band = static_cast<int>(std::clamp<std::size_t>(kBandBytes / row_bytes, 1, spec.height));
  std::vector<unsigned char> rows(band * row_bytes);
  for (int y = y0; y < y1; y += band) {
    const int n = std::min(band, y1 - y);
    if (!input.read_scanlines(0, 0, y, y + n, spec.z, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, rows.data()) ||
        !OIIO::convert_pixel_values(native, rows.data(), OIIO::TypeDesc::FLOAT, out + (y - y0) * row_values,
                                    static_cast<int>(n * row_values)))
      return false;
  }
  return true;
}

// Decodes the opened input's first subimage into `out` (limits, and at most `max_bytes` of decoded
// floats, checked against its header first).
std::string read_pixels(std::unique_ptr<OIIO::ImageInput> input, DecodedImage& out, StderrCapture& capture,
                        double max_bytes = kMaxImageFloats * sizeof(float)) {
  if (!input) return with_codec_text("cannot read as an image: " + one_line(OIIO::geterror()), capture);
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "image has no pixels";
  if (spec.depth > 1) return "volume images are not supported";
  // The header decides the allocation: refuse sizes beyond the limits before any pixel is decoded.
  if (std::string limits = limits_problem(spec.width, spec.height, spec.nchannels); !limits.empty()) return limits;
  if (double(spec.width) * spec.height * spec.nchannels * sizeof(float) > max_bytes)
    return "image of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
           " pixels needs more memory than is left for it";
  out.width = spec.width;
  out.height = spec.height;
  out.channels = spec.nchannels;
  out.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!decode_as_float(*input, spec, out.pixels.data()))
    return with_codec_text("cannot decode: " + one_line(input->geterror()), capture);
  out.srgb_encoded = is_srgb_encoded(spec);
  input->close();
  return "";
}

std::string read(const std::string& path, DecodedImage& out) {
  // The extension picks the one reader tried: a file that does not decode as its extension says is
  // refused, instead of being offered to every one of OpenImageIO's plugins (seconds per bad file).
  static const bool one_reader = OIIO::attribute("try_all_readers", 0);
  (void)one_reader;
  StderrCapture capture;
  std::string problem = read_pixels(OIIO::ImageInput::open(path), out, capture);
  if (!problem.empty()) out = DecodedImage{};
  return problem;
}

std::string read_memory(const std::string& bytes, const std::string& format, double max_bytes, DecodedImage& out) {
  static const bool one_reader = OIIO::attribute("try_all_readers", 0);
  (void)one_reader;
  StderrCapture capture;
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  std::string problem =
      read_pixels(OIIO::ImageInput::create("memory." + format, /*do_open=*/true, nullptr, &memory), out, capture, max_bytes);
  if (!problem.empty()) out = DecodedImage{};
  return problem;
}

std::string write(const std::string& file, const std::string& format_path, int width, int height, int channels,
                  const std::vector<float>& pixels, bool display) {
  auto output = OIIO::ImageOutput::create(format_path);
  if (!output) return "unsupported image format (by extension): " + one_line(OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, display ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  // No time stamp in the file: the same image must give the same bytes (determinism).
  spec.attribute("DateTime", "");
  if (display) {
    spec.attribute("oiio:ColorSpace", "sRGB");
    // prt's alpha channels are data (RGBD's D, coverage), never premultiplied colour: without this
    // OpenImageIO's PNG writer divides the colour by alpha a second time.
    spec.attribute("oiio:UnassociatedAlpha", 1);
  } else {
    spec.attribute("oiio:ColorSpace", "Linear");
    const std::string path = to_lower(format_path);
    if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".exr") == 0) spec.attribute("compression", "zip");
  }
  if (!output->open(file, spec)) return "cannot open for writing: " + one_line(output->geterror());
  bool ok;
  if (display) {
    std::vector<unsigned char> bytes(pixels.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      float v = pixels[i];
      v = std::isnan(v) ? 0.0f : std::min(1.0f, std::max(0.0f, v));
      bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
    ok = output->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  } else {
    ok = output->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  }
  if (!ok) return "write failed: " + one_line(output->geterror());
  if (!output->close()) return "write failed: " + one_line(output->geterror());
  return "";
}

const Functions kFunctions{kAbiVersion, &read, &write, &read_memory};

}  // namespace

}  // namespace prt::image::backend

extern "C" __attribute__((visibility("default"))) const prt::image::backend::Functions* prt_image_backend_functions() {
  return &prt::image::backend::kFunctions;
}
