// libFuzzer target: images through image::read_rgb and the OpenImageIO backend. The extension is
// picked from the magic bytes (PNG, JPEG, Radiance HDR, OpenEXR, BMP, TGA otherwise), as a user's file
// would carry it. OpenImageIO itself is not instrumented; prt's side (limits from the header before
// allocating, error lines) is.
#include <cstring>

#include "fuzz_support.h"
#include "image/image.h"

namespace {
const char* extension_for(const std::uint8_t* data, std::size_t size) {
  auto starts = [&](const char* magic, std::size_t n) { return size >= n && std::memcmp(data, magic, n) == 0; };
  if (starts("\x89PNG", 4)) return ".png";
  if (starts("\xFF\xD8", 2)) return ".jpg";
  if (starts("#?", 2)) return ".hdr";
  if (starts("\x76\x2F\x31\x01", 4)) return ".exr";
  if (starts("BM", 2)) return ".bmp";
  return ".tga";
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = prt::fuzz::write_input(data, size, std::string("input") + extension_for(data, size));
  prt::fuzz::expect_result_or_error([&] { prt::image::read_rgb(path); });
  return 0;
}
