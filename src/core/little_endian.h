#pragma once
// Little-endian packing of binary file fields (every prt binary format is little-endian whatever the
// host): append to a byte string, read from bytes. Readers do not check bounds: callers check sizes.
#include <cstdint>
#include <cstring>
#include <string>

namespace prt::le {

inline void put_u32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xffu));
}
inline void put_u64(std::string& out, std::uint64_t v) {
  for (int b = 0; b < 8; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xffu));
}
inline void put_f32(std::string& out, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  put_u32(out, bits);
}
inline void put_f64(std::string& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  put_u64(out, bits);
}

inline std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int b = 0; b < 4; ++b) v |= static_cast<std::uint32_t>(p[b]) << (8 * b);
  return v;
}
inline std::uint64_t get_u64(const unsigned char* p) {
  return get_u32(p) | (static_cast<std::uint64_t>(get_u32(p + 4)) << 32);
}
inline double get_f64(const unsigned char* p) {
  const std::uint64_t bits = get_u64(p);
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}
/// The same, at byte offset `at` of `bytes`.
inline std::uint32_t get_u32(const std::string& bytes, std::size_t at) {
  return get_u32(reinterpret_cast<const unsigned char*>(bytes.data()) + at);
}
inline std::uint64_t get_u64(const std::string& bytes, std::size_t at) {
  return get_u64(reinterpret_cast<const unsigned char*>(bytes.data()) + at);
}

}  // namespace prt::le
