// write_engine_glb's checks and the parts its two sources share; GltfExtras (engine_gltf.h).
#include "mesh/engine_gltf.h"

#include <algorithm>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/little_endian.h"
#include "core/text.h"
#include "mesh/engine_gltf_detail.h"
#include "mesh/gltf_reader.h"

namespace prt::mesh {

namespace detail {

std::vector<int> add_arrays(glb::Builder& glb, const std::vector<std::vector<float>>& arrays) {
  std::vector<int> indices;
  for (const std::vector<float>& values : arrays) {
    std::string bytes;
    for (float v : values) le::put_f32(bytes, v);
    const int view = glb.add_view(bytes);
    glb.accessors.push_back({{"bufferView", view}, {"componentType", glb::kFloat}, {"count", values.size()}, {"type", "SCALAR"}});
    indices.push_back(int(glb.accessors.size() - 1));
  }
  return indices;
}

int add_attribute_gather(glb::Builder& glb, const EngineAttribute& attribute, const std::vector<std::uint32_t>& vertices) {
  const std::size_t width = std::size_t(attribute.components);
  std::vector<float> values;
  values.reserve(vertices.size() * width);
  for (std::uint32_t v : vertices)
    values.insert(values.end(), attribute.values.begin() + std::ptrdiff_t(v * width),
                  attribute.values.begin() + std::ptrdiff_t((v + 1) * width));
  return glb.add_floats(values.data(), vertices.size(), attribute.components, glb::accessor_type(attribute.components));
}

int add_attribute_slice(glb::Builder& glb, const EngineAttribute& attribute, std::uint32_t first, std::uint32_t count) {
  const std::size_t width = std::size_t(attribute.components);
  return glb.add_floats(attribute.values.data() + std::size_t(first) * width, count, attribute.components,
                        glb::accessor_type(attribute.components));
}

std::string image_mime_type(const std::string& b, const std::string& hint) {
  if (b.rfind("\x89PNG", 0) == 0) return "image/png";
  if (b.rfind("\xFF\xD8", 0) == 0) return "image/jpeg";
  if (b.rfind("\xABKTX 20", 0) == 0) return "image/ktx2";
  if (b.size() > 12 && b.compare(8, 4, "WEBP") == 0) return "image/webp";
  const std::string ext = lower_extension(hint);
  return ext == ".jpg" || ext == ".jpeg" ? "image/jpeg" : "image/png";
}

void check_attribute_count(const std::string& path, std::size_t count, const std::string& what) {
  if (count > std::size_t(kMaxVertexAttributes))
    fail_file(path, "cannot write glTF: " + what + " would have " + std::to_string(count) + " vertex attributes, more than " +
                        std::to_string(kMaxVertexAttributes));
}

std::vector<int> source_primitive_groups(const std::string& path, const Mesh& mesh, const EngineExtras& extras) {
  std::vector<int> groups(mesh.source_primitives.size(), extras.triangle_group.empty() ? 0 : -1);
  for (std::size_t t = 0; t < extras.triangle_group.size() && t < mesh.triangle_source.size(); ++t) {
    int& group = groups[mesh.triangle_source[t].primitive];
    const int g = extras.triangle_group[t];
    if (group >= 0 && group != g) {
      const SourcePrimitive& sp = mesh.source_primitives[mesh.triangle_source[t].primitive];
      fail_file(path, "cannot write glTF: mesh " + std::to_string(sp.mesh) + " primitive " + std::to_string(sp.primitive) +
                          " has triangles of two kinds; a primitive is written whole, of one kind");
    }
    group = g;
  }
  for (int& group : groups) group = std::max(group, 0);  // a primitive whose triangles were all dropped
  return groups;
}

}  // namespace detail

void write_engine_glb(const std::string& path, const std::string& source_path, const Mesh& mesh, const EngineExtras& extras) {
  glb::check_mesh(path, mesh);
  std::set<std::string> names;
  for (const EngineAttribute& a : extras.attributes) {
    if (!glb::valid_semantic(a.name) || !names.insert(a.name).second)
      fail_file(path, "cannot write glTF: attribute name \"" + a.name + "\" is not a new application-specific semantic");
    if (a.components < 1 || a.components > 4 || a.values.size() != std::size_t(a.components) * mesh.vertex_count())
      fail_file(path, "cannot write glTF: attribute " + a.name + " has " + std::to_string(a.values.size()) + " values for " +
                          std::to_string(mesh.vertex_count()) + " vertices");
  }
  if (!extras.extension.empty() && (!extras.root || !extras.primitive))
    fail_file(path, "cannot write glTF: extension " + extras.extension + " has no root or primitive object");
  const std::string ext = lower_extension(source_path);
  const bool gltf = (ext == ".gltf" || ext == ".glb") && !extras.as_loaded;
  if (extras.corner_uvs && (extras.lightmap_set < 0 || mesh.lightmap_uv.size() != mesh.indices.size() ||
                            (gltf && mesh.triangle_source.size() != mesh.triangle_count())))
    fail_file(path, "cannot write glTF: generated lightmap UVs need a UV set and one UV per triangle corner");
  if (!extras.triangle_group.empty() && (extras.triangle_group.size() != mesh.triangle_count() ||
                                         (gltf && mesh.triangle_source.size() != mesh.triangle_count())))
    fail_file(path, "cannot write glTF: the primitives' groups need one entry per triangle");
  if (gltf && mesh.source_primitives.empty()) fail_file(path, "cannot write glTF: the mesh does not say which glTF primitives it came from");
  write_file_atomically(path, gltf ? detail::engine_glb_from_gltf(path, source_path, mesh, extras)
                                   : detail::engine_glb_from_mesh(path, source_path, mesh, extras));
}

struct GltfExtras::Model {
  tinygltf::Model model;
  nlohmann::json document;
  std::vector<detail::GltfImageBytes> images;
};

GltfExtras::GltfExtras(const std::string& path) : path_(path), model_(std::make_unique<Model>()) {
  std::string warn;
  model_->model = detail::read_gltf_model(path, lower_extension(path) == ".glb", &warn, &model_->images, &model_->document);
}

GltfExtras::~GltfExtras() = default;

const nlohmann::json& GltfExtras::document() const { return model_->document; }

std::vector<float> GltfExtras::floats(int index, int components, const std::string& what) const {
  int width = 0;
  const std::vector<double> values = detail::GltfReader(path_, model_->model).read_accessor(index, what, &width);
  if (width != components) fail_file(path_, what + ": accessor " + std::to_string(index) + " is not " + glb::accessor_type(components));
  return std::vector<float>(values.begin(), values.end());
}

std::vector<float> GltfExtras::vertex_attribute(const Mesh& mesh, const std::string& name, int components) const {
  std::vector<float> out;
  out.reserve(mesh.vertex_count() * std::size_t(components));
  for (const SourcePrimitive& sp : mesh.source_primitives) {
    const std::string what = "mesh " + std::to_string(sp.mesh) + " primitive " + std::to_string(sp.primitive);
    const tinygltf::Primitive& prim = model_->model.meshes.at(std::size_t(sp.mesh)).primitives.at(std::size_t(sp.primitive));
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) fail_file(path_, what + " has no " + name);
    const std::vector<float> values = floats(it->second, components, what + " " + name);
    if (values.size() != std::size_t(sp.vertex_count) * std::size_t(components))
      fail_file(path_, what + ": " + name + " has " + std::to_string(values.size() / std::size_t(components)) +
                           " elements for " + std::to_string(sp.vertex_count) + " vertices");
    out.insert(out.end(), values.begin(), values.end());
  }
  return out;
}

std::string GltfExtras::image(int index, const std::string& what) const {
  std::string bytes;
  if (index < 0 || std::size_t(index) >= model_->model.images.size() ||
      !detail::gltf_image_bytes(model_->model, model_->images, index, &bytes))
    fail_file(path_, what + ": image " + std::to_string(index) + " does not exist or has no data");
  return bytes;
}

}  // namespace prt::mesh
