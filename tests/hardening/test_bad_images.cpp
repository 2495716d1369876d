// Hostile and truncated PNG and OpenEXR files (issue 10, the image fuzz target's findings): each gives
// one prt::Error naming the file, decided from the container's own lengths before a codec reads or
// allocates by them; the files are made byte by byte here (ISO/IEC 15948 for PNG, "OpenEXR File
// Layout" for OpenEXR), so the expected pixels are known without prt's writers.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "hardening/bad_input_files.h"
#include "image/image.h"

namespace prt::test {
namespace {

using Catch::Matchers::Contains;

std::string put(const std::string& name, const std::string& bytes) { return write_in("hardening_images", name, bytes); }

void put_be32(std::string& out, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

// The sRGB decoding curve (IEC 61966-2-1), the truth for 8-bit PNG samples.
double srgb_to_linear_truth(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

std::string png_ihdr(std::uint32_t width, std::uint32_t height, char colour_type) {
  std::string ihdr;
  put_be32(ihdr, width);
  put_be32(ihdr, height);
  ihdr += std::string{8, colour_type, 0, 0, 0};  // 8 bits, deflate, adaptive filters, no interlace
  return png_chunk("IHDR", ihdr);
}

// A 2x2 8-bit grey PNG of samples 0, 64, 128, 255 (row by row): its IDAT is a zlib stream (RFC 1950)
// of one stored deflate block (RFC 1951, 3.2.4) holding the filtered rows, filter type 0.
const unsigned char kGrey[4] = {0, 64, 128, 255};
std::string grey_png() {
  const std::string rows = {0, char(kGrey[0]), char(kGrey[1]), 0, char(kGrey[2]), char(kGrey[3])};
  std::uint32_t a = 1, b = 0;  // Adler-32 (RFC 1950, 8.2)
  for (unsigned char c : rows) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  std::string idat = {0x78, 0x01, 0x01, char(rows.size()), 0, char(~rows.size()), char(0xff)};
  idat += rows;
  put_be32(idat, (b << 16) | a);
  return png_signature() + png_ihdr(2, 2, 0) + png_chunk("IDAT", idat) + png_chunk("IEND", "");
}

TEST_CASE("a PNG chunk that runs past the end of the file is refused before OpenImageIO reads it", "[hardening][image]") {
  // The fuzz target's leak (tests/fuzz/corpus/image/truncated_chunk.png): libpng's short read made
  // OpenImageIO 2.4 leak its error text; the message was OpenImageIO's, not the chunk's.
  std::string bytes = png_signature() + png_ihdr(2, 2, 0) + png_chunk("oFFs", std::string(9, '\0'));
  REQUIRE(bytes.size() == 54);
  put_be32(bytes, 1000);
  bytes += "tEXtComment";
  const std::string path = put("past_end.png", bytes);
  REQUIRE_THROWS_WITH(image::read_rgb(path),
                      Contains(path) && Contains("truncated PNG: chunk \"tEXt\" at byte 54 declares 1000 data bytes "
                                                 "but the file ends at byte 69"));
  // The CLI: one line, exit status 1.
  const RunResult run = run_prt("light " + path + " -o " + temp_folder("hardening_images") + "/past_end.json");
  REQUIRE(run.exit_code == 1);
  REQUIRE(is_one_error_line(run.output));
}

TEST_CASE("every cut of a PNG is refused as truncated, the whole file and trailing bytes decode", "[hardening][image]") {
  const std::string png = grey_png();
  for (std::size_t n = 8; n < png.size(); ++n) {
    INFO("cut at " << n << " of " << png.size() << " bytes");
    REQUIRE_THROWS_WITH(image::read_rgb(put("cut.png", png.substr(0, n))), Contains("truncated PNG"));
  }
  for (const std::string& bytes : {png, png + "trailing"}) {
    const image::Image im = image::read_rgb(put("whole.png", bytes));
    REQUIRE(im.width == 2);
    REQUIRE(im.height == 2);
    for (int p = 0; p < 4; ++p)
      for (int c = 0; c < 3; ++c) REQUIRE(im.pixels[p * 3 + c] == Approx(srgb_to_linear_truth(kGrey[p] / 255.0)).margin(1e-6));
  }
}

// OpenEXR attributes: name, type name, little-endian int32 size, value.
std::string exr_attribute(const std::string& name, const std::string& type, const std::string& value) {
  std::string out = name + '\0' + type + '\0';
  put32(out, static_cast<std::uint32_t>(value.size()));
  return out + value;
}
std::string le_floats(std::initializer_list<float> values) {
  std::string out;
  for (float v : values) out.append(reinterpret_cast<const char*>(&v), 4);
  return out;
}
std::string box2i(int x0, int y0, int x1, int y1) {
  std::string out;
  for (int v : {x0, y0, x1, y1}) put32(out, static_cast<std::uint32_t>(v));
  return out;
}

// A 2x2 scanline OpenEXR of three float channels B, G, R, uncompressed: the header, the offset table
// (one scanline per chunk) and the chunks (y, byte count, then each channel's row in name order).
// `header_end` is where the header's closing zero byte ends. Pixel (x, y) has R = 1 + x + 2y,
// G = 10 R, B = 100 R.
std::string float_exr(std::size_t& header_end, const std::string& window = box2i(0, 0, 1, 1)) {
  std::string chlist;
  for (const char* name : {"B", "G", "R"}) {
    chlist += std::string(name) + '\0';
    put32(chlist, 2);                          // FLOAT
    chlist += std::string(4, '\0');            // pLinear, reserved
    put32(chlist, 1);
    put32(chlist, 1);                          // x and y sampling
  }
  chlist += '\0';
  std::string out = "\x76\x2f\x31\x01";
  put32(out, 2);  // version 2, single-part scanline
  out += exr_attribute("channels", "chlist", chlist) + exr_attribute("compression", "compression", std::string(1, '\0')) +
         exr_attribute("dataWindow", "box2i", window) + exr_attribute("displayWindow", "box2i", box2i(0, 0, 1, 1)) +
         exr_attribute("lineOrder", "lineOrder", std::string(1, '\0')) +
         exr_attribute("pixelAspectRatio", "float", le_floats({1})) +
         exr_attribute("screenWindowCenter", "v2f", le_floats({0, 0})) +
         exr_attribute("screenWindowWidth", "float", le_floats({1})) + '\0';
  header_end = out.size();
  const std::size_t chunk_bytes = 8 + 3 * 2 * 4;
  put64(out, header_end + 16);
  put64(out, header_end + 16 + chunk_bytes);
  for (int y = 0; y < 2; ++y) {
    put32(out, static_cast<std::uint32_t>(y));
    put32(out, 3 * 2 * 4);
    for (float scale : {100.0f, 10.0f, 1.0f}) out += le_floats({scale * (1 + 2 * y), scale * (2 + 2 * y)});
  }
  return out;
}

TEST_CASE("a valid hand-made OpenEXR decodes, every cut inside its header is refused", "[hardening][image]") {
  std::size_t header_end = 0;
  const std::string exr = float_exr(header_end);
  const image::Image im = image::read_rgb(put("whole.exr", exr));
  REQUIRE(im.width == 2);
  REQUIRE(im.height == 2);
  for (int p = 0; p < 4; ++p) {
    REQUIRE(im.pixels[p * 3 + 0] == float(1 + p));
    REQUIRE(im.pixels[p * 3 + 1] == float(10 * (1 + p)));
    REQUIRE(im.pixels[p * 3 + 2] == float(100 * (1 + p)));
  }
  for (std::size_t n = 8; n < header_end; ++n) {
    INFO("cut at " << n << " of a " << header_end << "-byte header");
    REQUIRE_THROWS_WITH(image::read_rgb(put("cut.exr", exr.substr(0, n))), Contains("OpenEXR header"));
  }
  for (std::size_t n = header_end; n < exr.size(); ++n) REQUIRE_THROWS_AS(image::read_rgb(put("cut.exr", exr.substr(0, n))), Error);
}

TEST_CASE("OpenEXR attributes that lie about their size are refused before OpenEXR allocates them", "[hardening][image]") {
  std::size_t header_end = 0;
  const std::string exr = float_exr(header_end);
  SECTION("an attribute larger than the file (OpenEXR allocates it first)") {
    std::string bytes = exr.substr(0, 8) + "comments" + '\0' + "string" + '\0';
    put32(bytes, 0x7fffffffu);
    const std::string path = put("huge_attribute.exr", bytes + exr.substr(8));
    REQUIRE_THROWS_WITH(image::read_rgb(path), Contains(path) && Contains("truncated OpenEXR header: attribute \"comments\" "
                                                                          "(string) at byte 8 declares 2147483647 bytes"));
  }
  SECTION("a fixed-size type with another size (OpenEXR reads its own 16 bytes and loses its place)") {
    std::string bytes = exr.substr(0, 8) + exr_attribute("dataWindow", "box2i", box2i(0, 0, 1, 1) + std::string(128, 'x'));
    const std::string path = put("long_box.exr", bytes + exr.substr(8));
    REQUIRE_THROWS_WITH(image::read_rgb(path), Contains("declares 144 bytes, but a box2i value needs 16 bytes"));
  }
  SECTION("a data window beyond prt's limits") {
    const std::string path = put("wide.exr", float_exr(header_end, box2i(0, 0, 99999, 0)));
    REQUIRE_THROWS_WITH(image::read_rgb(path), Contains(path) && Contains("image of 100000x1 pixels") &&
                                                   Contains("exceeds prt's limits"));
  }
}

// A BMP: the 14-byte file header, then a 40-byte BITMAPINFOHEADER of the given size, 24 bits per pixel
// and `compression` (0 none, 1 RLE8), then `pixels`.
std::string bmp(std::int32_t width, std::int32_t height, std::uint32_t compression, const std::string& pixels) {
  std::string out = "BM";
  put32(out, static_cast<std::uint32_t>(54 + pixels.size()));
  put32(out, 0);
  put32(out, 54);
  for (std::uint32_t v : {40u, std::uint32_t(width), std::uint32_t(height)}) put32(out, v);
  out += std::string{1, 0, char(compression == 1 ? 8 : 24), 0};  // planes, bits per pixel
  for (std::uint32_t v : {compression, std::uint32_t(pixels.size()), 2835u, 2835u, 0u, 0u}) put32(out, v);
  return out + pixels;
}

TEST_CASE("BMP sides beyond prt's limits are refused before OpenImageIO allocates by them", "[hardening][image]") {
  // A valid 2x1 BMP first (rows bottom-up, BGR, padded to 4 bytes): pixels (255, 0, 0) and (0, 0, 255).
  const image::Image im = image::read_rgb(put("two.bmp", bmp(2, 1, 0, std::string{0, 0, char(255), char(255), 0, 0, 0, 0})));
  REQUIRE(im.width == 2);
  REQUIRE(im.height == 1);
  REQUIRE(im.pixels == std::vector<float>{1, 0, 0, 0, 0, 1});
  // The fuzz target's crash (corpus/image/bmp_rle_height.bmp): an RLE8 BMP of 4 x -989888509 rows,
  // whose width x height OpenImageIO 2.4 computed in int: "vector::_M_default_append" escaped as an
  // internal error (exit status 2), or std::terminate under ASan.
  for (std::int32_t height : {-989888509, 989888509, 40000}) {
    const std::string path = put("tall.bmp", bmp(4, height, 1, std::string(16, '\0')));
    REQUIRE_THROWS_WITH(image::read_rgb(path), Contains(path) && Contains("exceeds prt's limits"));
  }
  // The 12-byte OS/2 header's uint16 sides: 65535 x 65535 also overflowed int.
  std::string os2 = "BM";
  put32(os2, 14 + 12 + 16);
  put32(os2, 0);
  put32(os2, 26);
  put32(os2, 12);
  os2 += std::string{char(255), char(255), char(255), char(255), 1, 0, 24, 0} + std::string(16, '\0');
  REQUIRE_THROWS_WITH(image::read_rgb(put("os2.bmp", os2)), Contains("image of 65535x65535 pixels"));
}

TEST_CASE("an image taller than one decoding band reads back exactly", "[hardening][image]") {
  // 1200 x 1200 8-bit RGB: 3600-byte rows, so more than one 4 MiB band of rows (oiio_backend.cpp).
  const int w = 1200, h = 1200;
  image::Image pattern(w, h, 3);
  auto level = [](int x, int y, int c) { return (7 * x + 13 * y + 101 * c) % 256; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) pattern.at(x, y, c) = float(level(x, y, c) / 255.0);
  const std::string path = temp_folder("hardening_images") + "/bands.png";
  image::write(path, pattern);
  const image::Image back = image::read_rgb(path);
  REQUIRE(back.width == w);
  REQUIRE(back.height == h);
  int wrong = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        wrong += std::abs(back.at(x, y, c) - srgb_to_linear_truth(level(x, y, c) / 255.0)) > 1e-6;
  REQUIRE(wrong == 0);
}

}  // namespace
}  // namespace prt::test
