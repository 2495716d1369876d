#include "image/image_structure.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

#include "image/backend.h"

namespace prt::image {

namespace {

constexpr char kPngSignature[] = "\x89PNG\r\n\x1a\n";  // section 5.2
constexpr char kExrMagic[] = "\x76\x2f\x31\x01";        // 20000630, little-endian

/// The file's bytes from `offset`, as many as `n` (fewer at its end).
struct File {
  std::ifstream in;
  std::uint64_t size = 0;
  std::string read(std::uint64_t offset, std::size_t n) {
    if (offset >= size) return "";
    std::string out(static_cast<std::size_t>(std::min<std::uint64_t>(n, size - offset)), '\0');
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(out.data(), static_cast<std::streamsize>(out.size()));
    out.resize(static_cast<std::size_t>(in.gcount()));
    return out;
  }
};

std::uint32_t big_endian32(const std::string& b, std::size_t at) {
  auto u = [&](std::size_t k) { return std::uint32_t(static_cast<unsigned char>(b[at + k])); };
  return (u(0) << 24) | (u(1) << 16) | (u(2) << 8) | u(3);
}

std::int32_t little_endian32(const std::string& b, std::size_t at) {
  auto u = [&](std::size_t k) { return std::uint32_t(static_cast<unsigned char>(b[at + k])); };
  return static_cast<std::int32_t>(u(0) | (u(1) << 8) | (u(2) << 16) | (u(3) << 24));
}

// `chunk "IDAT" at byte 57`, the type quoted only when it is four ASCII letters (section 5.4).
std::string chunk_name(const std::string& type, std::uint64_t offset) {
  bool letters = true;
  for (char c : type) letters = letters && ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'));
  return "chunk " + (letters ? "\"" + type + "\" " : std::string()) + "at byte " + std::to_string(offset);
}

std::string png_problem(File& file) {
  const std::string ends = " but the file ends at byte " + std::to_string(file.size);
  std::uint64_t offset = sizeof(kPngSignature) - 1;
  for (;;) {
    const std::string header = file.read(offset, 8);
    if (header.size() < 8) return "truncated PNG: no IEND chunk before the end of the file (byte " + std::to_string(file.size) + ")";
    const std::uint64_t length = big_endian32(header, 0);
    // The data and the 4-byte CRC follow the 8 header bytes.
    if (length + 4 > file.size - offset - 8)
      return "truncated PNG: " + chunk_name(header.substr(4), offset) + " declares " + std::to_string(length) +
             " data bytes" + ends;
    if (header.compare(4, 4, "IEND") == 0) return "";
    offset += 12 + length;
  }
}

// A zero-terminated string of 1 to `max_length` bytes at `offset`; false if there is none.
bool exr_string(File& file, std::uint64_t& offset, std::size_t max_length, std::string& out) {
  const std::string bytes = file.read(offset, max_length + 1);
  const std::size_t end = bytes.find('\0');
  if (end == std::string::npos || end == 0) return false;
  out = bytes.substr(0, end);
  offset += end + 1;
  return true;
}

// The value size of each fixed-size attribute type ("OpenEXR File Layout", attribute types).
int exr_fixed_size(const std::string& type) {
  static const std::map<std::string, int> sizes = {
      {"box2i", 16},   {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8},   {"envmap", 1}, {"float", 4},           {"int", 4},          {"keycode", 28},
      {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72},           {"m44f", 64},        {"m44d", 128},
      {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},      {"v2i", 8},          {"v2f", 8},
      {"v2d", 16},     {"v3i", 12},   {"v3f", 12},            {"v3d", 24}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? -1 : it->second;
}

// "" if an attribute's value (its declared size, value.size() bytes) has the layout its type
// defines, so that OpenEXR, which reads a known type by the type's layout rather than by the declared
// size, consumes exactly those bytes; else what the type needs. Other types are read by size (opaque).
std::string exr_value_problem(const std::string& type, const std::string& value, std::size_t max_name) {
  const int fixed = exr_fixed_size(type);
  const std::size_t size = value.size();
  if (fixed >= 0) return size == std::size_t(fixed) ? "" : "needs " + std::to_string(fixed) + " bytes";
  if (type == "floatvector") return size % 4 == 0 ? "" : "needs a whole number of floats";
  if (type == "preview") {  // width, height, then 4 bytes per pixel
    if (size < 8) return "needs a width and a height";
    const double pixels = double(std::uint32_t(little_endian32(value, 0))) * std::uint32_t(little_endian32(value, 4));
    return 8 + 4 * pixels == double(size) ? "" : "needs 8 + 4 x width x height bytes";
  }
  std::size_t at = 0;
  if (type == "stringvector") {  // int32 length and that many bytes, repeated
    while (at < size) {
      const std::int64_t n = size - at >= 4 ? little_endian32(value, at) : -1;
      if (n < 0 || std::uint64_t(n) > size - at - 4) return "needs whole strings";
      at += 4 + std::size_t(n);
    }
    return "";
  }
  if (type == "chlist") {  // per channel: name, pixel type, pLinear, 3 reserved, x and y sampling; then 0
    while (at < size && value[at] != '\0') {
      const std::size_t end = value.find('\0', at);
      if (end == std::string::npos || end - at > max_name || size - end - 1 < 16) return "needs whole channels";
      at = end + 1 + 16;
    }
    return at + 1 == size ? "" : "needs to end with its last channel";
  }
  return "";
}

std::string exr_problem(File& file) {
  const unsigned char flags = static_cast<unsigned char>(file.read(5, 1)[0]);  // version bits 8-15
  const bool multipart = (flags & 0x10) != 0;                                   // flag 0x1000
  const std::size_t max_name = (flags & 0x04) != 0 ? 255 : 31;                  // long names, 0x400
  const std::string truncated = "truncated OpenEXR header: the file ends at byte " + std::to_string(file.size);
  std::uint64_t offset = 8;
  for (bool first_header = true;; first_header = false) {
    // A multi-part file's list of headers ends with an empty one.
    if (multipart && !first_header && file.read(offset, 1) == std::string(1, '\0')) return "";
    for (;;) {
      const std::string first = file.read(offset, 1);
      if (first.empty()) return truncated;
      if (first[0] == '\0') break;
      const std::uint64_t at = offset;
      std::string name, type;
      if (!exr_string(file, offset, max_name, name) || !exr_string(file, offset, max_name, type))
        return "bad OpenEXR header: the attribute at byte " + std::to_string(at) + " has no name and type of 1 to " +
               std::to_string(max_name) + " bytes";
      const std::string size_bytes = file.read(offset, 4);
      if (size_bytes.size() < 4) return truncated;
      const std::int64_t size = little_endian32(size_bytes, 0);
      offset += 4;
      const std::string where = "OpenEXR header: attribute \"" + name + "\" (" + type + ") at byte " + std::to_string(at);
      if (size < 0 || static_cast<std::uint64_t>(size) > file.size - offset)
        return "truncated " + where + " declares " + std::to_string(size) + " bytes but the file ends at byte " +
               std::to_string(file.size);
      const std::string value = file.read(offset, static_cast<std::size_t>(size));
      if (const std::string wrong = exr_value_problem(type, value, max_name); !wrong.empty())
        return "bad " + where + " declares " + std::to_string(size) + " bytes, but a " + type + " value " + wrong;
      if (name == "dataWindow" && type == "box2i") {
        const double width = double(little_endian32(value, 8)) - little_endian32(value, 0) + 1;
        const double height = double(little_endian32(value, 12)) - little_endian32(value, 4) + 1;
        if (width > 0 && height > 0)
          if (std::string limits = backend::limits_problem(width, height, 1); !limits.empty()) return limits;
      }
      offset += static_cast<std::uint64_t>(size);
    }
    ++offset;  // the header's terminating zero
    if (!multipart) return "";
  }
}

// BMP ("BMP file format", Microsoft's BITMAPINFOHEADER, BITMAPCOREHEADER): a 14-byte file header,
// then the DIB header's little-endian size and the image's width and height, int32 (negative height:
// rows from the top) or, in the 12-byte OS/2 core header, uint16. OpenImageIO 2.4 multiplies them in
// int before it allocates an RLE image's buffer: large sides overflow and abort the program.
std::string bmp_problem(File& file) {
  const std::string header = file.read(14, 12);
  if (header.size() < 12) return "";  // the reader refuses a short header
  const std::int32_t dib = little_endian32(header, 0);
  double width = 0, height = 0;
  if (dib == 12) {
    auto u16 = [&](std::size_t at) { return double(static_cast<unsigned char>(header[at]) | (static_cast<unsigned char>(header[at + 1]) << 8)); };
    width = u16(4);
    height = u16(6);
  } else if (dib == 40 || dib == 52 || dib == 56 || dib == 108 || dib == 124) {
    width = little_endian32(header, 4);
    height = std::abs(double(little_endian32(header, 8)));
  }
  return width > 0 && height > 0 ? backend::limits_problem(width, height, 1) : "";
}

}  // namespace

std::string structure_problem(const std::string& path) {
  File file{std::ifstream(path, std::ios::binary | std::ios::ate)};
  if (!file.in) return "";
  file.size = static_cast<std::uint64_t>(file.in.tellg());
  const std::string magic = file.read(0, 8);
  if (magic == std::string(kPngSignature, 8)) return png_problem(file);
  if (magic.size() == 8 && magic.compare(0, 4, kExrMagic) == 0) return exr_problem(file);
  // The file-header magics OpenImageIO's BMP reader accepts: BM, and OS/2's BA, CI, CP, PT.
  for (const char* bmp : {"BM", "BA", "CI", "CP", "PT"})
    if (magic.compare(0, 2, bmp) == 0) return bmp_problem(file);
  return "";
}

}  // namespace prt::image
