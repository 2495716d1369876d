#include "lightmap/mixed_scenes.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "lightmap/lightmap_scenes.h"

namespace prt::test {

mesh::Mesh room_with_box(bool with_box, std::vector<NamedPart>& parts) {
  QuadBuilder b;
  b.mesh = floor_and_box(with_box);
  parts = {{"Floor", 0, 2}};
  if (with_box) parts.push_back({"Box", 2, 12});
  const glm::vec2 uv[4] = {{0.81f, 0.01f}, {0.81f, 0.59f}, {0.99f, 0.59f}, {0.99f, 0.01f}};
  b.quad({{1, 0, 1}, {-1, 0, 1}, {-1, 0.6f, 1}, {1, 0.6f, 1}}, {0, 0, -1}, uv);
  parts.push_back({"Wall", b.mesh.triangle_count() - 2, 2});
  return b.mesh;
}

namespace {

template <class T>
std::size_t append(std::string& bin, const std::vector<T>& values) {
  while (bin.size() % 4) bin.push_back('\0');
  const std::size_t offset = bin.size();
  bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  return offset;
}

}  // namespace

void write_gltf_parts(const std::string& path, const mesh::Mesh& m, const std::vector<NamedPart>& parts) {
  using nlohmann::json;
  const std::string bin_name = std::filesystem::path(path).stem().string() + ".bin";
  std::string bin;
  json j = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", json::array()}}}}};
  auto view = [&](std::size_t offset, std::size_t bytes, int target) {
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    return j["bufferViews"].size() - 1;
  };
  auto accessor = [&](std::size_t view_index, int component, std::size_t count, const char* type) {
    j["accessors"].push_back({{"bufferView", view_index}, {"componentType", component}, {"count", count}, {"type", type}});
    return j["accessors"].size() - 1;
  };
  for (const NamedPart& part : parts) {
    std::map<std::uint32_t, std::uint32_t> local;  // mesh vertex -> part vertex, in order of first use
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices;
    for (std::size_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = m.indices[3 * t + k];
        auto [it, added] = local.emplace(v, std::uint32_t(positions.size()));
        if (added) positions.push_back(m.positions[v]), normals.push_back(m.normals[v]), uvs.push_back(m.lightmap_uv[3 * t + k]);
        indices.push_back(it->second);
      }
    const std::size_t p = accessor(view(append(bin, positions), positions.size() * 12, 34962), 5126, positions.size(), "VEC3");
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& q : positions) lo = glm::min(lo, q), hi = glm::max(hi, q);
    j["accessors"][p]["min"] = {lo.x, lo.y, lo.z};
    j["accessors"][p]["max"] = {hi.x, hi.y, hi.z};
    const std::size_t n = accessor(view(append(bin, normals), normals.size() * 12, 34962), 5126, normals.size(), "VEC3");
    const std::size_t u = accessor(view(append(bin, uvs), uvs.size() * 8, 34962), 5126, uvs.size(), "VEC2");
    const std::size_t i = accessor(view(append(bin, indices), indices.size() * 4, 34963), 5125, indices.size(), "SCALAR");
    const json primitive = {{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", u}}}, {"indices", i}};
    j["meshes"].push_back({{"primitives", json::array({primitive})}});
    j["nodes"].push_back({{"name", part.name}, {"mesh", j["meshes"].size() - 1}});
    j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  }
  j["buffers"] = {{{"uri", bin_name}, {"byteLength", bin.size()}}};
  std::ofstream(std::filesystem::path(path).parent_path() / bin_name, std::ios::binary) << bin;
  std::ofstream(path) << j.dump();
}

}  // namespace prt::test
