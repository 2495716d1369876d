#include "image/image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <dlfcn.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/srgb.h"
#include "core/text.h"
#include "image/backend.h"
#include "image/image_structure.h"

namespace prt::image {

namespace {

std::string executable_folder() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

// Loads libprt_image_oiio.so once: $PRT_IMAGE_BACKEND, else the path of the module this build made,
// else where `cmake --install` puts it, else the folder of the running executable.
const backend::Functions& functions() {
  static const backend::Functions* table = [] {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("PRT_IMAGE_BACKEND")) candidates.emplace_back(env);
    candidates.emplace_back(PRT_IMAGE_BACKEND_PATH);
    candidates.emplace_back(PRT_IMAGE_BACKEND_INSTALLED_PATH);
    candidates.push_back(executable_folder() + "/libprt_image_oiio.so");
    std::string errors;
    for (const std::string& path : candidates) {
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        errors += std::string(errors.empty() ? "" : "; ") + dlerror();
        continue;
      }
      using Entry = const backend::Functions* (*)();
      auto entry = reinterpret_cast<Entry>(dlsym(handle, "prt_image_backend_functions"));
      if (!entry || entry()->abi_version != backend::kAbiVersion) {
        errors += "; " + path + ": not a compatible prt image backend";
        continue;
      }
      return entry();
    }
    fail("image support (OpenImageIO backend) cannot be loaded: " + errors);
  }();
  return *table;
}

// 1 channel (grey) and 2 (grey + alpha) replicate the first channel; 3 or more keep R, G, B.
Image linear_rgb(const backend::DecodedImage& raw) {
  Image out(raw.width, raw.height, 3);
  const std::size_t pixels = static_cast<std::size_t>(raw.width) * raw.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) {
      const int source = raw.channels >= 3 ? c : 0;
      const float v = raw.pixels[p * raw.channels + source];
      out.pixels[p * 3 + c] = raw.srgb_encoded ? static_cast<float>(srgb_to_linear(v)) : v;
    }
  }
  return out;
}

}  // namespace

Image read_rgb(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail_file(path, "file not found");
  if (std::filesystem::is_directory(path, ec)) fail_file(path, "is a folder, not an image");
  check_regular_input(path);
  // Lengths the file declares are checked against its size first (image_structure.h).
  if (const std::string problem = structure_problem(path); !problem.empty()) fail_file(path, problem);
  backend::DecodedImage raw;
  const std::string problem = functions().read(path, raw);
  if (!problem.empty()) fail_file(path, problem);
  return linear_rgb(raw);
}

Image decode_rgb(const std::string& bytes, const std::string& format, const std::string& name, double max_bytes) {
  backend::DecodedImage raw;
  const std::string problem = functions().read_memory(bytes, format, max_bytes, raw);
  if (!problem.empty()) fail_file(name, problem);
  return linear_rgb(raw);
}

bool is_display_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga" || ext == ".bmp";
}

void write_file_at(const std::string& file, const Image& image, const std::string& reported_path) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    fail_file(reported_path, "cannot write an empty or inconsistent image");
  const std::string problem = functions().write(file, reported_path, image.width, image.height, image.channels,
                                                image.pixels, is_display_format(reported_path));
  if (!problem.empty()) fail_file(reported_path, problem);
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
