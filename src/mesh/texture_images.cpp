// Decoding of base colour images for the loaders (loaders.h, decode_texture) through prt_image.
#include <string_view>

#include "core/error.h"
#include "core/memory_check.h"
#include "image/image.h"
#include "mesh/loaders.h"
#include "mesh/texture.h"

namespace prt::mesh::detail {

namespace {

bool has_prefix(const std::string& bytes, std::string_view prefix) {
  return bytes.size() >= prefix.size() && std::string_view(bytes).substr(0, prefix.size()) == prefix;
}

// The format of an image file's content by its signature, else "" (then the hint decides).
std::string signature_format(const std::string& bytes) {
  if (has_prefix(bytes, "\x89PNG")) return "png";
  if (has_prefix(bytes, "\xFF\xD8\xFF")) return "jpg";
  if (has_prefix(bytes, "\xABKTX 2")) return "ktx2";
  if (has_prefix(bytes, "RIFF") && bytes.size() >= 12 && bytes.compare(8, 4, "WEBP") == 0) return "webp";
  if (has_prefix(bytes, "GIF8")) return "gif";
  if (has_prefix(bytes, "BM")) return "bmp";
  if (has_prefix(bytes, "\x76\x2f\x31\x01")) return "exr";
  if (has_prefix(bytes, "#?")) return "hdr";
  return "";
}

// "image/png" -> "png", "textures/a.JPG" -> "jpg": the last word after '/' or '.', lower case.
std::string format_of_hint(const std::string& hint) {
  std::string format = hint.substr(hint.find_last_of("/.") == std::string::npos ? 0 : hint.find_last_of("/.") + 1);
  for (char& ch : format) ch = char(ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch);
  return format == "jpeg" ? "jpg" : format;
}

}  // namespace

bool decode_texture(const std::string& bytes, const std::string& hint, const std::string& name, std::uint64_t* held_bytes,
                    Texture* texture, std::string* problem) {
  std::string format = signature_format(bytes);
  if (format.empty()) format = format_of_hint(hint);
  if (format == "ktx2") {
    *problem = name + ": KTX2/Basis images are not decoded";
    return false;
  }
  // The textures of one mesh may hold at most half of the machine's memory (checked from the header).
  const std::uint64_t budget = physical_memory_bytes() / 2;
  image::Image decoded;
  try {
    decoded = image::decode_rgb(bytes, format, name, double(budget > *held_bytes ? budget - *held_bytes : 0));
  } catch (const Error& e) {
    *problem = e.what();
    return false;
  }
  texture->width = decoded.width;
  texture->height = decoded.height;
  texture->rgb = std::move(decoded.pixels);
  texture->source = name;
  pack_srgb8(texture);  // 8-bit sRGB files: their codes, a quarter of the floats' memory
  *held_bytes += texture->codes.empty() ? std::uint64_t(texture->rgb.size()) * sizeof(float) : texture->codes.size();
  return true;
}

}  // namespace prt::mesh::detail
