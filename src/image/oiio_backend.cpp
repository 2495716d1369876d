// The OpenImageIO backend module (libprt_image_oiio.so): see backend.h for why it is separate.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include <unistd.h>

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
/// libtiff's warnings) to a temporary file while it lives; text() gives it back as one line, so prt
/// can fold it into its own "prt: <file>: <problem>" line instead of leaving an unprefixed one.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = file_ ? dup(STDERR_FILENO) : -1;
    if (saved_ >= 0) dup2(fileno(file_), STDERR_FILENO);
  }
  ~StderrCapture() {
    restore();
    if (file_) std::fclose(file_);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  /// Restores stderr and returns what was captured, as one line (at most 200 characters).
  std::string text() {
    restore();
    if (!file_) return "";
    std::rewind(file_);
    char buffer[201] = {};
    const std::size_t n = std::fread(buffer, 1, 200, file_);
    return one_line(std::string(buffer, n));
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

/// The problem text with what the codec printed, if anything, appended.
std::string with_codec_text(const std::string& problem, StderrCapture& capture) {
  const std::string printed = capture.text();
  return printed.empty() ? problem : problem + " (" + printed + ")";
}

std::string read_pixels(const std::string& path, DecodedImage& out, StderrCapture& capture) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) return with_codec_text("cannot read as an image: " + one_line(OIIO::geterror()), capture);
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "image has no pixels";
  if (spec.depth > 1) return "volume images are not supported";
  // The header decides the allocation: refuse sizes beyond the limits before any pixel is decoded.
  const double pixels = double(spec.width) * double(spec.height);
  if (spec.width > kMaxImageSide || spec.height > kMaxImageSide || pixels > kMaxImagePixels ||
      spec.nchannels > kMaxImageChannels || pixels * spec.nchannels > kMaxImageFloats)
    return "image of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels and " +
           std::to_string(spec.nchannels) + " channels exceeds prt's limits (sides up to 32768, 2^26 pixels, " +
           "16 channels, 2^28 values)";
  out.width = spec.width;
  out.height = spec.height;
  out.channels = spec.nchannels;
  out.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()))
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
  std::string problem = read_pixels(path, out, capture);
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

const Functions kFunctions{kAbiVersion, &read, &write};

}  // namespace

}  // namespace prt::image::backend

extern "C" __attribute__((visibility("default"))) const prt::image::backend::Functions* prt_image_backend_functions() {
  return &prt::image::backend::kFunctions;
}
