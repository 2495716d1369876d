// KTX2 RGBA16F textures (ktx2.h).
#include "transfer/ktx2.h"

#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "core/little_endian.h"
#include "transfer/half.h"

namespace prt::transfer {

namespace {

constexpr unsigned char kKtx2Identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kVkFormatR16G16B16A16Sfloat = 97;
constexpr std::size_t kHeaderBytes = 80 + 24;  // header + index, one level entry

using le::get_u32;
using le::get_u64;
using le::put_u32;
using le::put_u64;

// The Basic Data Format Descriptor for R16G16B16A16_SFLOAT (KTX 2.0 spec, section 3.10; Khronos Data
// Format spec 1.3, section 5): model RGBSDA, primaries BT.709, linear transfer, 8 bytes per texel,
// samples R, G, B, A of 16 bits each, qualifiers FLOAT | SIGNED, lower/upper -1.0f / 1.0f.
std::string basic_dfd() {
  std::string block;
  put_u32(block, 0);                                // vendorId 0 (Khronos), descriptorType 0 (basic)
  put_u32(block, 2u | (static_cast<std::uint32_t>(24 + 16 * 4) << 16));  // version 2, block size 88
  block.push_back(1);                               // colorModel KHR_DF_MODEL_RGBSDA
  block.push_back(1);                               // colorPrimaries KHR_DF_PRIMARIES_BT709
  block.push_back(1);                               // transferFunction KHR_DF_TRANSFER_LINEAR
  block.push_back(0);                               // flags: straight alpha
  for (int k = 0; k < 4; ++k) block.push_back(0);   // texelBlockDimension 1x1x1x1 (stored minus one)
  block.push_back(8);                               // bytesPlane0
  for (int k = 1; k < 8; ++k) block.push_back(0);
  const unsigned char channel[4] = {0, 1, 2, 15};   // R, G, B, A
  for (int s = 0; s < 4; ++s) {
    block.push_back(static_cast<char>((16 * s) & 0xFF));
    block.push_back(0);                             // bitOffset (u16)
    block.push_back(15);                            // bitLength - 1
    block.push_back(static_cast<char>(channel[s] | 0x80 | 0x40));  // FLOAT | SIGNED
    for (int k = 0; k < 4; ++k) block.push_back(0); // samplePosition
    put_u32(block, 0xBF800000u);                    // sampleLower -1.0f
    put_u32(block, 0x3F800000u);                    // sampleUpper 1.0f
  }
  std::string dfd;
  put_u32(dfd, static_cast<std::uint32_t>(4 + block.size()));
  return dfd + block;
}

std::uint64_t texel_count(const Ktx2Image& image) {
  return static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height) *
         static_cast<std::uint64_t>(image.depth > 0 ? image.depth : 1) * static_cast<std::uint64_t>(image.layers > 0 ? image.layers : 1);
}

}  // namespace

std::string write_ktx2_rgba16f(const Ktx2Image& image) {
  if (image.width < 1 || image.height < 1 || image.depth < 0 || image.layers < 0)
    fail("KTX2: texture size must be at least 1x1");
  if (image.depth > 0 && image.layers > 0) fail("KTX2: a 3D texture array is not supported");
  const std::uint64_t texels = texel_count(image);
  if (image.rgba.size() != texels * 4) fail("KTX2: texel data does not match the texture size");
  std::string data;
  data.reserve(static_cast<std::size_t>(texels * 8));
  for (float v : image.rgba) {
    const std::uint16_t h = float_to_half(v);
    data.push_back(static_cast<char>(h & 0xFF));
    data.push_back(static_cast<char>(h >> 8));
  }
  const std::string dfd = basic_dfd();
  std::string kvd;
  const std::string key = std::string("KTXwriter") + '\0' + "prt 0.1.0" + '\0';
  put_u32(kvd, static_cast<std::uint32_t>(key.size()));
  kvd += key;
  while (kvd.size() % 4 != 0) kvd.push_back('\0');
  const std::size_t dfd_offset = kHeaderBytes;
  const std::size_t kvd_offset = dfd_offset + dfd.size();
  std::size_t data_offset = kvd_offset + kvd.size();
  while (data_offset % 8 != 0) ++data_offset;  // level data aligned to lcm(texel size 8, 4)

  std::string out(reinterpret_cast<const char*>(kKtx2Identifier), 12);
  put_u32(out, kVkFormatR16G16B16A16Sfloat);
  put_u32(out, 2);  // typeSize
  put_u32(out, static_cast<std::uint32_t>(image.width));
  put_u32(out, static_cast<std::uint32_t>(image.height));
  put_u32(out, static_cast<std::uint32_t>(image.depth));
  put_u32(out, static_cast<std::uint32_t>(image.layers));
  put_u32(out, 1);  // faceCount
  put_u32(out, 1);  // levelCount
  put_u32(out, 0);  // supercompressionScheme: none
  put_u32(out, static_cast<std::uint32_t>(dfd_offset));
  put_u32(out, static_cast<std::uint32_t>(dfd.size()));
  put_u32(out, static_cast<std::uint32_t>(kvd_offset));
  put_u32(out, static_cast<std::uint32_t>(kvd.size()));
  put_u64(out, 0);  // sgdByteOffset
  put_u64(out, 0);  // sgdByteLength
  put_u64(out, data_offset);
  put_u64(out, data.size());  // byteLength
  put_u64(out, data.size());  // uncompressedByteLength
  out += dfd;
  out += kvd;
  out.resize(data_offset, '\0');
  out += data;
  return out;
}

Ktx2Image read_ktx2_rgba16f(const std::string& bytes, const std::string& name) {
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kKtx2Identifier, 12) != 0) fail_file(name, "not a KTX2 file");
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (get_u32(p + 12) != kVkFormatR16G16B16A16Sfloat || get_u32(p + 16) != 2) fail_file(name, "KTX2 format is not R16G16B16A16_SFLOAT");
  Ktx2Image t;
  t.width = static_cast<int>(get_u32(p + 20));
  t.height = static_cast<int>(get_u32(p + 24));
  t.depth = static_cast<int>(get_u32(p + 28));
  t.layers = static_cast<int>(get_u32(p + 32));
  if (t.width < 1 || t.height < 1 || t.depth < 0 || t.layers < 0 || (t.depth > 0 && t.layers > 0))
    fail_file(name, "KTX2 texture size is not supported");
  if (get_u32(p + 36) != 1 || get_u32(p + 40) != 1 || get_u32(p + 44) != 0)
    fail_file(name, "KTX2 file is not a single-level, single-face, uncompressed texture");
  const std::uint32_t dfd_offset = get_u32(p + 48), dfd_length = get_u32(p + 52);
  if (dfd_offset + static_cast<std::size_t>(dfd_length) > bytes.size() || bytes.compare(dfd_offset, dfd_length, basic_dfd()) != 0)
    fail_file(name, "KTX2 data format descriptor is not the expected RGBA16F one");
  const std::uint64_t offset = get_u64(p + 80), length = get_u64(p + 88);
  const std::uint64_t texels = texel_count(t);
  if (length != texels * 8 || offset > bytes.size() || length > bytes.size() - offset) fail_file(name, "KTX2 level 0 has the wrong size");
  t.rgba.resize(static_cast<std::size_t>(texels * 4));
  for (std::size_t k = 0; k < t.rgba.size(); ++k) {
    const std::size_t at = static_cast<std::size_t>(offset) + 2 * k;
    t.rgba[k] = half_to_float(static_cast<std::uint16_t>(p[at] | (p[at + 1] << 8)));
  }
  return t;
}

}  // namespace prt::transfer
