// The engine glTF of a mesh as loaded (engine_gltf.h): an OBJ or PLY source, or a glTF source whose
// lightmap UVs were generated. One node, one mesh, one primitive per material, the vertices split by UV,
// the materials as pbrMetallicRoughness with embedded PNG/JPEG files.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "mesh/engine_gltf_detail.h"

namespace prt::mesh::detail {

namespace {

using nlohmann::json;

// The triangles of one primitive, with a vertex per distinct (mesh vertex, corner UVs) in order of
// first use by the corners.
struct Part {
  std::size_t material = 0;
  int group = 0;                      // EngineExtras::triangle_group
  std::vector<std::uint32_t> source;  // per output vertex: the mesh vertex
  std::vector<glm::vec2> uv0, uv1;    // per output vertex (empty without those UVs)
  std::vector<std::uint32_t> indices;
};

// The corner UVs of TEXCOORD_0 and TEXCOORD_1 (null: not written). Lightmap UVs of set 1 (generated, or
// a glTF's TEXCOORD_1): TEXCOORD_0 the base colour UVs, TEXCOORD_1 the lightmap UVs. Otherwise TEXCOORD_0
// the base colour UVs, else the lightmap UVs (OBJ and PLY take both from the same "vt" / u, v), and the
// lightmap UVs as TEXCOORD_1 when they are others.
struct CornerUvs {
  const std::vector<glm::vec2>* uv0 = nullptr;
  const std::vector<glm::vec2>* uv1 = nullptr;
};

CornerUvs corner_uvs(const Mesh& mesh) {
  CornerUvs out;
  if (mesh.has_lightmap_uv() && mesh.lightmap_uv_set == 1) {
    if (mesh.textured()) out.uv0 = &mesh.base_color_uv;
    out.uv1 = &mesh.lightmap_uv;
    return out;
  }
  out.uv0 = mesh.textured() ? &mesh.base_color_uv : &mesh.lightmap_uv;
  if (mesh.textured() && mesh.has_lightmap_uv() && mesh.lightmap_uv != mesh.base_color_uv) out.uv1 = &mesh.lightmap_uv;
  return out;
}

// One part per (material, group) in material order, then group order (the triangles of material m and
// group g, in mesh order); one material for a mesh without materials. Parts without triangles are left empty.
std::vector<Part> split(const Mesh& mesh, const std::vector<std::uint8_t>& triangle_group) {
  const CornerUvs uvs = corner_uvs(mesh);
  const std::size_t groups = triangle_group.empty() ? 1 : std::size_t(*std::max_element(triangle_group.begin(), triangle_group.end())) + 1;
  std::vector<Part> parts(std::max<std::size_t>(mesh.materials.size(), 1) * groups);
  for (std::size_t p = 0; p < parts.size(); ++p) parts[p].material = p / groups, parts[p].group = int(p % groups);
  std::vector<std::map<std::tuple<std::uint32_t, std::uint64_t, std::uint64_t>, std::uint32_t>> seen(parts.size());
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    const std::size_t material = mesh.materials.empty() ? 0 : mesh.triangle_material[corner / 3];
    const std::size_t m = material * groups + (triangle_group.empty() ? 0 : triangle_group[corner / 3]);
    std::uint64_t key0 = 0, key1 = 0;
    if (uvs.uv0 && !uvs.uv0->empty()) std::memcpy(&key0, &(*uvs.uv0)[corner], sizeof key0);
    if (uvs.uv1) std::memcpy(&key1, &(*uvs.uv1)[corner], sizeof key1);
    const auto found = seen[m].emplace(std::make_tuple(mesh.indices[corner], key0, key1), std::uint32_t(parts[m].source.size()));
    if (found.second) {
      parts[m].source.push_back(mesh.indices[corner]);
      if (uvs.uv0 && !uvs.uv0->empty()) parts[m].uv0.push_back((*uvs.uv0)[corner]);
      if (uvs.uv1) parts[m].uv1.push_back((*uvs.uv1)[corner]);
    }
    parts[m].indices.push_back(found.first->second);
  }
  return parts;
}

int wrap_code(Wrap wrap) { return wrap == Wrap::repeat ? 10497 : wrap == Wrap::clamp_to_edge ? 33071 : 33648; }

// A texture's image: its file's bytes (OBJ map_Kd), or for a glTF source the bytes of the glTF image it
// was decoded from (Texture::source "image N (...)"), when PNG or JPEG (what glTF core allows); else none
// (-1, with a note on stderr naming the image).
int image_of(glb::Builder& glb, const std::string& source, const Texture& texture, json* images) {
  std::string bytes;
  const std::string ext = lower_extension(source);
  if (std::filesystem::is_regular_file(texture.source)) {
    bytes = read_file(texture.source);
  } else if ((ext == ".gltf" || ext == ".glb") && texture.source.rfind("image ", 0) == 0) {
    bytes = GltfExtras(source).image(std::stoi(texture.source.substr(6)), "texture");
  }
  const std::string mime = image_mime_type(bytes, texture.source);
  if (bytes.empty() || (mime != "image/png" && mime != "image/jpeg")) {
    std::fprintf(stderr, "prt: %s: not a PNG or JPEG file; the glTF material keeps its base colour factor alone\n",
                 texture.source.c_str());
    return -1;
  }
  images->push_back({{"bufferView", glb.add_view(bytes)}, {"mimeType", mime}});
  return int(images->size() - 1);
}

// The materials (pbrMetallicRoughness), and in *out the textures, samplers and images they use.
json materials(glb::Builder& glb, const std::string& source, const Mesh& mesh, json* out) {
  json materials = json::array(), textures = json::array(), samplers = json::array(), images = json::array();
  std::map<int, int> image_index;  // Mesh::textures index -> glTF image (-1: none)
  for (const Material& m : mesh.materials) {
    json pbr = {{"baseColorFactor", {m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b, 1.0}},
                {"metallicFactor", m.metallic_factor}, {"roughnessFactor", m.roughness_factor}};
    if (m.textured() && !image_index.count(m.base_color.image))
      image_index[m.base_color.image] = image_of(glb, source, mesh.textures[std::size_t(m.base_color.image)], &images);
    if (m.textured() && image_index[m.base_color.image] >= 0) {
      const TextureRef& t = m.base_color;
      samplers.push_back({{"wrapS", wrap_code(t.wrap_s)}, {"wrapT", wrap_code(t.wrap_t)},
                          {"magFilter", t.filter == Filter::linear ? 9729 : 9728}});
      textures.push_back({{"source", image_index[t.image]}, {"sampler", samplers.size() - 1}});
      json info = {{"index", textures.size() - 1}, {"texCoord", 0}};
      const TextureTransform& x = t.transform;
      if (x.offset != glm::vec2(0.0f) || x.rotation != 0.0f || x.scale != glm::vec2(1.0f)) {
        info["extensions"]["KHR_texture_transform"] = {
            {"offset", {x.offset.x, x.offset.y}}, {"rotation", x.rotation}, {"scale", {x.scale.x, x.scale.y}}};
        json& used = (*out)["extensionsUsed"];
        if (std::find(used.begin(), used.end(), "KHR_texture_transform") == used.end()) used.push_back("KHR_texture_transform");
      }
      pbr["baseColorTexture"] = info;
    }
    materials.push_back({{"name", m.name}, {"pbrMetallicRoughness", pbr}});
  }
  if (!textures.empty()) (*out)["textures"] = textures;
  if (!samplers.empty()) (*out)["samplers"] = samplers;
  if (!images.empty()) (*out)["images"] = images;
  return materials;
}

json primitive(glb::Builder& glb, const Mesh& mesh, const Part& part, const EngineExtras& extras, const EngineIndices& added) {
  json attributes = json::object();
  std::vector<glm::vec3> positions, normals, colours;
  for (std::uint32_t v : part.source) {
    positions.push_back(mesh.positions[v]);
    normals.push_back(mesh.normals[v]);
    if (!mesh.vertex_color.empty()) colours.push_back(mesh.vertex_color[v]);
  }
  attributes["POSITION"] = glb.add_positions(positions);
  attributes["NORMAL"] = glb.add_floats(&normals[0].x, normals.size(), 3, "VEC3");
  if (!part.uv0.empty()) attributes["TEXCOORD_0"] = glb.add_floats(&part.uv0[0].x, part.uv0.size(), 2, "VEC2");
  if (!part.uv1.empty()) attributes["TEXCOORD_1"] = glb.add_floats(&part.uv1[0].x, part.uv1.size(), 2, "VEC2");
  // glTF's texture coordinate sets start at 0: without base colour UVs, set 0 is the same accessor.
  if (part.uv0.empty() && !part.uv1.empty()) attributes["TEXCOORD_0"] = attributes["TEXCOORD_1"];
  if (!colours.empty()) attributes["COLOR_0"] = glb.add_floats(&colours[0].x, colours.size(), 3, "VEC3");
  for (const EngineAttribute& a : extras.attributes)
    if (a.group < 0 || a.group == part.group) attributes[a.name] = add_attribute_gather(glb, a, part.source);
  json out = {{"attributes", attributes}, {"indices", glb.add_indices(part.indices)}, {"mode", 4}};
  if (extras.extension.empty()) return out;
  json ext = extras.primitive(added, part.group);
  if (extras.lightmap_set >= 0 && ext.contains("texCoord")) ext["texCoord"] = part.uv1.empty() ? 0 : 1;  // the set the lightmap UVs are written as
  out["extensions"][extras.extension] = ext;
  return out;
}

}  // namespace

std::string engine_glb_from_mesh(const std::string& path, const std::string& source, const Mesh& mesh, const EngineExtras& extras) {
  if (extras.lightmap_set >= 0 && !mesh.has_lightmap_uv()) fail_file(path, "cannot write glTF: the mesh has no lightmap UVs");
  glb::Builder glb;
  EngineIndices added;
  added.arrays = add_arrays(glb, extras.arrays);
  json out = {{"asset", {{"version", "2.0"}, {"generator", "prt"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}}, {"extensionsUsed", json::array()}};
  if (!mesh.materials.empty()) out["materials"] = materials(glb, source, mesh, &out);
  json images = out.value("images", json::array());
  for (const GlbImage& image : extras.images) {
    added.images.push_back(int(images.size()));
    images.push_back({{"bufferView", glb.add_view(image.bytes)}, {"mimeType", image.mime_type}});
  }
  if (!images.empty()) out["images"] = images;
  json primitives = json::array();
  const std::vector<Part> parts = split(mesh, extras.triangle_group);
  for (const Part& part : parts) {
    if (part.indices.empty()) continue;
    json p = primitive(glb, mesh, part, extras, added);
    check_attribute_count(path, p["attributes"].size(), "primitive " + std::to_string(primitives.size()));
    if (!mesh.materials.empty()) p["material"] = part.material;
    primitives.push_back(p);
  }
  out["meshes"] = {{{"primitives", primitives}}};
  if (!extras.extension.empty()) {
    out["extensionsUsed"].push_back(extras.extension);
    out["extensions"][extras.extension] = extras.root(added);
  }
  if (out["extensionsUsed"].empty()) out.erase("extensionsUsed");
  out["bufferViews"] = glb.buffer_views;
  out["accessors"] = glb.accessors;
  return glb::container(path, out, glb.bin);
}

}  // namespace prt::mesh::detail
