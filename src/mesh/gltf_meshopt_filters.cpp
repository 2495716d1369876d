// EXT_meshopt_compression's filters (the extension's spec, "Filters"), in float32 arithmetic in one
// fixed order, rounded to nearest even: the results of meshoptimizer's own decoders (its SIMD paths,
// which gltf-transform's WebAssembly decoder runs), bit for bit. Debian's libmeshoptimizer 0.18 is
// not used for them: its x86 filters differ from that in the last bit of about 1% of octahedral
// normals and require a count that is a multiple of 4. Built with -ffp-contract=off (CMakeLists.txt):
// a fused multiply-add would change the bits.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "mesh/gltf_compressed.h"

namespace prt::mesh::detail {

namespace {

/// Rounds to the nearest integer, ties to even (the default rounding mode); NaN gives 0. The value
/// is then wrapped to T's bits, as the spec's decoders keep the low bits.
template <typename T>
T round_to(float value) {
  if (!(value == value)) return T(0);
  return T(static_cast<std::int32_t>(std::nearbyint(value)));
}

/// OCTAHEDRAL: x, y signed K-bit octahedral coordinates, z the K-bit encoding of 1, w kept.
template <typename T>
void octahedral(unsigned char* data, std::size_t count, std::size_t stride) {
  const float one = float(std::numeric_limits<T>::max());
  for (std::size_t i = 0; i < count; ++i) {
    T v[3];
    std::memcpy(v, data + i * stride, sizeof(v));
    float x = float(v[0]), y = float(v[1]);
    // 16-bit z is read as 15 unsigned bits; 8-bit z as a signed byte.
    const float stored_z = sizeof(T) == 2 ? float(std::uint16_t(v[2]) & 0x7FFFu) : float(v[2]);
    const float z = stored_z - (std::fabs(x) + std::fabs(y));
    const float t = z < 0.0f ? z : 0.0f;  // fold the lower hemisphere back
    x = x >= 0.0f ? x + t : x - t;
    y = y >= 0.0f ? y + t : y - t;
    const float scale = one / std::sqrt(x * x + (y * y + z * z));
    const T out[3] = {round_to<T>(x * scale), round_to<T>(y * scale), round_to<T>(z * scale)};
    std::memcpy(data + i * stride, out, sizeof(out));
  }
}

/// QUATERNION (stride 8): x, y, z of a unit quaternion scaled by 1/sqrt(2), the fourth short's top
/// bits (with its two low bits set) their scale, its two low bits the index of the largest, omitted
/// component, rebuilt as sqrt(1 - x^2 - y^2 - z^2).
void quaternion(unsigned char* data, std::size_t count) {
  const float root_half = 1.0f / std::sqrt(2.0f);
  for (std::size_t i = 0; i < count; ++i) {
    std::int16_t v[4];
    std::memcpy(v, data + i * 8, sizeof(v));
    const float scale = root_half / float(std::int32_t(v[3]) | 3);
    const float x = float(v[0]) * scale, y = float(v[1]) * scale, z = float(v[2]) * scale;
    const float ww = 1.0f - (x * x + (y * y + z * z));
    const float w = std::sqrt(ww > 0.0f ? ww : 0.0f);
    const int largest = v[3] & 3;
    std::int16_t out[4];
    out[largest] = round_to<std::int16_t>(w * 32767.0f);
    out[(largest + 1) & 3] = round_to<std::int16_t>(x * 32767.0f);
    out[(largest + 2) & 3] = round_to<std::int16_t>(y * 32767.0f);
    out[(largest + 3) & 3] = round_to<std::int16_t>(z * 32767.0f);
    std::memcpy(data + i * 8, out, sizeof(out));
  }
}

/// EXPONENTIAL: each 32-bit word holds a signed 8-bit exponent e (top) and a signed 24-bit
/// mantissa m; the float m * 2^e, 2^e made from its bits as the spec's decoders make it.
void exponential(unsigned char* data, std::size_t words) {
  for (std::size_t i = 0; i < words; ++i) {
    std::uint32_t v;
    std::memcpy(&v, data + 4 * i, 4);
    const std::int32_t e = std::int32_t(v) >> 24;
    const std::int32_t m = std::int32_t(v << 8) >> 8;
    const std::uint32_t power_bits = std::uint32_t(e + 127) << 23;
    float power;
    std::memcpy(&power, &power_bits, 4);
    const float value = power * float(m);
    std::memcpy(data + 4 * i, &value, 4);
  }
}

}  // namespace

void apply_meshopt_filter(const std::string& filter, unsigned char* data, std::size_t count, std::size_t stride) {
  if (filter == "OCTAHEDRAL" && stride == 4) octahedral<std::int8_t>(data, count, stride);
  if (filter == "OCTAHEDRAL" && stride == 8) octahedral<std::int16_t>(data, count, stride);
  if (filter == "QUATERNION") quaternion(data, count);
  if (filter == "EXPONENTIAL") exponential(data, count * (stride / 4));
}

}  // namespace prt::mesh::detail
