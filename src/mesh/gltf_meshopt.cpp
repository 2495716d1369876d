// extensionsRequired, and EXT_meshopt_compression buffer views decoded with meshoptimizer (the
// extension's spec: modes ATTRIBUTES / TRIANGLES / INDICES, filters NONE / OCTAHEDRAL / QUATERNION /
// EXPONENTIAL, fallback buffers).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/error.h"
#include "mesh/gltf_compressed.h"

namespace prt::mesh::detail {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
/// The one-byte buffer a meshopt fallback buffer without a uri is given for tinygltf.
constexpr const char* kFallbackStub = "data:application/octet-stream;base64,AA==";

/// Extensions prt reads or that change nothing it reads (materials, textures, lights).
bool extension_is_supported(const std::string& name) {
  return name == "KHR_draco_mesh_compression" || name == kMeshopt || name == "KHR_mesh_quantization" ||
         name == "KHR_texture_transform" || name == "KHR_texture_basisu" || name == "KHR_lights_punctual" ||
         name == "EXT_texture_webp" || name.rfind("KHR_materials_", 0) == 0;
}

/// The extension's integer property `key` (>= 0), or `fallback` when absent; -1 when not a
/// non-negative integer.
long long int_property(const tinygltf::Value& ext, const char* key, long long fallback) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsNumber()) return -1;
  const double d = v.GetNumberAsDouble();
  return d >= 0.0 && d <= 9.0e15 && d == double(static_cast<long long>(d)) ? static_cast<long long>(d) : -1;
}

std::string string_property(const tinygltf::Value& ext, const char* key, const char* fallback) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  return v.IsString() ? v.Get<std::string>() : std::string("(not a string)");
}

/// One compressed view's extension object.
struct MeshoptView {
  std::size_t buffer = 0, offset = 0, length = 0, stride = 0, count = 0;
  std::string mode, filter;
};

MeshoptView read_meshopt_view(const tinygltf::Value& ext, const std::string& what, const std::string& path) {
  const long long buffer = int_property(ext, "buffer", -1), offset = int_property(ext, "byteOffset", 0),
                  length = int_property(ext, "byteLength", -1), stride = int_property(ext, "byteStride", -1),
                  count = int_property(ext, "count", -1);
  if (buffer < 0 || offset < 0 || length < 0 || stride < 0 || count < 0)
    fail_file(path, what + ": buffer, byteOffset, byteLength, byteStride or count is missing or not a "
                           "non-negative integer");
  return {std::size_t(buffer), std::size_t(offset), std::size_t(length), std::size_t(stride), std::size_t(count),
          string_property(ext, "mode", ""), string_property(ext, "filter", "NONE")};
}

/// The spec's rules for `v`, and the sizes, checked before anything is allocated.
void check_meshopt_view(const tinygltf::Model& model, const tinygltf::BufferView& view, const MeshoptView& v,
                        const std::string& what, const std::string& path) {
  auto bad = [&](const std::string& problem) { fail_file(path, what + ": " + problem); };
  if (v.buffer >= model.buffers.size()) bad("buffer " + std::to_string(v.buffer) + " does not exist");
  const std::size_t have = model.buffers[v.buffer].data.size();
  if (v.offset > have || v.length > have - v.offset) bad("compressed data runs past the end of its buffer");
  const bool attributes = v.mode == "ATTRIBUTES";
  if (!attributes && v.mode != "TRIANGLES" && v.mode != "INDICES") bad("unknown mode \"" + v.mode + "\"");
  if (attributes ? (v.stride == 0 || v.stride > 256 || v.stride % 4 != 0) : (v.stride != 2 && v.stride != 4))
    bad("byteStride " + std::to_string(v.stride) + " is invalid for mode " + v.mode);
  if (v.mode == "TRIANGLES" && v.count % 3 != 0) bad("TRIANGLES count is not a multiple of 3");
  const bool filter_ok =
      v.filter == "NONE" ||
      (attributes && ((v.filter == "OCTAHEDRAL" && (v.stride == 4 || v.stride == 8)) ||
                      (v.filter == "QUATERNION" && v.stride == 8) || v.filter == "EXPONENTIAL"));
  if (!filter_ok)
    bad("filter \"" + v.filter + "\" is invalid for mode " + v.mode + " and byteStride " + std::to_string(v.stride));
  // Each 16 decoded bytes take at least 2 bits of the vertex codec (and more in the index codecs):
  // a count that would decode to more than 64x the compressed bytes cannot be honest.
  if (v.count > v.length * 64 / v.stride)
    bad("count " + std::to_string(v.count) + " is too large for " + std::to_string(v.length) + " compressed bytes");
  if (v.count * v.stride != view.byteLength)
    bad("count x byteStride (" + std::to_string(v.count * v.stride) + ") differs from the buffer view's byteLength (" +
        std::to_string(view.byteLength) + ")");
}

std::vector<unsigned char> decode_view(const tinygltf::Model& model, const MeshoptView& v, const std::string& what,
                                       const std::string& path) {
  std::vector<unsigned char> out(v.count * v.stride);
  const unsigned char* src = model.buffers[v.buffer].data.data() + v.offset;
  int rc = 0;
  if (v.mode == "ATTRIBUTES")
    rc = meshopt_decodeVertexBuffer(out.data(), v.count, v.stride, src, v.length);
  else if (v.mode == "TRIANGLES")
    rc = meshopt_decodeIndexBuffer(out.data(), v.count, v.stride, src, v.length);
  else
    rc = meshopt_decodeIndexSequence(out.data(), v.count, v.stride, src, v.length);
  if (rc != 0)
    fail_file(path, what + ": the compressed data is corrupt or truncated (meshoptimizer error " + std::to_string(rc) + ")");
  apply_meshopt_filter(v.filter, out.data(), v.count, v.stride);
  return out;
}

/// Whether `view` uses a fallback buffer that stub_meshopt_fallback_buffers gave a placeholder.
bool uses_stubbed_fallback(const tinygltf::Model& model, const tinygltf::BufferView& view) {
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) return false;
  const tinygltf::Buffer& buffer = model.buffers[std::size_t(view.buffer)];
  const auto it = buffer.extensions.find(kMeshopt);
  return buffer.uri == kFallbackStub && it != buffer.extensions.end() && it->second.IsObject() &&
         it->second.Has("fallback");
}

}  // namespace

void check_required_extensions(const std::string& path, const nlohmann::json& document) {
  if (!document.is_object() || !document.contains("extensionsRequired")) return;
  const nlohmann::json& required = document["extensionsRequired"];
  if (!required.is_array()) fail_file(path, "\"extensionsRequired\" is not an array");
  for (const nlohmann::json& name : required) {
    if (!name.is_string()) fail_file(path, "\"extensionsRequired\" holds something other than a name");
    if (!extension_is_supported(name.get<std::string>()))
      fail_file(path, "requires glTF extension " + name.get<std::string>() + ", which prt does not support");
  }
}

/// Gives each meshopt fallback buffer without a "uri" a one-byte data: uri; whether any changed.
static bool stub_meshopt_fallback_buffers(nlohmann::json* document) {
  if (!document->is_object() || !document->contains("buffers") || !(*document)["buffers"].is_array()) return false;
  bool changed = false;
  for (nlohmann::json& buffer : (*document)["buffers"]) {
    if (!buffer.is_object() || buffer.contains("uri")) continue;
    const nlohmann::json* ext = nullptr;
    if (buffer.contains("extensions") && buffer["extensions"].is_object() && buffer["extensions"].contains(kMeshopt))
      ext = &buffer["extensions"][kMeshopt];
    if (!ext || !ext->is_object() || ext->value("fallback", false) != true) continue;
    buffer["uri"] = kFallbackStub;
    buffer["byteLength"] = 1;
    changed = true;
  }
  return changed;
}

bool patch_for_tinygltf(nlohmann::json* document) {
  const bool stubbed = stub_meshopt_fallback_buffers(document);
  return drop_draco_indices(document) || stubbed;
}

void decode_meshopt_views(const std::string& path, tinygltf::Model* model) {
  for (std::size_t i = 0; i < model->bufferViews.size(); ++i) {
    tinygltf::BufferView& view = model->bufferViews[i];
    const auto it = view.extensions.find(kMeshopt);
    const std::string what = "buffer view " + std::to_string(i) + " (" + kMeshopt + ")";
    if (it == view.extensions.end()) {
      if (uses_stubbed_fallback(*model, view))
        fail_file(path, "buffer view " + std::to_string(i) + " is not compressed but uses a meshopt fallback buffer, "
                        "which holds no data");
      continue;
    }
    if (!it->second.IsObject()) fail_file(path, what + ": the extension is not an object");
    const MeshoptView compressed = read_meshopt_view(it->second, what, path);
    check_meshopt_view(*model, view, compressed, what, path);
    tinygltf::Buffer decoded;
    decoded.data = decode_view(*model, compressed, what, path);
    model->buffers.push_back(std::move(decoded));
    view.buffer = int(model->buffers.size() - 1);
    view.byteOffset = 0;
    view.extensions.erase(it);
  }
}

}  // namespace prt::mesh::detail
