#include "mesh/gltf_materials.h"

#include <algorithm>

#include "core/error.h"

namespace prt::mesh::detail {

namespace {

Wrap wrap_of(int gl_wrap) {
  if (gl_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::clamp_to_edge;
  if (gl_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::mirrored_repeat;
  return Wrap::repeat;
}

// The number `key` of a JSON object, or `fallback` when absent or not a number.
double number_or(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return object.Get(key).GetNumberAsDouble();
}

// The 2-number array `key` of a JSON object, or `fallback`.
glm::vec2 pair_or(const tinygltf::Value& object, const char* key, glm::vec2 fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& array = object.Get(key);
  if (!array.IsArray() || array.ArrayLen() != 2 || !array.Get(0).IsNumber() || !array.Get(1).IsNumber()) return fallback;
  return glm::vec2(float(array.Get(0).GetNumberAsDouble()), float(array.Get(1).GetNumberAsDouble()));
}

// KHR_texture_transform of a textureInfo, with its texCoord override, into `ref`.
void read_transform(const tinygltf::TextureInfo& info, TextureRef* ref) {
  const auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return;
  const tinygltf::Value& t = it->second;
  ref->transform.offset = pair_or(t, "offset", glm::vec2(0.0f));
  ref->transform.scale = pair_or(t, "scale", glm::vec2(1.0f));
  ref->transform.rotation = float(number_or(t, "rotation", 0.0));
  const double texcoord = number_or(t, "texCoord", -1.0);
  if (texcoord >= 0.0 && texcoord < 64.0) ref->texcoord = std::uint32_t(texcoord);
}

}  // namespace

bool keep_gltf_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int, const unsigned char* bytes,
                     int size, void* user) {
  auto& images = *static_cast<std::vector<GltfImageBytes>*>(user);
  if (index < 0) return true;
  if (std::size_t(index) >= images.size()) images.resize(std::size_t(index) + 1);
  GltfImageBytes& kept = images[std::size_t(index)];
  kept.hint = image->mimeType.empty() ? image->uri : image->mimeType;
  // A buffer view's bytes are read later, bounds-checked (GltfMaterials::image_bytes).
  if (image->bufferView < 0 && bytes && size > 0) {
    kept.bytes.assign(reinterpret_cast<const char*>(bytes), std::size_t(size));
    kept.present = true;
  }
  return true;
}

GltfMaterials::GltfMaterials(const std::string& path, const tinygltf::Model& model,
                             const std::vector<GltfImageBytes>& images)
    : path_(path), model_(model), images_(images), image_texture_(model.images.size(), -1),
      plain_(model.materials.size(), -1) {
  for (std::size_t i = 0; i < model.materials.size(); ++i) materials_.push_back(read_material(model.materials[i], i));
}

Material GltfMaterials::read_material(const tinygltf::Material& material, std::size_t index) {
  Material m;
  m.name = material.name;
  const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() >= 3)
    m.base_color_factor = glm::vec3(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]));
  m.metallic_factor = float(pbr.metallicFactor);
  m.roughness_factor = float(pbr.roughnessFactor);
  m.metallic_roughness_textured = pbr.metallicRoughnessTexture.index >= 0;
  const tinygltf::TextureInfo& info = pbr.baseColorTexture;
  if (info.index < 0) return m;
  m.base_color.image = texture_image(info, "material " + std::to_string(index) + " baseColorTexture");
  if (m.base_color.image < 0) return m;
  m.base_color.texcoord = std::uint32_t(std::max(info.texCoord, 0));
  read_transform(info, &m.base_color);
  const int sampler = model_.textures[std::size_t(info.index)].sampler;
  if (sampler >= 0 && std::size_t(sampler) < model_.samplers.size()) {
    const tinygltf::Sampler& s = model_.samplers[std::size_t(sampler)];
    m.base_color.wrap_s = wrap_of(s.wrapS);
    m.base_color.wrap_t = wrap_of(s.wrapT);
    m.base_color.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::nearest : Filter::linear;
  }
  return m;
}

// The index in textures_ of the image the texture uses, decoded on first use; -1 (noted) if none.
int GltfMaterials::texture_image(const tinygltf::TextureInfo& info, const std::string& what) {
  if (std::size_t(info.index) >= model_.textures.size())
    fail_file(path_, what + ": texture " + std::to_string(info.index) + " does not exist");
  const int source = model_.textures[std::size_t(info.index)].source;
  if (source < 0) {
    notes_.push_back(what + ": texture " + std::to_string(info.index) +
                     " has no image prt decodes (KTX2/Basis or WebP only); the base colour factor alone is used");
    return -1;
  }
  if (std::size_t(source) >= model_.images.size())
    fail_file(path_, what + ": image " + std::to_string(source) + " does not exist");
  int& slot = image_texture_[std::size_t(source)];
  if (slot != -1) return std::max(slot, -1);
  const tinygltf::Image& image = model_.images[std::size_t(source)];
  const std::string name = "image " + std::to_string(source) + " (" + (image.uri.empty() ? "embedded" : image.uri) + ")";
  std::string bytes, problem;
  const std::string hint = std::size_t(source) < images_.size() ? images_[std::size_t(source)].hint : image.uri;
  Texture texture;
  if (!image_bytes(source, &bytes))
    problem = name + ": cannot be read";
  else if (decode_texture(bytes, hint, name, &held_bytes_, &texture, &problem)) {
    slot = int(textures_.size());
    textures_.push_back(std::move(texture));
    return slot;
  }
  notes_.push_back(problem + "; its materials use the base colour factor alone");
  slot = -2;
  return -1;
}

// The file content of image `source`: its buffer view's bytes (bounds-checked), else what tinygltf read.
bool gltf_image_bytes(const tinygltf::Model& model, const std::vector<GltfImageBytes>& images, int source, std::string* bytes) {
  const tinygltf::Image& image = model.images[std::size_t(source)];
  if (image.bufferView < 0) {
    if (std::size_t(source) >= images.size() || !images[std::size_t(source)].present) return false;
    *bytes = images[std::size_t(source)].bytes;
    return true;
  }
  if (std::size_t(image.bufferView) >= model.bufferViews.size()) return false;
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(image.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) return false;
  const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) return false;
  bytes->assign(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
  return true;
}

bool GltfMaterials::image_bytes(int source, std::string* bytes) const { return gltf_image_bytes(model_, images_, source, bytes); }

std::uint32_t GltfMaterials::material_of(int material, const std::string& what) {
  if (material >= 0) {
    if (std::size_t(material) >= model_.materials.size()) fail_file(path_, what + ": material does not exist");
    return std::uint32_t(material);
  }
  if (default_ < 0) {
    default_ = std::int64_t(materials_.size());
    materials_.push_back(Material{"(none)", glm::vec3(1.0f), TextureRef{}, 1.0f, 1.0f, false});
  }
  return std::uint32_t(default_);
}

int GltfMaterials::texcoord_set(std::uint32_t m) const {
  return materials_[m].textured() ? int(materials_[m].base_color.texcoord) : -1;
}

std::uint32_t GltfMaterials::without_texture(std::uint32_t m, const std::string& what) {
  if (m >= plain_.size()) return m;
  if (plain_[m] < 0) {
    notes_.push_back(what + " has no TEXCOORD_" + std::to_string(materials_[m].base_color.texcoord) +
                     " for its base colour texture; its base colour factor alone is used");
    plain_[m] = std::int64_t(materials_.size());
    Material copy = materials_[m];
    copy.base_color = TextureRef{};
    materials_.push_back(copy);
  }
  return std::uint32_t(plain_[m]);
}

void GltfMaterials::finish(RawMesh* raw) {
  raw->materials = std::move(materials_);
  raw->textures = std::move(textures_);
  for (std::string& note : notes_) raw->notes_only.notes.push_back(std::move(note));
}

}  // namespace prt::mesh::detail
