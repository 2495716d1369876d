// KHR_draco_mesh_compression primitives decoded with Draco into plain accessors (the extension's
// spec: the primitive's "bufferView" holds a Draco mesh; "attributes" maps glTF attribute names to
// Draco attribute unique ids; the primitive's accessors give each attribute's glTF type).
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/error.h"
#include "mesh/gltf_compressed.h"

namespace prt::mesh::detail {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

/// Every point's value of `attribute`, converted to OutT as Draco converts (normalised where the
/// attribute is), appended little-endian to `out`. False where Draco cannot convert.
template <typename OutT>
bool append_values(const draco::PointAttribute& attribute, std::uint32_t points, int components,
                   std::vector<unsigned char>* out) {
  OutT value[4] = {};
  for (std::uint32_t p = 0; p < points; ++p) {
    if (!attribute.ConvertValue<OutT>(attribute.mapped_index(draco::PointIndex(p)), std::int8_t(components), value))
      return false;
    const auto* bytes = reinterpret_cast<const unsigned char*>(value);
    out->insert(out->end(), bytes, bytes + sizeof(OutT) * std::size_t(components));
  }
  return true;
}

bool convert_attribute(const draco::PointAttribute& attribute, int component_type, std::uint32_t points,
                       int components, std::vector<unsigned char>* out) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return append_values<std::int8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return append_values<std::uint8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return append_values<std::int16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return append_values<std::uint16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return append_values<std::uint32_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return append_values<float>(attribute, points, components, out);
    default: return false;
  }
}

/// Appends `bytes` as a new buffer and buffer view, and a copy of `like` (type, component type,
/// normalized) reading them; returns the new accessor's index.
int add_accessor(tinygltf::Model* model, std::vector<unsigned char> bytes, const tinygltf::Accessor& like,
                 std::size_t count) {
  tinygltf::BufferView view;
  view.buffer = int(model->buffers.size());
  view.byteLength = bytes.size();
  model->buffers.emplace_back();
  model->buffers.back().data = std::move(bytes);
  model->bufferViews.push_back(view);
  tinygltf::Accessor accessor = like;
  accessor.bufferView = int(model->bufferViews.size() - 1);
  accessor.byteOffset = 0;
  accessor.count = count;
  accessor.sparse.isSparse = false;
  model->accessors.push_back(accessor);
  return int(model->accessors.size() - 1);
}

std::unique_ptr<draco::Mesh> decode_mesh(const tinygltf::Model& model, const tinygltf::Value& ext,
                                         const std::string& what, const std::string& path) {
  const tinygltf::Value& index = ext.Get("bufferView");
  const int view_index = index.IsNumber() ? index.GetNumberAsInt() : -1;
  if (view_index < 0 || std::size_t(view_index) >= model.bufferViews.size())
    fail_file(path, what + ": bufferView missing or does not exist");
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(view_index)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
    fail_file(path, what + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& data = model.buffers[std::size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail_file(path, what + ": its buffer view runs past the end of its buffer");
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  try {
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
      fail_file(path, what + ": the Draco data is corrupt or truncated (" + decoded.status().error_msg_string() + ")");
    return std::move(decoded).value();
  } catch (const std::bad_alloc&) {
    fail_file(path, what + ": the Draco data asks for more memory than there is (corrupt?)");
  }
}

void decode_primitive(tinygltf::Model* model, tinygltf::Primitive* prim, const tinygltf::Value& ext,
                      const std::string& what, const std::string& path) {
  const std::unique_ptr<draco::Mesh> mesh = decode_mesh(*model, ext, what, path);
  const tinygltf::Value& ids = ext.Get("attributes");
  if (!ids.IsObject()) fail_file(path, what + ": \"attributes\" is missing or not an object");
  const std::uint32_t points = mesh->num_points();
  for (const std::string& name : ids.Keys()) {
    const tinygltf::Value& id = ids.Get(name);
    const auto it = prim->attributes.find(name);
    if (it == prim->attributes.end()) continue;  // a Draco attribute the primitive does not use
    const int unique_id = id.IsNumber() ? id.GetNumberAsInt() : -1;
    const draco::PointAttribute* attribute =
        unique_id >= 0 ? mesh->GetAttributeByUniqueId(std::uint32_t(unique_id)) : nullptr;
    if (!attribute) fail_file(path, what + ": " + name + " is not in the Draco data");
    if (it->second < 0 || std::size_t(it->second) >= model->accessors.size())
      fail_file(path, what + ": " + name + ": accessor " + std::to_string(it->second) + " does not exist");
    const tinygltf::Accessor like = model->accessors[std::size_t(it->second)];
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(like.type));
    if (components <= 0 || components != attribute->num_components() || like.count != points)
      fail_file(path, what + ": " + name + ": the accessor's type or count does not match the Draco data");
    std::vector<unsigned char> bytes;
    if (!convert_attribute(*attribute, like.componentType, points, components, &bytes))
      fail_file(path, what + ": " + name + ": the Draco values cannot be converted to the accessor's component type");
    it->second = add_accessor(model, std::move(bytes), like, points);
  }
  std::vector<unsigned char> indices(std::size_t(mesh->num_faces()) * 3 * sizeof(std::uint32_t));
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh->face(f)[k].value();
      std::memcpy(indices.data() + (std::size_t(f.value()) * 3 + std::size_t(k)) * sizeof(v), &v, sizeof(v));
    }
  tinygltf::Accessor index_type;
  index_type.type = TINYGLTF_TYPE_SCALAR;
  index_type.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  prim->indices = add_accessor(model, std::move(indices), index_type, std::size_t(mesh->num_faces()) * 3);
  prim->mode = TINYGLTF_MODE_TRIANGLES;
}

}  // namespace

bool drop_draco_indices(nlohmann::json* document) {
  bool changed = false;
  if (!document->is_object() || !document->contains("meshes") || !(*document)["meshes"].is_array()) return false;
  for (nlohmann::json& mesh : (*document)["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(kDraco) || !prim.contains("indices"))
        continue;
      prim.erase("indices");
      changed = true;
    }
  }
  return changed;
}

void decode_draco_primitives(const std::string& path, tinygltf::Model* model) {
  for (std::size_t m = 0; m < model->meshes.size(); ++m)
    for (std::size_t p = 0; p < model->meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model->meshes[m].primitives[p];
      const auto it = prim.extensions.find(kDraco);
      if (it == prim.extensions.end()) continue;
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + " (" + kDraco + ")";
      if (!it->second.IsObject()) fail_file(path, what + ": the extension is not an object");
      const tinygltf::Value ext = it->second;
      prim.extensions.erase(it);
      decode_primitive(model, &prim, ext, what, path);
    }
}

}  // namespace prt::mesh::detail
