#pragma once
// Internal to prt_image: the interface between image.cpp and the OpenImageIO backend module.
//
// OpenImageIO drags in some 250 shared libraries (OpenVDB, GDAL, DCMTK, ...) whose static
// initialisation alone costs ~120 MB of resident memory and most of a process's start-up time. prt
// therefore keeps it in a separate module, libprt_image_oiio.so, loaded with dlopen() the first time an
// image is read or written: `prt bake`, `prt shade --light`, `prt info`, ... never load it.
#include <string>
#include <vector>

namespace prt::image::backend {

/// Pixels as decoded from a file: `channels` interleaved floats per pixel, rows from the top.
struct DecodedImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
  bool srgb_encoded = false;  ///< integer file in a display (sRGB) encoding
};

/// The module's entry points. Each returns an empty string on success, else a one-line problem
/// (without the path, which the caller adds).
struct Functions {
  int abi_version;
  std::string (*read)(const std::string& path, DecodedImage& out);
  /// Writes width x height x channels floats to `file`; `display` selects 8-bit output, where values
  /// are already display values in [0,1]. `format_path` names the format by its extension.
  std::string (*write)(const std::string& file, const std::string& format_path, int width, int height, int channels,
                       const std::vector<float>& pixels, bool display);
  /// Decodes an image file held in memory (`bytes`), in the format named by `format` (an extension
  /// without the dot: "png", "jpg", ...), under the same limits as `read`, and refuses (from the header,
  /// before decoding) an image whose decoded floats would take more than `max_bytes`.
  std::string (*read_memory)(const std::string& bytes, const std::string& format, double max_bytes, DecodedImage& out);
};

inline constexpr int kAbiVersion = 2;

/// Decoding limits, checked against the file's header before pixels are allocated (docs/formats.md,
/// "Limits"): a side of at most 32768, at most 2^26 pixels (8192 x 8192, 16384 x 4096), at most 16
/// channels, and at most 2^28 decoded floats (1 GiB) in all.
inline constexpr int kMaxImageSide = 32768;
inline constexpr int kMaxImageChannels = 16;
#ifndef PRT_FUZZ_IMAGE_LIMITS
inline constexpr int kMaxImagePixelsLog2 = 26;
inline constexpr int kMaxImageFloatsLog2 = 28;
#else
// Only the fuzz build (-DPRT_BUILD_FUZZ=ON, tests/fuzz/README.md) is compiled with these: 2^18 pixels
// and 2^20 floats (4 MiB), so that a mutated header cannot make every execution decode a large image.
inline constexpr int kMaxImagePixelsLog2 = 18;
inline constexpr int kMaxImageFloatsLog2 = 20;
#endif
inline constexpr double kMaxImagePixels = double(1 << kMaxImagePixelsLog2);
inline constexpr double kMaxImageFloats = double(1 << kMaxImageFloatsLog2);

/// "" if a width x height image of `channels` channels is within the limits above, else the one-line
/// problem ("image of 60000x30000 pixels and 3 channels exceeds prt's limits (...)").
inline std::string limits_problem(double width, double height, int channels) {
  const double pixels = width * height;
  if (width <= kMaxImageSide && height <= kMaxImageSide && pixels <= kMaxImagePixels &&
      channels <= kMaxImageChannels && pixels * channels <= kMaxImageFloats)
    return "";
  return "image of " + std::to_string(static_cast<long long>(width)) + "x" +
         std::to_string(static_cast<long long>(height)) + " pixels and " + std::to_string(channels) +
         (channels == 1 ? " channel" : " channels") + " exceeds prt's limits (sides up to " + std::to_string(kMaxImageSide) + ", 2^" +
         std::to_string(kMaxImagePixelsLog2) + " pixels, " + std::to_string(kMaxImageChannels) + " channels, 2^" +
         std::to_string(kMaxImageFloatsLog2) + " values)";
}

}  // namespace prt::image::backend

/// Exported by the module: its function table.
extern "C" const prt::image::backend::Functions* prt_image_backend_functions();
