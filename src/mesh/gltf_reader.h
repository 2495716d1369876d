#pragma once
// Internal to prt_mesh: reading a parsed glTF model's accessors (bounds-checked, sparse applied), shared
// by the loader (gltf_loader.cpp) and the engine glTF writer (gltf_engine_writer.cpp), and the parse
// itself (compressed geometry decoded, so that the model reads as plain glTF).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/error.h"
#include "mesh/gltf_materials.h"

namespace prt::mesh::detail {

/// Reads and parses a .gltf (binary false) or .glb file with tinygltf, checks extensionsRequired,
/// decodes EXT_meshopt_compression views and KHR_draco_mesh_compression primitives in place, and keeps
/// each image's file bytes in *images (decoding none). *warn gets tinygltf's warnings. Throws
/// prt::Error("<path>: <problem>"). `document`, if given, gets the file's JSON as written (before any
/// decoding).
tinygltf::Model read_gltf_model(const std::string& path, bool binary, std::string* warn, std::vector<GltfImageBytes>* images,
                                nlohmann::json* document = nullptr);

inline std::size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

inline int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;
  }
}

/// One little-endian component, as double; normalised integers mapped to [0,1] / [-1,1].
inline double read_component(const unsigned char* p, int component_type, bool normalized) {
  std::uint32_t bits = 0;
  const std::size_t size = component_size(component_type);
  for (std::size_t k = 0; k < size; ++k) bits |= std::uint32_t(p[k]) << (8 * k);
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = std::int8_t(std::uint8_t(bits));
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? bits / 255.0 : double(bits);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = std::int16_t(std::uint16_t(bits));
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? bits / 65535.0 : double(bits);
    case TINYGLTF_COMPONENT_TYPE_INT:
      return double(std::int32_t(bits));
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return double(bits);
    default: {
      float f;
      std::memcpy(&f, &bits, 4);
      return double(f);
    }
  }
}

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

  /// Accessor `index` as count x components doubles (row per element), bounds-checked; sparse
  /// substitutions applied. `what` names it in errors.
  /// `normalize` false: normalised integers as their stored integer values.
  std::vector<double> read_accessor(int index, const std::string& what, int* components_out, bool normalize = true) const {
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
      bad(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
    const int components = component_count(a.type);
    const std::size_t csize = component_size(a.componentType);
    if (components == 0 || csize == 0) bad(what + ": unsupported accessor type or component type");
    *components_out = components;
    const std::size_t element_size = std::size_t(components) * csize;
    std::vector<double> values;
    if (a.bufferView >= 0) {
      const unsigned char* data = view_data(a.bufferView, what);
      const tinygltf::BufferView& view = model_.bufferViews[std::size_t(a.bufferView)];
      const std::size_t stride = view.byteStride ? view.byteStride : element_size;
      if (stride < element_size) bad(what + ": buffer view stride smaller than an element");
      if (a.count > 0 && (a.byteOffset > view.byteLength || a.count - 1 > view.byteLength / stride ||
                          a.byteOffset + stride * (a.count - 1) + element_size > view.byteLength))
        bad(what + ": accessor runs past the end of its buffer view");
      values.resize(a.count * std::size_t(components));
      for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < components; ++c)
          values[i * std::size_t(components) + std::size_t(c)] =
              read_component(data + a.byteOffset + i * stride + std::size_t(c) * csize, a.componentType, a.normalized && normalize);
    } else {
      // No buffer view: zeros (plus sparse values). Bound the count by the data there is, so that a
      // garbage count cannot ask for an enormous allocation.
      std::size_t buffer_bytes = 0;
      for (const tinygltf::Buffer& buffer : model_.buffers) buffer_bytes += buffer.data.size();
      if (a.count > std::max<std::size_t>(std::size_t(1) << 20, buffer_bytes)) bad(what + ": accessor count too large");
      values.assign(a.count * std::size_t(components), 0.0);
    }
    if (a.sparse.isSparse) apply_sparse(a, components, csize, what, normalize, &values);
    return values;
  }

  [[noreturn]] void bad(const std::string& problem) const { fail_file(path_, problem); }

 private:
  const unsigned char* view_data(int view_index, const std::string& what) const {
    if (view_index < 0 || std::size_t(view_index) >= model_.bufferViews.size())
      bad(what + ": buffer view " + std::to_string(view_index) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(view_index)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
      bad(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model_.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
      bad(what + ": buffer view " + std::to_string(view_index) + " runs past the end of its buffer");
    return buffer.data() + view.byteOffset;
  }

  void apply_sparse(const tinygltf::Accessor& a, int components, std::size_t csize, const std::string& what,
                    bool normalize, std::vector<double>* values) const {
    const std::size_t count = std::size_t(std::max(a.sparse.count, 0));
    const int index_type = a.sparse.indices.componentType;
    const std::size_t isize = component_size(index_type);
    if (isize == 0 || index_type == TINYGLTF_COMPONENT_TYPE_FLOAT) bad(what + ": bad sparse index type");
    auto check = [&](int view, int offset, std::size_t bytes) {
      const unsigned char* data = view_data(view, what + " (sparse)");
      const std::size_t length = model_.bufferViews[std::size_t(view)].byteLength;
      if (offset < 0 || std::size_t(offset) > length || bytes > length - std::size_t(offset))
        bad(what + ": sparse data runs past the end of its buffer view");
      return data + offset;
    };
    if (count > a.count) bad(what + ": more sparse values than elements");
    const unsigned char* indices = check(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, count * isize);
    const std::size_t element_size = std::size_t(components) * csize;
    const unsigned char* data = check(a.sparse.values.bufferView, a.sparse.values.byteOffset, count * element_size);
    for (std::size_t k = 0; k < count; ++k) {
      const double target = read_component(indices + k * isize, index_type, false);
      if (target < 0 || target >= double(a.count)) bad(what + ": sparse index out of range");
      for (int c = 0; c < components; ++c)
        (*values)[std::size_t(target) * std::size_t(components) + std::size_t(c)] =
            read_component(data + k * element_size + std::size_t(c) * csize, a.componentType, a.normalized && normalize);
    }
  }

  const std::string path_;
  const tinygltf::Model& model_;
};


}  // namespace prt::mesh::detail
