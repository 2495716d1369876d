// The engine glTF of an OBJ or PLY source (engine_gltf.h): one node, one mesh, one primitive per
// material, the vertices split by UV, the materials as pbrMetallicRoughness with embedded PNG/JPEG.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "mesh/engine_gltf_detail.h"

namespace prt::mesh::detail {

namespace {

using nlohmann::json;

// The triangles of one primitive, with a vertex per distinct (mesh vertex, corner UV) pair in order
// of first use by the corners.
struct Part {
  std::vector<std::uint32_t> source;  // per output vertex: the mesh vertex
  std::vector<glm::vec2> uv;          // per output vertex (empty without UVs)
  std::vector<std::uint32_t> indices;
};

// The corner UVs that TEXCOORD_0 holds: the base colour UVs, else the lightmap UVs (OBJ and PLY take
// both from the same "vt" / u, v), else none.
const std::vector<glm::vec2>& corner_uvs(const Mesh& mesh) { return mesh.textured() ? mesh.base_color_uv : mesh.lightmap_uv; }

// One part per material in material order (the triangles of material m, in mesh order); one part for
// a mesh without materials. Parts without triangles are left empty.
std::vector<Part> split(const Mesh& mesh) {
  const std::vector<glm::vec2>& uvs = corner_uvs(mesh);
  std::vector<Part> parts(std::max<std::size_t>(mesh.materials.size(), 1));
  std::vector<std::map<std::pair<std::uint32_t, std::uint64_t>, std::uint32_t>> seen(parts.size());
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    const std::size_t m = mesh.materials.empty() ? 0 : mesh.triangle_material[corner / 3];
    std::uint64_t key = 0;
    if (!uvs.empty()) std::memcpy(&key, &uvs[corner], sizeof key);
    const auto found = seen[m].emplace(std::make_pair(mesh.indices[corner], key), std::uint32_t(parts[m].source.size()));
    if (found.second) {
      parts[m].source.push_back(mesh.indices[corner]);
      if (!uvs.empty()) parts[m].uv.push_back(uvs[corner]);
    }
    parts[m].indices.push_back(found.first->second);
  }
  return parts;
}

int wrap_code(Wrap wrap) { return wrap == Wrap::repeat ? 10497 : wrap == Wrap::clamp_to_edge ? 33071 : 33648; }

// A texture's image: its file's bytes when it is a PNG or JPEG file (what glTF core allows), else
// none (-1, with a note on stderr naming the file).
int image_of(glb::Builder& glb, const Texture& texture, json* images) {
  const std::string ext = lower_extension(texture.source);
  const bool png = ext == ".png", jpeg = ext == ".jpg" || ext == ".jpeg";
  if (!(png || jpeg) || !std::filesystem::is_regular_file(texture.source)) {
    std::fprintf(stderr, "prt: %s: not a PNG or JPEG file; the glTF material keeps its base colour factor alone\n",
                 texture.source.c_str());
    return -1;
  }
  images->push_back({{"bufferView", glb.add_view(read_file(texture.source))}, {"mimeType", png ? "image/png" : "image/jpeg"}});
  return int(images->size() - 1);
}

// The materials (pbrMetallicRoughness), and in *out the textures, samplers and images they use.
json materials(glb::Builder& glb, const Mesh& mesh, json* out) {
  json materials = json::array(), textures = json::array(), samplers = json::array(), images = json::array();
  std::map<int, int> image_index;  // Mesh::textures index -> glTF image (-1: none)
  for (const Material& m : mesh.materials) {
    json pbr = {{"baseColorFactor", {m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b, 1.0}},
                {"metallicFactor", m.metallic_factor}, {"roughnessFactor", m.roughness_factor}};
    if (m.textured() && !image_index.count(m.base_color.image))
      image_index[m.base_color.image] = image_of(glb, mesh.textures[std::size_t(m.base_color.image)], &images);
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
  if (!part.uv.empty()) attributes["TEXCOORD_0"] = glb.add_floats(&part.uv[0].x, part.uv.size(), 2, "VEC2");
  if (!colours.empty()) attributes["COLOR_0"] = glb.add_floats(&colours[0].x, colours.size(), 3, "VEC3");
  for (const EngineAttribute& a : extras.attributes) attributes[a.name] = add_attribute_gather(glb, a, part.source);
  json out = {{"attributes", attributes}, {"indices", glb.add_indices(part.indices)}, {"mode", 4}};
  out["extensions"][extras.extension] = extras.primitive(added);
  return out;
}

}  // namespace

std::string engine_glb_from_mesh(const std::string& path, const Mesh& mesh, const EngineExtras& extras) {
  if (extras.lightmap_set >= 0 && (!mesh.has_lightmap_uv() || (mesh.textured() && mesh.base_color_uv != mesh.lightmap_uv)))
    fail_file(path, "cannot write glTF: the lightmap UVs are not the mesh's one UV set");
  glb::Builder glb;
  EngineIndices added;
  added.arrays = add_arrays(glb, extras.arrays);
  json out = {{"asset", {{"version", "2.0"}, {"generator", "prt"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}}, {"extensionsUsed", json::array()}};
  if (!mesh.materials.empty()) out["materials"] = materials(glb, mesh, &out);
  json images = out.value("images", json::array());
  for (const GlbImage& image : extras.images) {
    added.images.push_back(int(images.size()));
    images.push_back({{"bufferView", glb.add_view(image.bytes)}, {"mimeType", image.mime_type}});
  }
  if (!images.empty()) out["images"] = images;
  json primitives = json::array();
  const std::vector<Part> parts = split(mesh);
  for (std::size_t m = 0; m < parts.size(); ++m) {
    if (parts[m].indices.empty()) continue;
    json p = primitive(glb, mesh, parts[m], extras, added);
    check_attribute_count(path, p["attributes"].size(), "primitive " + std::to_string(primitives.size()));
    if (!mesh.materials.empty()) p["material"] = m;
    primitives.push_back(p);
  }
  out["meshes"] = {{{"primitives", primitives}}};
  out["extensionsUsed"].push_back(extras.extension);
  out["extensions"][extras.extension] = extras.root(added);
  out["bufferViews"] = glb.buffer_views;
  out["accessors"] = glb.accessors;
  return glb::container(path, out, glb.bin);
}

}  // namespace prt::mesh::detail
