#include "image/image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>

#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace prt::image {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

// Integer-encoded files are display-referred unless they say otherwise: OpenImageIO reports
// "oiio:ColorSpace" as "sRGB" for PNG/JPEG, and "Linear" only where the file declares it.
bool is_srgb_encoded(const OIIO::ImageSpec& spec) {
  if (spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
      spec.format.basetype == OIIO::TypeDesc::DOUBLE)
    return false;
  std::string space = spec.get_string_attribute("oiio:ColorSpace");
  for (char& c : space) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return space.find("linear") == std::string::npos;
}

}  // namespace

Image read_rgb(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail_file(path, "file not found");
  if (std::filesystem::is_directory(path, ec)) fail_file(path, "is a folder, not an image");
  auto input = OIIO::ImageInput::open(path);
  if (!input) fail_file(path, "cannot read as an image: " + one_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) fail_file(path, "image has no pixels");
  if (spec.depth > 1) fail_file(path, "volume images are not supported");

  const int file_channels = spec.nchannels;
  std::vector<float> raw(static_cast<std::size_t>(spec.width) * spec.height * file_channels);
  if (!input->read_image(0, 0, 0, file_channels, OIIO::TypeDesc::FLOAT, raw.data()))
    fail_file(path, "cannot decode: " + one_line(input->geterror()));
  const bool srgb = is_srgb_encoded(spec);
  input->close();

  // 1 channel (grey) and 2 (grey + alpha) replicate the first channel; 3 or more keep R, G, B.
  Image out(spec.width, spec.height, 3);
  const std::size_t pixels = static_cast<std::size_t>(spec.width) * spec.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) {
      int source = file_channels >= 3 ? c : 0;
      float v = raw[p * file_channels + source];
      out.pixels[p * 3 + c] = srgb ? static_cast<float>(srgb_to_linear(v)) : v;
    }
  }
  return out;
}

bool is_display_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga" || ext == ".bmp";
}

void write_file_at(const std::string& file, const Image& image, const std::string& reported_path) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    fail_file(reported_path, "cannot write an empty or inconsistent image");
  auto output = OIIO::ImageOutput::create(file);
  if (!output) fail_file(reported_path, "unsupported image format (by extension): " + one_line(OIIO::geterror()));

  const bool display = is_display_format(reported_path);
  OIIO::ImageSpec spec(image.width, image.height, image.channels,
                       display ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  // No time stamp in the file: the same image must give the same bytes (determinism).
  spec.attribute("DateTime", "");
  if (display) {
    spec.attribute("oiio:ColorSpace", "sRGB");
  } else {
    spec.attribute("oiio:ColorSpace", "Linear");
    if (lower_extension(reported_path) == ".exr") spec.attribute("compression", "zip");
  }
  if (!output->open(file, spec)) fail_file(reported_path, "cannot open for writing: " + one_line(output->geterror()));

  bool ok;
  if (display) {
    std::vector<unsigned char> bytes(image.pixels.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      float v = image.pixels[i];
      v = std::isnan(v) ? 0.0f : std::min(1.0f, std::max(0.0f, v));
      bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
    ok = output->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  } else {
    ok = output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  }
  if (!ok) fail_file(reported_path, "write failed: " + one_line(output->geterror()));
  if (!output->close()) fail_file(reported_path, "write failed: " + one_line(output->geterror()));
}

void write(const std::string& path, const Image& image) {
  AtomicFile file(path);
  write_file_at(file.temp_path(), image, path);
  file.commit();
}

Image to_display(const Image& linear, double exposure_stops, ToneMap op) {
  Image out(linear.width, linear.height, linear.channels);
  const double scale = std::exp2(exposure_stops);
  for (std::size_t i = 0; i < linear.pixels.size(); ++i) {
    double x = static_cast<double>(linear.pixels[i]) * scale;
    if (!(x > 0.0)) x = 0.0;  // negatives and NaN display as black
    if (op == ToneMap::aces) {
      // Narkowicz 2015, "ACES Filmic Tone Mapping Curve" (applied to linear values, no 0.6 pre-scale).
      x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    }
    x = std::min(1.0, std::max(0.0, x));
    out.pixels[i] = static_cast<float>(linear_to_srgb(x));
  }
  return out;
}

}  // namespace prt::image
