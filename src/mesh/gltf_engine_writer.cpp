// The engine glTF of a glTF source (engine_gltf.h): the document as authored, its primitives' data
// rewritten from the decoded model, the baked node instances' primitives given the extras.
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/little_endian.h"
#include "core/text.h"
#include "mesh/engine_gltf.h"
#include "mesh/engine_gltf_detail.h"
#include "mesh/glb_builder.h"
#include "mesh/gltf_reader.h"

namespace prt::mesh::detail {

namespace {

using nlohmann::json;

// Extensions that refer to data the writer does not keep, or that it decodes.
const std::set<std::string> kDroppedExtensions = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                                  "EXT_mesh_gpu_instancing"};

void put_component(std::string& out, double v, int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      out.push_back(char(std::uint8_t(std::int64_t(v))));
      break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const auto u = std::uint16_t(std::int64_t(v));
      out.push_back(char(u & 0xFF));
      out.push_back(char(u >> 8));
      break;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      le::put_f32(out, float(v));
      break;
    default:
      le::put_u32(out, std::uint32_t(std::int64_t(v)));
  }
}

// An image's MIME type: the document's, else image_mime_type's.
std::string mime_type(const json& image, const GltfImageBytes& bytes) {
  if (image.contains("mimeType") && image["mimeType"].is_string()) return image["mimeType"];
  return image_mime_type(bytes.bytes, bytes.hint);
}

json without_extensions(json object, const std::set<std::string>& names) {
  if (!object.contains("extensions")) return object;
  for (const std::string& name : names) object["extensions"].erase(name);
  if (object["extensions"].empty()) object.erase("extensions");
  return object;
}

class SourceWriter {
 public:
  SourceWriter(const std::string& path, const std::string& source, const Mesh& mesh, const EngineExtras& extras)
      : path_(path), source_(source), mesh_(mesh), extras_(extras) {}

  std::string write() {
    std::string warn;
    model_ = read_gltf_model(source_, lower_extension(source_) == ".glb", &warn, &images_, &doc_);
    reader_ = std::make_unique<GltfReader>(source_, model_);
    added_.arrays = add_arrays(glb_, extras_.arrays);
    groups_ = source_primitive_groups(path_, mesh_, extras_);
    assign_meshes();
    json out = {{"asset", doc_.value("asset", json::object())}};
    out["asset"]["version"] = "2.0";
    out["asset"]["generator"] = "prt";
    for (const char* key : {"scene", "scenes", "cameras", "materials", "textures", "samplers", "extras"})
      if (doc_.contains(key)) out[key] = doc_[key];
    json images = source_images();  // before the primitives, whose extension names the added images
    for (const GlbImage& image : extras_.images) {
      added_.images.push_back(int(images.size()));
      images.push_back({{"bufferView", glb_.add_view(image.bytes)}, {"mimeType", image.mime_type}});
    }
    if (!images.empty()) out["images"] = images;
    out["nodes"] = nodes();
    out["meshes"] = meshes();
    finish_extensions(&out);
    out["bufferViews"] = glb_.buffer_views;
    out["accessors"] = glb_.accessors;
    return glb::container(path_, out, glb_.bin);
  }

 private:
  // The output mesh of each node: the source's, or for a baked node whose mesh another node uses too,
  // a copy appended after the source's meshes.
  void assign_meshes() {
    const json& nodes = doc_["nodes"];
    node_mesh_.assign(nodes.size(), -1);
    for (std::size_t n = 0; n < nodes.size(); ++n) node_mesh_[n] = nodes[n].value("mesh", -1);
    std::map<int, int> users;
    for (int m : node_mesh_)
      if (m >= 0) ++users[m];
    mesh_source_.clear();
    for (std::size_t m = 0; m < doc_.value("meshes", json::array()).size(); ++m) mesh_source_.push_back(int(m));
    std::set<int> baked_nodes;
    std::map<int, std::vector<int>> baked_users;  // per mesh: its baked nodes, in bake order
    for (std::size_t i = 0; i < mesh_.source_primitives.size(); ++i) {
      const SourcePrimitive& sp = mesh_.source_primitives[i];
      const bool starts = i == 0 || sp.node != mesh_.source_primitives[i - 1].node ||
                          sp.primitive <= mesh_.source_primitives[i - 1].primitive;
      if (!starts) continue;
      if (!baked_nodes.insert(sp.node).second)
        fail_file(path_, "cannot write glTF: node " + std::to_string(sp.node) +
                             " was baked twice (it is in two of the scenes loaded); bake one scene");
      baked_users[sp.mesh].push_back(sp.node);
    }
    // A mesh used by baked nodes only stays with its first baked user; every other baked user (and every
    // baked user of a mesh that an unbaked node also uses) gets a copy.
    for (const auto& [m, baked] : baked_users)
      for (std::size_t i = 0; i < baked.size(); ++i) {
        if (i == 0 && users[m] == int(baked.size())) continue;
        node_mesh_[std::size_t(baked[i])] = int(mesh_source_.size());
        mesh_source_.push_back(m);
      }
    baked_.assign(mesh_source_.size(), {});
    for (const SourcePrimitive& sp : mesh_.source_primitives)
      baked_[std::size_t(node_mesh_[std::size_t(sp.node)])][sp.primitive] = &sp;
  }

  json nodes() const {
    json nodes = doc_["nodes"];
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      nodes[n] = without_extensions(nodes[n], kDroppedExtensions);
      nodes[n].erase("skin");
      nodes[n].erase("weights");
      if (node_mesh_[n] >= 0) nodes[n]["mesh"] = node_mesh_[n];
    }
    return nodes;
  }

  json meshes() {
    json meshes = json::array();
    for (std::size_t m = 0; m < mesh_source_.size(); ++m) {
      const int source = mesh_source_[m];
      json mesh = doc_["meshes"][std::size_t(source)];
      mesh.erase("weights");
      json primitives = json::array();
      const auto& model_prims = model_.meshes[std::size_t(source)].primitives;
      for (std::size_t p = 0; p < model_prims.size(); ++p) {
        const auto found = baked_[m].find(int(p));
        primitives.push_back(primitive(mesh["primitives"][p], model_prims[p],
                                       found == baked_[m].end() ? nullptr : found->second,
                                       "mesh " + std::to_string(source) + " primitive " + std::to_string(p)));
      }
      mesh["primitives"] = primitives;
      meshes.push_back(mesh);
    }
    return meshes;
  }

  json primitive(const json& source, const tinygltf::Primitive& prim, const SourcePrimitive* baked, const std::string& what) {
    json out = without_extensions(source, kDroppedExtensions);
    out.erase("targets");
    json attributes = json::object();
    const SplitVertices vertices = baked && extras_.corner_uvs ? split_by_uv(*baked) : SplitVertices{};
    const bool split = !vertices.source.empty();  // (a primitive whose triangles were all dropped stays as it is)
    for (const auto& [name, accessor] : prim.attributes) {
      if (name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) continue;
      attributes[name] = copy_accessor(accessor, name == "POSITION", what + " " + name, split ? &vertices.source : nullptr);
    }
    if (split) {  // the loaded triangles, as a triangle list over the split vertices
      const int uv = glb_.add_floats(&vertices.uv[0].x, vertices.uv.size(), 2, "VEC2");
      attributes["TEXCOORD_" + std::to_string(extras_.lightmap_set)] = uv;
      // glTF's texture coordinate sets start at 0 and have no gaps: missing lower sets share the accessor.
      for (int set = 0; set < extras_.lightmap_set; ++set)
        if (!attributes.contains("TEXCOORD_" + std::to_string(set))) attributes["TEXCOORD_" + std::to_string(set)] = uv;
      out["indices"] = glb_.add_indices(vertices.indices);
      out["mode"] = 4;
    } else if (prim.indices >= 0) {
      out["indices"] = copy_indices(prim.indices, what + " indices");
    }
    if (baked) {
      const int group = groups_[std::size_t(baked - mesh_.source_primitives.data())];
      std::vector<std::uint32_t> loaded(vertices.source.size());  // split: the mesh vertex of each written vertex
      for (std::size_t i = 0; i < loaded.size(); ++i) loaded[i] = baked->first_vertex + vertices.source[i];
      for (const EngineAttribute& a : extras_.attributes) {
        if (a.group >= 0 && a.group != group) continue;
        attributes[a.name] =
            split ? add_attribute_gather(glb_, a, loaded) : add_attribute_slice(glb_, a, baked->first_vertex, baked->vertex_count);
      }
      if (!extras_.extension.empty()) out["extensions"][extras_.extension] = extras_.primitive(added_, group);
    }
    check_attribute_count(path_, attributes.size(), what);
    out["attributes"] = attributes;
    return out;
  }

  // Accessor `index` rewritten tightly packed; with `gather`, its elements gather[0], gather[1], ...
  // (each < its count) instead of all of them in order.
  int copy_accessor(int index, bool with_bounds, const std::string& what, const std::vector<std::uint32_t>* gather = nullptr) {
    const auto cached = copied_.find(index);
    if (!gather && cached != copied_.end()) return cached->second;
    int components = 0;
    std::vector<double> values = reader_->read_accessor(index, what, &components, /*normalize=*/false);
    const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
    std::size_t count = a.count;
    if (gather) values = gathered(values, std::size_t(components), *gather, what), count = gather->size();
    const std::size_t size = component_size(a.componentType), element = size * std::size_t(components);
    const std::size_t stride = (element + 3) / 4 * 4;  // vertex attributes: elements 4-byte aligned (spec)
    std::string bytes;
    for (std::size_t i = 0; i < count; ++i) {
      for (int c = 0; c < components; ++c) put_component(bytes, values[i * std::size_t(components) + std::size_t(c)], a.componentType);
      bytes.append(stride - element, '\0');
    }
    const int out = glb_.add(bytes, count, glb::accessor_type(components), a.componentType, glb::kArrayBuffer);
    json& accessor = glb_.accessors[std::size_t(out)];
    if (a.normalized) accessor["normalized"] = true;
    if (stride != element) glb_.buffer_views[accessor["bufferView"].get<std::size_t>()]["byteStride"] = stride;
    if (with_bounds && count > 0) {
      json lo = json::array(), hi = json::array();
      for (int c = 0; c < components; ++c) {
        double l = values[std::size_t(c)], h = l;
        for (std::size_t i = 0; i < count; ++i) {
          l = std::min(l, values[i * std::size_t(components) + std::size_t(c)]);
          h = std::max(h, values[i * std::size_t(components) + std::size_t(c)]);
        }
        lo.push_back(l);
        hi.push_back(h);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    return gather ? out : copied_[index] = out;
  }

  std::vector<double> gathered(const std::vector<double>& values, std::size_t components, const std::vector<std::uint32_t>& gather,
                               const std::string& what) const {
    std::vector<double> out;
    out.reserve(gather.size() * components);
    for (std::uint32_t v : gather) {
      if ((std::size_t(v) + 1) * components > values.size())
        fail_file(path_, "cannot write glTF: " + what + " has fewer elements than the primitive's POSITION");
      out.insert(out.end(), values.begin() + std::ptrdiff_t(v * components), values.begin() + std::ptrdiff_t((v + 1) * components));
    }
    return out;
  }

  // A baked primitive's loaded triangles with the generated lightmap UVs (extras.corner_uvs): one vertex
  // per distinct (source vertex, UV bits) in order of first use over the triangles' corners.
  struct SplitVertices {
    std::vector<std::uint32_t> source;  // per vertex: its element of the source primitive's attributes
    std::vector<glm::vec2> uv;          // per vertex: its lightmap UV
    std::vector<std::uint32_t> indices;  // 3 per loaded triangle of the primitive, in mesh order
  };
  SplitVertices split_by_uv(const SourcePrimitive& baked) {
    const std::size_t index = std::size_t(&baked - mesh_.source_primitives.data());
    if (primitive_triangles_.empty()) {  // each source primitive's loaded triangles, in mesh order, once
      primitive_triangles_.resize(mesh_.source_primitives.size());
      for (std::uint32_t t = 0; t < mesh_.triangle_count(); ++t) primitive_triangles_[mesh_.triangle_source[t].primitive].push_back(t);
    }
    SplitVertices out;
    std::map<std::pair<std::uint32_t, std::uint64_t>, std::uint32_t> seen;
    for (const std::uint32_t t : primitive_triangles_[index]) {
      for (std::size_t corner = 3 * std::size_t(t); corner < 3 * std::size_t(t) + 3; ++corner) {
        const glm::vec2 uv = mesh_.lightmap_uv[corner];
        const std::uint32_t v = mesh_.indices[corner] - baked.first_vertex;
        std::uint64_t key = 0;
        std::memcpy(&key, &uv, sizeof key);
        const auto found = seen.emplace(std::make_pair(v, key), std::uint32_t(out.source.size()));
        if (found.second) out.source.push_back(v), out.uv.push_back(uv);
        out.indices.push_back(found.first->second);
      }
    }
    return out;
  }

  int copy_indices(int index, const std::string& what) {
    const auto cached = copied_indices_.find(index);
    if (cached != copied_indices_.end()) return cached->second;
    int components = 0;
    const std::vector<double> values = reader_->read_accessor(index, what, &components, false);
    const int type = model_.accessors[std::size_t(index)].componentType;
    std::string bytes;
    for (double v : values) put_component(bytes, v, type);
    return copied_indices_[index] = glb_.add(bytes, values.size(), "SCALAR", type, glb::kElementArrayBuffer);
  }

  json source_images() {
    json images = doc_.value("images", json::array());
    for (std::size_t i = 0; i < images.size(); ++i) {
      GltfImageBytes kept;
      if (i < images_.size()) kept.hint = images_[i].hint;
      if (!gltf_image_bytes(model_, images_, int(i), &kept.bytes))
        fail_file(path_, "cannot write glTF: image " + std::to_string(i) + " of " + source_ + " could not be read");
      json image = {{"bufferView", glb_.add_view(kept.bytes)}, {"mimeType", mime_type(images[i], kept)}};
      if (images[i].contains("name")) image["name"] = images[i]["name"];
      images[i] = image;
    }
    return images;
  }

  void finish_extensions(json* out) const {
    json root = without_extensions(doc_, kDroppedExtensions).value("extensions", json::object());
    if (!extras_.extension.empty()) root[extras_.extension] = extras_.root(added_);
    if (!root.empty()) (*out)["extensions"] = root;
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
      json names = json::array();
      for (const json& name : doc_.value(list, json::array()))
        if (name.is_string() && !kDroppedExtensions.count(name.get<std::string>())) names.push_back(name);
      if (std::string(list) == "extensionsUsed" && !extras_.extension.empty()) names.push_back(extras_.extension);
      if (!names.empty()) (*out)[list] = names;
    }
  }

  const std::string& path_;
  const std::string& source_;
  const Mesh& mesh_;
  const EngineExtras& extras_;
  tinygltf::Model model_;
  json doc_;
  std::vector<GltfImageBytes> images_;
  std::unique_ptr<GltfReader> reader_;
  glb::Builder glb_;
  EngineIndices added_;
  std::vector<int> node_mesh_;    // per node: its output mesh
  std::vector<int> mesh_source_;  // per output mesh: the source mesh it copies
  std::vector<std::map<int, const SourcePrimitive*>> baked_;  // per output mesh: primitive -> baked slice
  std::map<int, int> copied_, copied_indices_;
  std::vector<std::vector<std::uint32_t>> primitive_triangles_;  // per source primitive (split_by_uv)
  std::vector<int> groups_;  // per source primitive: its group (EngineExtras::triangle_group)
};

}  // namespace

std::string engine_glb_from_gltf(const std::string& path, const std::string& source, const Mesh& mesh,
                                 const EngineExtras& extras) {
  return SourceWriter(path, source, mesh, extras).write();
}

}  // namespace prt::mesh::detail
