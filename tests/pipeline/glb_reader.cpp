#include "glb_reader.h"

#include <cstdint>
#include <cstring>

#include <catch2/catch.hpp>

#include "core/atomic_file.h"

namespace prt::test {

namespace {

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

}  // namespace

Glb parse_glb(const std::string& path) {
  const std::string b = read_file(path);
  REQUIRE(b.compare(0, 4, "glTF") == 0);
  REQUIRE(u32(b, 8) == b.size());
  const std::uint32_t json_length = u32(b, 12);
  Glb g{nlohmann::json::parse(b.substr(20, json_length)), {}};
  if (20 + json_length < b.size()) g.bin = b.substr(28 + json_length, u32(b, 20 + json_length));
  return g;
}

std::vector<float> floats(const Glb& g, int index) {
  const nlohmann::json& a = g.doc["accessors"][index];
  REQUIRE(a["componentType"] == 5126);
  const int width = a["type"] == "SCALAR" ? 1 : a["type"] == "VEC2" ? 2 : a["type"] == "VEC3" ? 3 : 4;
  const nlohmann::json& view = g.doc["bufferViews"][a["bufferView"].get<int>()];
  const std::size_t stride = view.value("byteStride", 4 * width), offset = view.value("byteOffset", 0) + a.value("byteOffset", 0);
  std::vector<float> out;
  for (std::size_t i = 0; i < a["count"].get<std::size_t>(); ++i)
    for (int c = 0; c < width; ++c) {
      float v;
      std::memcpy(&v, g.bin.data() + offset + i * stride + 4 * std::size_t(c), 4);
      out.push_back(v);
    }
  return out;
}

std::string view_bytes(const Glb& g, int index) {
  const nlohmann::json& view = g.doc["bufferViews"][index];
  return g.bin.substr(view.value("byteOffset", 0), view["byteLength"]);
}

}  // namespace prt::test
