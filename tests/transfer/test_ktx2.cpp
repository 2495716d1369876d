// KTX2 RGBA16F files (transfer/ktx2.h): the header fields at the KTX 2.0 specification's offsets (read
// here byte by byte), the level data in layer, row, texel order as float16 of the input, the reader
// returning what was written, and refusals of bad sizes and foreign files.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include "core/error.h"
#include "transfer/half.h"
#include "transfer/ktx2.h"

using namespace prt;
using namespace prt::transfer;

namespace {

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t(static_cast<unsigned char>(b[at + k])) << (8 * k);
  return v;
}
std::uint64_t u64(const std::string& b, std::size_t at) { return u32(b, at) | (std::uint64_t(u32(b, at + 4)) << 32); }

}  // namespace

TEST_CASE("KTX2 RGBA16F 2D arrays: header fields, level layout, round trip", "[transfer][ktx2]") {
  Ktx2Image image;
  image.width = 5;
  image.height = 3;
  image.layers = 2;
  for (int layer = 0; layer < 2; ++layer)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 5; ++x)
        for (int c = 0; c < 4; ++c) image.rgba.push_back(1000.0f * layer + 100.0f * y + 10.0f * x + c + 0.1f);
  const std::string bytes = write_ktx2_rgba16f(image);
  CHECK(bytes.substr(0, 12) == std::string("\xABKTX 20\xBB\r\n\x1A\n", 12));
  CHECK(u32(bytes, 12) == 97);  // VK_FORMAT_R16G16B16A16_SFLOAT
  CHECK(u32(bytes, 16) == 2);   // typeSize
  CHECK(u32(bytes, 20) == 5);
  CHECK(u32(bytes, 24) == 3);
  CHECK(u32(bytes, 28) == 0);   // pixelDepth: 2D
  CHECK(u32(bytes, 32) == 2);   // layerCount
  CHECK(u32(bytes, 36) == 1);   // faceCount
  CHECK(u32(bytes, 40) == 1);   // levelCount
  CHECK(u32(bytes, 44) == 0);   // no supercompression
  const std::uint64_t offset = u64(bytes, 80), length = u64(bytes, 88);
  CHECK(offset % 8 == 0);
  CHECK(length == 5 * 3 * 2 * 8);
  CHECK(u64(bytes, 96) == length);
  REQUIRE(offset + length == bytes.size());
  // Texel (x = 3, y = 2) of layer 1, channel 2: at ((layer * H + y) * W + x) * 4 + c halves.
  const std::size_t at = offset + 2 * (((1 * 3 + 2) * 5 + 3) * 4 + 2);
  const auto bits = static_cast<std::uint16_t>(static_cast<unsigned char>(bytes[at]) | (static_cast<unsigned char>(bytes[at + 1]) << 8));
  CHECK(bits == float_to_half(1232.1f));

  const Ktx2Image back = read_ktx2_rgba16f(bytes, "t.ktx2");
  CHECK(back.width == 5);
  CHECK(back.height == 3);
  CHECK(back.depth == 0);
  CHECK(back.layers == 2);
  REQUIRE(back.rgba.size() == image.rgba.size());
  for (std::size_t k = 0; k < image.rgba.size(); ++k) CHECK(back.rgba[k] == half_to_float(float_to_half(image.rgba[k])));
}

TEST_CASE("KTX2 writer and reader refuse what they do not support", "[transfer][ktx2]") {
  Ktx2Image image;
  image.width = 2;
  image.height = 2;
  image.rgba.assign(15, 0.0f);
  CHECK_THROWS_WITH(write_ktx2_rgba16f(image), Catch::Contains("does not match"));
  image.rgba.assign(16, 0.0f);
  image.depth = 2;
  image.layers = 2;
  CHECK_THROWS_WITH(write_ktx2_rgba16f(image), Catch::Contains("3D texture array"));
  image.depth = 0;
  image.layers = 0;
  std::string bytes = write_ktx2_rgba16f(image);
  CHECK_THROWS_WITH(read_ktx2_rgba16f(bytes.substr(0, bytes.size() - 1), "short.ktx2"), Catch::Contains("short.ktx2: KTX2 level 0 has the wrong size"));
  bytes[12] = 98;  // another format
  CHECK_THROWS_WITH(read_ktx2_rgba16f(bytes, "f.ktx2"), Catch::Contains("not R16G16B16A16_SFLOAT"));
  CHECK_THROWS_WITH(read_ktx2_rgba16f("PNG", "p.png"), Catch::Contains("not a KTX2 file"));
}
