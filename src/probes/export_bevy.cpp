// Bevy irradiance volume: a KTX2 3D texture of ambient cubes (see exporters.h, probes/bevy/README.md).
// KTX2 layout per the Khronos KTX 2.0 specification: 80-byte header + index, one level index entry,
// a Basic Data Format Descriptor (RGBSDA model, linear, 4 float16 samples), a KTXwriter key/value,
// then the level data (texels x fastest, then rows y, then slices z).
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "core/little_endian.h"
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "transfer/half.h"

namespace prt::probes {

namespace {

constexpr unsigned char kKtx2Identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kVkFormatR16G16B16A16Sfloat = 97;

using le::get_u32;
using le::get_u64;
using le::put_u32;
using le::put_u64;

using transfer::float_to_half;
using transfer::half_to_float;

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

}  // namespace

std::vector<glm::vec3> dilate_invalid(const ProbeSet& p) {
  const std::size_t n = p.coefficient_count(), count = p.count();
  std::vector<glm::vec3> values = p.coefficients;
  std::vector<std::uint8_t> known = p.valid;
  if (p.valid_count() == 0) fail("bevy: every probe is invalid (inside geometry): nothing to fill the volume with");
  const int nx = p.grid.counts[0], ny = p.grid.counts[1], nz = p.grid.counts[2];
  const int offsets[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // Each round fills every unknown cell that has known neighbours with their mean (computed from the
  // previous round's values only, so the result does not depend on traversal order).
  for (;;) {
    std::vector<std::size_t> filled;
    std::vector<glm::vec3> next = values;
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const std::size_t i = static_cast<std::size_t>(x) + nx * (static_cast<std::size_t>(y) + ny * static_cast<std::size_t>(z));
          if (known[i]) continue;
          int neighbours = 0;
          for (std::size_t k = 0; k < n; ++k) next[i * n + k] = glm::vec3(0.0f);
          for (const auto& o : offsets) {
            const int ax = x + o[0], ay = y + o[1], az = z + o[2];
            if (ax < 0 || ay < 0 || az < 0 || ax >= nx || ay >= ny || az >= nz) continue;
            const std::size_t j = static_cast<std::size_t>(ax) + nx * (static_cast<std::size_t>(ay) + ny * static_cast<std::size_t>(az));
            if (!known[j]) continue;
            ++neighbours;
            for (std::size_t k = 0; k < n; ++k) next[i * n + k] += values[j * n + k];
          }
          if (neighbours == 0) continue;
          for (std::size_t k = 0; k < n; ++k) next[i * n + k] /= static_cast<float>(neighbours);
          filled.push_back(i);
        }
    if (filled.empty()) break;
    for (std::size_t i : filled) known[i] = 1;
    values.swap(next);
  }
  (void)count;
  return values;
}

std::string format_bevy_ktx2(const ProbeSet& p) {
  check_probe_set(p, "Bevy export");
  if (p.layout != ProbeSet::Layout::grid) fail("--format bevy needs a probe grid (--grid): an irradiance volume is a 3D texture");
  const std::vector<glm::vec3> values = dilate_invalid(p);
  const std::size_t nx = p.grid.counts[0], ny = p.grid.counts[1], nz = p.grid.counts[2];
  const std::size_t width = nx, height = 2 * ny, depth = 3 * nz, n = p.coefficient_count();
  std::string texels(width * height * depth * 8, '\0');
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t y = 0; y < ny; ++y)
      for (std::size_t x = 0; x < nx; ++x) {
        const std::size_t probe = x + nx * (y + ny * z);
        sh::RgbCoefficients c(p.bands);
        for (std::size_t k = 0; k < n; ++k) c.values[k] = glm::dvec3(values[probe * n + k]);
        const std::array<glm::dvec3, 6> cube = bevy_ambient_cube(c);
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = 0; sign < 2; ++sign) {
            const glm::dvec3& v = cube[2 * axis + sign];
            const std::size_t tx = x, ty = y + ny * sign, tz = z + nz * axis;
            const std::size_t at = ((tz * height + ty) * width + tx) * 8;
            const std::uint16_t h[4] = {float_to_half(static_cast<float>(v.x)), float_to_half(static_cast<float>(v.y)),
                                        float_to_half(static_cast<float>(v.z)), float_to_half(1.0f)};
            for (int k = 0; k < 4; ++k) {
              texels[at + 2 * k] = static_cast<char>(h[k] & 0xFF);
              texels[at + 2 * k + 1] = static_cast<char>(h[k] >> 8);
            }
          }
      }

  const std::string dfd = basic_dfd();
  std::string kvd;
  {
    const std::string key = std::string("KTXwriter") + '\0' + "prt 0.1.0" + '\0';
    put_u32(kvd, static_cast<std::uint32_t>(key.size()));
    kvd += key;
    while (kvd.size() % 4 != 0) kvd.push_back('\0');
  }
  const std::size_t dfd_offset = 80 + 24;
  const std::size_t kvd_offset = dfd_offset + dfd.size();
  std::size_t data_offset = kvd_offset + kvd.size();
  while (data_offset % 8 != 0) ++data_offset;  // level data aligned to lcm(texel size 8, 4)

  std::string out(reinterpret_cast<const char*>(kKtx2Identifier), 12);
  put_u32(out, kVkFormatR16G16B16A16Sfloat);
  put_u32(out, 2);  // typeSize
  put_u32(out, static_cast<std::uint32_t>(width));
  put_u32(out, static_cast<std::uint32_t>(height));
  put_u32(out, static_cast<std::uint32_t>(depth));
  put_u32(out, 0);  // layerCount: not an array
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
  put_u64(out, texels.size());
  put_u64(out, texels.size());
  out += dfd;
  out += kvd;
  out.resize(data_offset, '\0');
  out += texels;
  return out;
}

Ktx2Texture read_bevy_ktx2(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 104 || std::memcmp(bytes.data(), kKtx2Identifier, 12) != 0) fail_file(name, "not a KTX2 file");
  if (get_u32(bytes, 12) != kVkFormatR16G16B16A16Sfloat || get_u32(bytes, 16) != 2)
    fail_file(name, "KTX2 format is not R16G16B16A16_SFLOAT");
  Ktx2Texture t;
  t.width = static_cast<int>(get_u32(bytes, 20));
  t.height = static_cast<int>(get_u32(bytes, 24));
  t.depth = static_cast<int>(get_u32(bytes, 28));
  if (get_u32(bytes, 32) != 0 || get_u32(bytes, 36) != 1 || get_u32(bytes, 40) != 1 || get_u32(bytes, 44) != 0)
    fail_file(name, "KTX2 file is not a single-level, single-face, non-array 3D texture");
  const std::uint32_t dfd_offset = get_u32(bytes, 48), dfd_length = get_u32(bytes, 52);
  if (dfd_offset + static_cast<std::size_t>(dfd_length) > bytes.size() || bytes.compare(dfd_offset, dfd_length, basic_dfd()) != 0)
    fail_file(name, "KTX2 data format descriptor is not the expected RGBA16F one");
  const std::uint64_t offset = get_u64(bytes, 80), length = get_u64(bytes, 88);
  const std::uint64_t texel_count = static_cast<std::uint64_t>(t.width) * t.height * t.depth;
  if (length != texel_count * 8 || offset + length > bytes.size()) fail_file(name, "KTX2 level 0 has the wrong size");
  t.rgba.resize(texel_count * 4);
  for (std::uint64_t k = 0; k < texel_count * 4; ++k) {
    const std::size_t at = static_cast<std::size_t>(offset + 2 * k);
    t.rgba[k] = half_to_float(static_cast<std::uint16_t>(static_cast<unsigned char>(bytes[at]) |
                                                     (static_cast<unsigned char>(bytes[at + 1]) << 8)));
  }
  return t;
}

}  // namespace prt::probes
