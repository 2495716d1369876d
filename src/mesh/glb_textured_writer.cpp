// glTF 2.0 binary (.glb) output of a mesh with its lightmap UVs and images in the BIN chunk, referenced
// by an application extension (writers.h, write_glb_textured).
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/glb_builder.h"
#include "mesh/writers.h"

namespace prt::mesh {

namespace {

// One output vertex per distinct (mesh vertex, corner UV bits) pair, in order of first use by the
// corners (deterministic; a vertex on a UV seam is split, every other vertex kept once).
struct SplitMesh {
  std::vector<std::uint32_t> source;  ///< per output vertex: the mesh vertex
  std::vector<glm::vec2> uv;          ///< per output vertex
  std::vector<std::uint32_t> indices; ///< per corner
};

SplitMesh split_by_uv(const Mesh& mesh) {
  SplitMesh out;
  std::map<std::pair<std::uint32_t, std::uint64_t>, std::uint32_t> seen;
  out.indices.reserve(mesh.indices.size());
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    const glm::vec2 uv = mesh.lightmap_uv[corner];
    std::uint32_t bits[2];
    std::memcpy(bits, &uv, sizeof bits);
    const auto key = std::make_pair(mesh.indices[corner], (static_cast<std::uint64_t>(bits[1]) << 32) | bits[0]);
    const auto found = seen.emplace(key, static_cast<std::uint32_t>(out.source.size()));
    if (found.second) {
      out.source.push_back(mesh.indices[corner]);
      out.uv.push_back(uv);
    }
    out.indices.push_back(found.first->second);
  }
  return out;
}

}  // namespace

namespace {

void check_lightmap_uv(const std::string& path, const Mesh& mesh) {
  glb::check_mesh(path, mesh);
  if (mesh.lightmap_uv.size() != mesh.indices.size()) fail_file(path, "cannot write glTF: the mesh has no lightmap UVs");
  for (const glm::vec2& uv : mesh.lightmap_uv)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) fail_file(path, "cannot write glTF: a lightmap UV is not finite");
}

// The primitive of the split mesh: POSITION, NORMAL (if any), the lightmap UVs as `uv_attribute`, indices.
nlohmann::json split_primitive(glb::Builder& glb, const Mesh& mesh, const char* uv_attribute) {
  const SplitMesh split = split_by_uv(mesh);
  Mesh out;
  out.positions.reserve(split.source.size());
  for (std::uint32_t v : split.source) out.positions.push_back(mesh.positions[v]);
  if (!mesh.normals.empty())
    for (std::uint32_t v : split.source) out.normals.push_back(mesh.normals[v]);
  nlohmann::json attributes = nlohmann::json::object();
  attributes["POSITION"] = glb.add_positions(out.positions);
  if (!out.normals.empty()) attributes["NORMAL"] = glb.add_floats(&out.normals[0].x, out.normals.size(), 3, "VEC3");
  attributes[uv_attribute] = glb.add_floats(&split.uv[0].x, split.uv.size(), 2, "VEC2");
  const int indices = glb.add_indices(split.indices);
  return {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
}

nlohmann::json one_mesh_document(const glb::Builder& glb, const nlohmann::json& primitive) {
  return {
      {"asset", {{"version", "2.0"}, {"generator", "prt"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {primitive}}}}},
      {"bufferViews", glb.buffer_views},
      {"accessors", glb.accessors},
  };
}

}  // namespace

void write_glb_textured(const std::string& path, const Mesh& mesh, const std::vector<GlbImage>& images,
                        const std::string& extension_name, const std::string& extension_json) {
  check_lightmap_uv(path, mesh);
  const nlohmann::json extension = nlohmann::json::parse(extension_json, nullptr, false);
  if (!extension.is_object()) fail_file(path, "cannot write glTF: the " + extension_name + " extension is not a JSON object");

  glb::Builder glb;
  nlohmann::json primitive = split_primitive(glb, mesh, "TEXCOORD_0");
  nlohmann::json gltf_images = nlohmann::json::array();
  for (const GlbImage& image : images)
    gltf_images.push_back({{"bufferView", glb.add_view(image.bytes)}, {"mimeType", image.mime_type}});
  primitive["extensions"][extension_name] = extension;
  nlohmann::json document = one_mesh_document(glb, primitive);
  document["extensionsUsed"] = {extension_name};
  if (!gltf_images.empty()) document["images"] = gltf_images;
  write_file_atomically(path, glb::container(path, document, glb.bin));
}

void write_glb_lightmap_uv(const std::string& path, const Mesh& mesh) {
  check_lightmap_uv(path, mesh);
  glb::Builder glb;
  const nlohmann::json primitive = split_primitive(glb, mesh, "TEXCOORD_1");
  write_file_atomically(path, glb::container(path, one_mesh_document(glb, primitive), glb.bin));
}

}  // namespace prt::mesh
