#pragma once
// Internal to prt_mesh: a glTF file's materials as prt's (mesh.h "MATERIALS AND BASE COLOUR"): base
// colour factor, baseColorTexture with its texCoord, KHR_texture_transform and sampler, and the decoded
// images. gltf_loader.cpp asks it, per primitive, for the mesh material and the UV set to read.
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "mesh/loaders.h"

namespace prt::mesh::detail {

/// An image's file content as tinygltf handed it over (embedded buffer view, data: URI or external
/// file), and a format hint (mime type or uri).
struct GltfImageBytes {
  bool present = false;
  std::string bytes, hint;
};

/// tinygltf's image loader callback: keeps the bytes of image `index` in the vector of GltfImageBytes
/// that `user` points to, decoding nothing.
bool keep_gltf_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int, int,
                     const unsigned char* bytes, int size, void* user);

/// The file bytes of image `source` (< model.images.size()) of `model`: its buffer view's (bounds-checked)
/// or what keep_gltf_image kept in `images`. False when there are none.
bool gltf_image_bytes(const tinygltf::Model& model, const std::vector<GltfImageBytes>& images, int source, std::string* bytes);

class GltfMaterials {
 public:
  /// Reads every material of `model` and decodes the images their base colour textures use; an
  /// image that cannot be decoded is a note (its materials keep the factor alone).
  GltfMaterials(const std::string& path, const tinygltf::Model& model, const std::vector<GltfImageBytes>& images);

  /// The mesh material of a primitive with glTF material `material` (-1: none, factor 1). Throws
  /// prt::Error naming `what` if it does not exist.
  std::uint32_t material_of(int material, const std::string& what);
  /// The TEXCOORD set the base colour texture of mesh material `m` reads, or -1 if untextured.
  int texcoord_set(std::uint32_t m) const;
  /// The untextured copy of mesh material `m`, for a primitive without its texcoord set (noted once,
  /// naming `what`).
  std::uint32_t without_texture(std::uint32_t m, const std::string& what);

  /// Moves the materials, textures and notes into `raw`.
  void finish(RawMesh* raw);

 private:
  int texture_image(const tinygltf::TextureInfo& info, const std::string& what);
  bool image_bytes(int source, std::string* bytes) const;
  Material read_material(const tinygltf::Material& material, std::size_t index);

  const std::string& path_;
  const tinygltf::Model& model_;
  const std::vector<GltfImageBytes>& images_;
  std::vector<Material> materials_;
  std::vector<int> image_texture_;  // per glTF image: index into textures_, -1 unread, -2 failed
  std::vector<Texture> textures_;
  std::vector<std::string> notes_;
  std::uint64_t held_bytes_ = 0;
  std::int64_t default_ = -1;        // the material of primitives without one, once made
  std::vector<std::int64_t> plain_;  // per material: its untextured copy, once made
};

}  // namespace prt::mesh::detail
