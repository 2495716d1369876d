// glTF 2.0 binary (.glb) output with application-specific vertex attributes (layout in writers.h).
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/little_endian.h"
#include "mesh/glb_builder.h"
#include "mesh/writers.h"

namespace prt::mesh {

namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;

using le::put_u32;

// COLOR_0 from linear radiance: Reinhard's x / (1 + x) per channel, in [0, 1) as glTF requires
// (negative and NaN values become 0, +Inf becomes 1).
std::vector<glm::vec3> tone_mapped(const std::vector<glm::vec3>& radiance) {
  std::vector<glm::vec3> out(radiance.size());
  for (std::size_t i = 0; i < radiance.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = radiance[i][c];
      out[i][c] = !(x > 0.0f) ? 0.0f : (std::isinf(x) ? 1.0f : x / (1.0f + x));
    }
  return out;
}

}  // namespace

namespace glb {

bool valid_semantic(const std::string& name) {
  if (name.size() < 2 || name[0] != '_') return false;
  for (char c : name)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

const char* accessor_type(int components) {
  static const char* names[] = {"SCALAR", "VEC2", "VEC3", "VEC4"};
  return names[components - 1];
}

void check_mesh(const std::string& path, const Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  if (n == 0 || mesh.indices.empty()) fail_file(path, "cannot write glTF: the mesh is empty");
  if (mesh.indices.size() % 3 != 0) fail_file(path, "cannot write glTF: index count is not a multiple of 3");
  for (std::uint32_t index : mesh.indices)
    if (index >= n) fail_file(path, "cannot write glTF: index " + std::to_string(index) + " out of range");
  for (const glm::vec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail_file(path, "cannot write glTF: a position is not finite");
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    fail_file(path, "cannot write glTF: normal count differs from vertex count");
}

int Builder::add(const std::string& bytes, std::size_t count, const char* type, int component_type, int target) {
  while (bin.size() % 4 != 0) bin.push_back('\0');
  buffer_views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}, {"target", target}});
  bin += bytes;
  accessors.push_back(
      {{"bufferView", buffer_views.size() - 1}, {"componentType", component_type}, {"count", count}, {"type", type}});
  return int(accessors.size() - 1);
}

int Builder::add_floats(const float* values, std::size_t count, int components, const char* type) {
  std::string bytes;
  bytes.reserve(count * std::size_t(components) * 4);
  for (std::size_t i = 0; i < count * std::size_t(components); ++i) le::put_f32(bytes, values[i]);
  return add(bytes, count, type, kFloat, kArrayBuffer);
}

int Builder::add_positions(const std::vector<glm::vec3>& positions) {
  const int position = add_floats(&positions[0].x, positions.size(), 3, "VEC3");
  glm::vec3 lo = positions[0], hi = positions[0];
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // Floats widen to double exactly and nlohmann prints the shortest round-trip text, so min/max
  // read back as exactly the extreme float values (the spec requires them to match the data).
  accessors[std::size_t(position)]["min"] = {double(lo.x), double(lo.y), double(lo.z)};
  accessors[std::size_t(position)]["max"] = {double(hi.x), double(hi.y), double(hi.z)};
  return position;
}

int Builder::add_indices(const std::vector<std::uint32_t>& indices) {
  std::string bytes;
  bytes.reserve(indices.size() * 4);
  for (std::uint32_t index : indices) put_u32(bytes, index);
  return add(bytes, indices.size(), "SCALAR", kUnsignedInt, kElementArrayBuffer);
}

int Builder::add_view(const std::string& bytes) {
  while (bin.size() % 4 != 0) bin.push_back('\0');
  buffer_views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
  bin += bytes;
  return int(buffer_views.size() - 1);
}

std::string container(const std::string& path, nlohmann::json document, std::string bin) {
  while (bin.size() % 4 != 0) bin.push_back('\0');
  document["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = document.dump();
  while (json.size() % 4 != 0) json.push_back(' ');  // the spec pads the JSON chunk with spaces
  const std::uint64_t total = 12 + 8 + json.size() + 8 + bin.size();
  if (total > std::numeric_limits<std::uint32_t>::max()) fail_file(path, "cannot write glTF: more than 4 GiB");
  std::string bytes;
  bytes.reserve(std::size_t(total));
  put_u32(bytes, kGlbMagic);
  put_u32(bytes, 2);
  put_u32(bytes, std::uint32_t(total));
  put_u32(bytes, std::uint32_t(json.size()));
  put_u32(bytes, kChunkJson);
  bytes += json;
  put_u32(bytes, std::uint32_t(bin.size()));
  put_u32(bytes, kChunkBin);
  bytes += bin;
  return bytes;
}

}  // namespace glb

void write_glb(const std::string& path, const Mesh& mesh, const std::vector<glm::vec3>& colour_0) {
  glb::check_mesh(path, mesh);
  const std::size_t n = mesh.positions.size();
  if (!colour_0.empty() && colour_0.size() != n)
    fail_file(path, "cannot write glTF: COLOR_0 length differs from vertex count");

  glb::Builder glb;
  nlohmann::json attributes = nlohmann::json::object();
  attributes["POSITION"] = glb.add_positions(mesh.positions);
  if (!mesh.normals.empty()) attributes["NORMAL"] = glb.add_floats(&mesh.normals[0].x, n, 3, "VEC3");
  if (!colour_0.empty()) {
    const std::vector<glm::vec3> display = tone_mapped(colour_0);
    attributes["COLOR_0"] = glb.add_floats(&display[0].x, n, 3, "VEC3");
    attributes["_PRT_RADIANCE"] = glb.add_floats(&colour_0[0].x, n, 3, "VEC3");
  }
  const int indices = glb.add_indices(mesh.indices);

  const nlohmann::json document = {
      {"asset", {{"version", "2.0"}, {"generator", "prt"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", indices}, {"mode", 4}}}}}}},
      {"bufferViews", glb.buffer_views},
      {"accessors", glb.accessors},
  };
  const std::string bytes = glb::container(path, document, glb.bin);
  write_file_atomically(path, bytes);
}

}  // namespace prt::mesh
