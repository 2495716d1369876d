// glTF 2.0 (.gltf / .glb) loading through tinygltf: the scene's nodes depth-first, node transforms
// applied, every triangle primitive's vertices in accessor order (see mesh.h for the exact order).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <tiny_gltf.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "core/json_depth.h"
#include "mesh/gltf_compressed.h"
#include "mesh/gltf_materials.h"
#include "mesh/gltf_reader.h"
#include "mesh/loaders.h"

namespace prt::mesh::detail {

namespace {

constexpr int kMaxNodeDepth = 1024;

glm::dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glTF
  glm::dmat4 m(1.0);
  if (node.translation.size() == 3)
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)  // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z)
    m = m * glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
  if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return m;
}

struct Loader {
  const std::string& path;
  const tinygltf::Model& model;
  GltfReader reader;
  GltfMaterials& materials;
  RawMesh raw;
  std::vector<std::uint8_t> visited;  // the hierarchy must be a forest: each node reached once
  bool any_albedo_source = false, any_vertex_colour = false, any_skin_or_morph = false;
  bool any_emission = false, any_emissive_texture = false;
  std::size_t primitives_without_normals = 0, skipped_modes = 0;
  int uv_set = -1;  // the lightmap UV set (TEXCOORD_<uv_set>); -1 when no triangle primitive has one
  std::string missing_uv{};  // the first primitive without it, for missing_uv_reason

  void visit(int node_index, const glm::dmat4& parent, int depth) {
    if (node_index < 0 || std::size_t(node_index) >= model.nodes.size())
      reader.bad("node " + std::to_string(node_index) + " does not exist");
    // glTF requires disjoint strict trees; refusing a second visit also stops cycles and the
    // exponential blow-up of a node DAG. The depth limit keeps the recursion's stack bounded.
    if (visited[std::size_t(node_index)])
      reader.bad("node " + std::to_string(node_index) +
                 " is reached twice (the node hierarchy must be a set of trees)");
    if (depth > kMaxNodeDepth) reader.bad("the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
    visited[std::size_t(node_index)] = 1;
    const tinygltf::Node& node = model.nodes[std::size_t(node_index)];
    const glm::dmat4 world = parent * local_transform(node);
    if (node.mesh >= 0) {
      if (std::size_t(node.mesh) >= model.meshes.size())
        reader.bad("node " + std::to_string(node_index) + ": mesh does not exist");
      const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
      if (node.skin >= 0) any_skin_or_morph = true;
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
        add_primitive(mesh.primitives[p], world, SourcePrimitive{node_index, node.mesh, int(p), 0, 0, node.name});
    }
    for (int child : node.children) visit(child, world, depth + 1);
  }

  // Adds the triangles of `prim` (drawn by node source.node) and, when it has vertices, its entry in
  // source_primitives, which its triangles' triangle_source refer to.
  void add_primitive(const tinygltf::Primitive& prim, const glm::dmat4& world, SourcePrimitive source) {
    const std::string what = "mesh " + std::to_string(source.mesh) + " primitive " + std::to_string(source.primitive);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN) reader.bad(what + ": invalid mode " + std::to_string(mode));
    const auto position_it = prim.attributes.find("POSITION");
    if (mode < TINYGLTF_MODE_TRIANGLES || position_it == prim.attributes.end()) {
      ++skipped_modes;
      return;
    }
    if (!prim.targets.empty()) any_skin_or_morph = true;
    int components = 0;
    const std::vector<double> positions = reader.read_accessor(position_it->second, what + " POSITION", &components);
    if (components != 3) reader.bad(what + ": POSITION is not a vec3");
    const std::size_t count = positions.size() / 3;
    const std::size_t base = raw.positions.size();
    if (base + count >= std::numeric_limits<std::uint32_t>::max()) reader.bad("too many vertices");
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec3 local(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
      if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z)) {
        std::ostringstream text;
        text << what << ": POSITION " << i << " is not finite (" << local.x << ", " << local.y << ", " << local.z
             << ")";
        reader.bad(text.str());
      }
      const glm::dvec4 p = world * glm::dvec4(local, 1.0);
      raw.positions.emplace_back(float(p.x), float(p.y), float(p.z));
    }

    // Triangles, in the winding the spec defines for each mode; reversed where the transform mirrors.
    const glm::dmat3 linear(world);
    const bool mirrored = glm::determinant(linear) < 0.0;
    std::vector<std::uint32_t> order;
    if (prim.indices >= 0) {
      if (std::size_t(prim.indices) >= model.accessors.size()) reader.bad(what + ": indices accessor does not exist");
      const tinygltf::Accessor& ia = model.accessors[std::size_t(prim.indices)];
      if (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        reader.bad(what + ": indices must be unsigned byte, short or int");
      const std::vector<double> values = reader.read_accessor(prim.indices, what + " indices", &components);
      if (components != 1) reader.bad(what + ": indices are not scalars");
      order.reserve(values.size());
      for (double v : values) {
        if (v >= double(count))
          reader.bad(what + ": index " + std::to_string(std::uint64_t(v)) + " out of range (POSITION has " +
                     std::to_string(count) + " vertices)");
        order.push_back(std::uint32_t(v));
      }
    } else {
      for (std::size_t i = 0; i < count; ++i) order.push_back(std::uint32_t(i));
    }
    const std::vector<glm::vec2> uv = read_uv(prim, count, what);
    std::vector<glm::vec2> colour_uv;
    const std::uint32_t material = primitive_material(prim, count, what, &colour_uv);
    const std::uint32_t source_index = std::uint32_t(raw.source_primitives.size());
    source.first_vertex = std::uint32_t(base);
    source.vertex_count = std::uint32_t(count);
    if (count > 0) raw.source_primitives.push_back(std::move(source));
    std::uint32_t local_triangle = 0;
    auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (mirrored) std::swap(b, c);
      raw.triangle_source.push_back({source_index, local_triangle++});
      raw.indices.insert(raw.indices.end(),
                         {std::uint32_t(base + a), std::uint32_t(base + b), std::uint32_t(base + c)});
      if (!uv.empty()) raw.corner_uv.insert(raw.corner_uv.end(), {uv[a], uv[b], uv[c]});
      raw.triangle_material.push_back(material);
      if (colour_uv.empty())
        raw.base_color_uv.insert(raw.base_color_uv.end(), 3, glm::vec2(0.0f));
      else
        raw.base_color_uv.insert(raw.base_color_uv.end(), {colour_uv[a], colour_uv[b], colour_uv[c]});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (std::size_t t = 0; t + 2 < order.size(); t += 3) emit(order[t], order[t + 1], order[t + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < order.size(); ++i) emit(order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]);
    } else {  // fan: (v[i+1], v[i+2], v[0])
      for (std::size_t i = 0; i + 2 < order.size(); ++i) emit(order[i + 1], order[i + 2], order[0]);
    }

    add_normals(prim, linear, count, what);
    add_albedo(prim, count, what);
    add_emission(prim, count);
  }

  // The primitive's mesh material, and in *colour_uv the UVs its base colour texture reads (empty if
  // untextured; a primitive without that TEXCOORD set gets the material's untextured copy).
  std::uint32_t primitive_material(const tinygltf::Primitive& prim, std::size_t count, const std::string& what,
                                   std::vector<glm::vec2>* colour_uv) {
    const std::uint32_t material = materials.material_of(prim.material, what);
    const int set = materials.texcoord_set(material);
    if (set < 0) return material;
    *colour_uv = read_texcoord(prim, set, count, what);
    return colour_uv->empty() ? materials.without_texture(material, what) : material;
  }

  // The primitive's TEXCOORD_<uv_set> per vertex; empty, with missing_uv noted, when it has none.
  std::vector<glm::vec2> read_uv(const tinygltf::Primitive& prim, std::size_t count, const std::string& what) {
    const int set = uv_set < 0 ? 0 : uv_set;
    std::vector<glm::vec2> uv = read_texcoord(prim, set, count, what);
    if (uv.empty() && missing_uv.empty()) missing_uv = what + " has no TEXCOORD_" + std::to_string(set);
    return uv;
  }

  // The primitive's TEXCOORD_<set> per vertex (glTF's v-down convention is prt's); empty when it has none.
  std::vector<glm::vec2> read_texcoord(const tinygltf::Primitive& prim, int set, std::size_t count, const std::string& what) {
    const std::string name = "TEXCOORD_" + std::to_string(set);
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) return {};
    int components = 0;
    const std::vector<double> values = reader.read_accessor(it->second, what + " " + name, &components);
    if (components != 2 || values.size() != 2 * count) reader.bad(what + ": " + name + " is not a vec2 per vertex");
    std::vector<glm::vec2> uv(count);
    for (std::size_t i = 0; i < count; ++i) uv[i] = glm::vec2(float(values[2 * i]), float(values[2 * i + 1]));
    return uv;
  }

  // emissiveFactor times KHR_materials_emissive_strength.emissiveStrength (glTF spec and the extension's).
  void add_emission(const tinygltf::Primitive& prim, std::size_t count) {
    glm::dvec3 emission(0.0);
    if (prim.material >= 0 && std::size_t(prim.material) < model.materials.size()) {
      const tinygltf::Material& material = model.materials[std::size_t(prim.material)];
      if (material.emissiveFactor.size() >= 3)
        emission = glm::dvec3(material.emissiveFactor[0], material.emissiveFactor[1], material.emissiveFactor[2]);
      const auto ext = material.extensions.find("KHR_materials_emissive_strength");
      if (ext != material.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength")) {
        const tinygltf::Value& strength = ext->second.Get("emissiveStrength");
        if (strength.IsNumber()) emission *= strength.GetNumberAsDouble();
      }
      if (material.emissiveTexture.index >= 0) any_emissive_texture = true;
    }
    if (emission != glm::dvec3(0.0)) any_emission = true;
    raw.emission.insert(raw.emission.end(), count, glm::vec3(emission));
  }

  void add_normals(const tinygltf::Primitive& prim, const glm::dmat3& linear, std::size_t count,
                   const std::string& what) {
    raw.normals.resize(raw.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
    raw.has_normal.resize(raw.positions.size(), 0);
    const std::size_t base = raw.positions.size() - count;
    const auto it = prim.attributes.find("NORMAL");
    if (it == prim.attributes.end()) {
      ++primitives_without_normals;
      return;
    }
    int components = 0;
    const std::vector<double> normals = reader.read_accessor(it->second, what + " NORMAL", &components);
    if (components != 3 || normals.size() != 3 * count) reader.bad(what + ": NORMAL is not a vec3 per vertex");
    const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec3 n = normal_matrix * glm::dvec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
      const double len = glm::length(n);
      // Leave unit normals unrounded by a division (finish_mesh keeps them bit for bit), and zero or
      // non-finite ones as they are (finish_mesh replaces them).
      const bool keep = !(len > 0.0) || !std::isfinite(len) || std::abs(len * len - 1.0) <= 1e-6;
      raw.normals[base + i] = keep ? glm::vec3(n) : glm::vec3(n / len);
      raw.has_normal[base + i] = 1;
    }
  }

  void add_albedo(const tinygltf::Primitive& prim, std::size_t count, const std::string& what) {
    glm::dvec3 factor(1.0);
    if (prim.material >= 0) {
      if (std::size_t(prim.material) >= model.materials.size()) reader.bad(what + ": material does not exist");
      const tinygltf::PbrMetallicRoughness& pbr = model.materials[std::size_t(prim.material)].pbrMetallicRoughness;
      if (pbr.baseColorFactor.size() >= 3)
        factor = glm::dvec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
      any_albedo_source = true;
    }
    std::vector<double> colours;
    int components = 0;
    const auto it = prim.attributes.find("COLOR_0");
    if (it != prim.attributes.end()) {
      colours = reader.read_accessor(it->second, what + " COLOR_0", &components);
      if ((components != 3 && components != 4) || colours.size() != std::size_t(components) * count)
        reader.bad(what + ": COLOR_0 is not a vec3 or vec4 per vertex");
      any_albedo_source = any_vertex_colour = true;
    }
    for (std::size_t i = 0; i < count; ++i) {
      glm::dvec3 colour(1.0);
      if (!colours.empty())
        colour = glm::dvec3(colours[i * std::size_t(components)], colours[i * std::size_t(components) + 1],
                            colours[i * std::size_t(components) + 2]);
      raw.vertex_color.emplace_back(colour);
      raw.albedo.emplace_back(factor * colour);
    }
  }
};

}  // namespace

namespace {

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t(static_cast<unsigned char>(bytes[offset + std::size_t(k)])) << (8 * k);
  return v;
}

/// Checks the GLB container (glTF 2.0 spec, "Binary glTF Layout") before tinygltf sees it: magic,
/// version 2, a total length equal to the file's, a JSON chunk first, and every chunk inside the
/// file (tinygltf 2.7 accepts a BIN chunk that runs 8 bytes past the end, and reads past it).
/// Returns the JSON chunk's text.
std::string_view glb_json_chunk(const std::string& path, const std::string& bytes) {
  if (bytes.size() < 20) fail_file(path, "truncated GLB: shorter than its 12-byte header and first chunk header");
  if (bytes.compare(0, 4, "glTF") != 0) fail_file(path, "not a binary glTF file (wrong magic)");
  const std::uint32_t version = u32_at(bytes, 4), length = u32_at(bytes, 8);
  if (version != 2) fail_file(path, "GLB version " + std::to_string(version) + " (prt reads version 2, glTF 2.0)");
  if (length != bytes.size())
    fail_file(path, "GLB header gives a total length of " + std::to_string(length) + " bytes, but the file has " +
                        std::to_string(bytes.size()));
  std::string_view json;
  for (std::size_t offset = 12; offset < bytes.size();) {
    if (bytes.size() - offset < 8) fail_file(path, "truncated GLB: a chunk header at byte " + std::to_string(offset));
    const std::uint32_t chunk_length = u32_at(bytes, offset), type = u32_at(bytes, offset + 4);
    if (chunk_length > bytes.size() - offset - 8)
      fail_file(path, "GLB chunk at byte " + std::to_string(offset) + " claims " + std::to_string(chunk_length) +
                          " bytes, more than the file holds");
    if (offset == 12 && type != 0x4E4F534Au) fail_file(path, "GLB's first chunk is not JSON");
    if (offset == 12) json = std::string_view(bytes).substr(20, chunk_length);
    offset += 8 + std::size_t(chunk_length);
  }
  return json;
}

/// tinygltf's file reader for external buffers: only regular files of at most kMaxInputBytes (a
/// folder or a FIFO as a buffer uri would allocate without bound or block).
bool read_external_file(std::vector<unsigned char>* out, std::string* err, const std::string& file, void*) {
  try {
    const std::string bytes = read_file(file);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const Error& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

/// Whether a buffer uri names anything, by stat(): tinygltf's own check opens the file, which blocks
/// on a FIFO. read_external_file then refuses what is not a regular file.
bool file_exists(const std::string& file, void*) {
  struct stat info;
  return stat(file.c_str(), &info) == 0;
}

/// Paths are used as written: no shell-style expansion of "~" or "$VAR" in a buffer uri.
std::string path_as_written(const std::string& file, void*) { return file; }

/// The bytes to hand tinygltf: `bytes` with its JSON replaced by `json` (the GLB's other chunks kept).
std::string with_json(const std::string& bytes, std::string_view old_json, bool binary, std::string json) {
  if (!binary) return json;
  json.append((4 - json.size() % 4) % 4, ' ');
  const std::size_t rest = std::size_t(old_json.data() - bytes.data()) + old_json.size();
  std::string out(20, '\0');
  auto put = [&](std::size_t at, std::size_t v) {
    for (int k = 0; k < 4; ++k) out[at + std::size_t(k)] = char((v >> (8 * k)) & 0xFF);
  };
  put(0, 0x46546C67u);  // "glTF"
  put(4, 2);
  put(8, 20 + json.size() + (bytes.size() - rest));
  put(12, json.size());
  put(16, 0x4E4F534Au);  // "JSON"
  return out + json + bytes.substr(rest);
}

/// Checks extensionsRequired before any buffer is read, then parses with tinygltf and decodes the
/// compressed geometry (gltf_compressed.h), so that the model reads as plain glTF.
tinygltf::Model parse_gltf(const std::string& path, const std::string& file_bytes, bool binary, std::string* warn,
                           std::vector<GltfImageBytes>* images, nlohmann::json* source_document = nullptr) {
  const std::string_view text = binary ? glb_json_chunk(path, file_bytes) : std::string_view(file_bytes);
  check_json_depth(text, path);
  nlohmann::json document = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  check_required_extensions(path, document);  // a malformed document is tinygltf's to name
  if (source_document) *source_document = document;
  const bool stubbed = patch_for_tinygltf(&document);
  const std::string patched = stubbed ? with_json(file_bytes, text, binary, document.dump()) : std::string();
  const std::string& bytes = stubbed ? patched : file_bytes;
  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(keep_gltf_image, images);
  gltf.SetFsCallbacks({&file_exists, &path_as_written, &read_external_file, &tinygltf::WriteWholeFile, nullptr});
  tinygltf::Model model;
  std::string err;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  bool ok = false;
  try {
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned int>(bytes.size()), base_dir)
                : gltf.LoadASCIIFromString(&model, &err, warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                           base_dir);
  } catch (const std::bad_alloc&) {
    fail_file(path, "cannot read glTF: a buffer is too large for memory");
  } catch (const std::exception&) {  // e.g. vector::at for a buffer of byteLength 0 in tinygltf 2.7
    fail_file(path, "cannot read glTF: a buffer or buffer view is malformed (byteLength 0?)");
  }
  if (!ok) fail_file(path, "cannot read glTF: " + first_line(err.empty() ? *warn : err));
  decode_meshopt_views(path, &model);
  decode_draco_primitives(path, &model);
  return model;
}

}  // namespace

std::vector<std::string> gltf_referenced_files(const std::string& path, bool binary) {
  const std::string bytes = read_file(path);
  const std::string_view text = binary ? glb_json_chunk(path, bytes) : std::string_view(bytes);
  check_json_depth(text, path);
  const nlohmann::json document = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  std::vector<std::string> files;
  if (!document.is_object()) return files;
  // tinygltf joins a uri to the glTF's folder as written (no percent-decoding in this version).
  const std::string folder = std::filesystem::path(path).parent_path().string();
  for (const char* list : {"buffers", "images"}) {
    if (!document.contains(list) || !document[list].is_array()) continue;
    for (const nlohmann::json& item : document[list]) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
      files.push_back(folder.empty() ? uri : folder + "/" + uri);
    }
  }
  return files;
}

// The lightmap UV set: 1 if any triangle primitive has TEXCOORD_1, else 0 if any has TEXCOORD_0, else -1.
int lightmap_uv_set(const tinygltf::Model& model) {
  int set = -1;
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      if (prim.mode >= 0 && prim.mode < TINYGLTF_MODE_TRIANGLES) continue;
      if (prim.attributes.count("TEXCOORD_1")) return 1;
      if (prim.attributes.count("TEXCOORD_0")) set = 0;
    }
  return set;
}

// The root nodes of each scene to load, scene by scene (mesh.h, VERTEX ORDER): the chosen scene, every
// scene, or the default one (with a note when there are several); every node that is no node's child
// when the file has no scenes.
std::vector<std::vector<int>> scene_roots(const std::string& path, const tinygltf::Model& model, int scene,
                                          LoadReport* notes) {
  const std::size_t scenes = model.scenes.size();
  const std::string have = "the file has " + std::to_string(scenes) + (scenes == 1 ? " scene" : " scenes");
  if (scene >= 0 && std::size_t(scene) >= scenes)
    fail_file(path, "scene " + std::to_string(scene) + " does not exist (" + have + ")");
  if (scene >= 0) return {model.scenes[std::size_t(scene)].nodes};
  if (scene == kAllScenes && scenes > 0) {
    std::vector<std::vector<int>> all;
    for (const tinygltf::Scene& s : model.scenes) all.push_back(s.nodes);
    return all;
  }
  if (model.defaultScene >= 0 && std::size_t(model.defaultScene) >= scenes)
    fail_file(path, "the default scene does not exist");
  if (scenes > 0) {
    const std::size_t chosen = model.defaultScene >= 0 ? std::size_t(model.defaultScene) : 0;
    if (scene == kDefaultScene && scenes > 1)
      notes->notes.push_back(have + "; loaded only scene " + std::to_string(chosen) +
                             ", the default (a scene can be chosen by index, or all of them)");
    return {model.scenes[chosen].nodes};
  }
  std::vector<std::uint8_t> is_child(model.nodes.size(), 0);
  for (const tinygltf::Node& node : model.nodes)
    for (int child : node.children)
      if (child >= 0 && std::size_t(child) < model.nodes.size()) is_child[std::size_t(child)] = 1;
  std::vector<int> roots;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(int(i));
  return {roots};
}

tinygltf::Model read_gltf_model(const std::string& path, bool binary, std::string* warn, std::vector<GltfImageBytes>* images,
                                nlohmann::json* document) {
  const std::string bytes = read_file(path);
  if (bytes.size() >= std::numeric_limits<unsigned int>::max())
    fail_file(path, "file too large for glTF (4 GiB or more)");
  return parse_gltf(path, bytes, binary, warn, images, document);
}

RawMesh load_gltf(const std::string& path, bool binary, int scene) {
  std::string warn;
  std::vector<GltfImageBytes> images;
  const tinygltf::Model model = read_gltf_model(path, binary, &warn, &images);

  GltfMaterials materials(path, model, images);
  Loader loader{path, model, GltfReader(path, model), materials, RawMesh{},
                std::vector<std::uint8_t>(model.nodes.size(), 0)};
  if (!first_line(warn).empty()) loader.raw.notes_only.notes.push_back("glTF reader: " + first_line(warn));

  loader.uv_set = lightmap_uv_set(model);
  for (const std::vector<int>& roots : scene_roots(path, model, scene, &loader.raw.notes_only)) {
    std::fill(loader.visited.begin(), loader.visited.end(), std::uint8_t(0));  // a node may be in several scenes
    for (int root : roots) loader.visit(root, glm::dmat4(1.0), 0);
  }

  RawMesh raw = std::move(loader.raw);
  LoadReport& notes = raw.notes_only;
  notes.skipped_primitives = loader.skipped_modes;
  if (loader.skipped_modes > 0)
    notes.notes.push_back("skipped " + std::to_string(loader.skipped_modes) +
                          " primitives in point or line modes or without POSITION");
  if (loader.any_skin_or_morph) notes.notes.push_back("skins and morph targets are ignored (the bind pose is used)");
  materials.finish(&raw);
  if (!loader.any_albedo_source) {
    raw.albedo.clear();
    raw.materials.clear();
  }
  if (!loader.any_vertex_colour) raw.vertex_color.clear();
  if (!loader.any_emission) raw.emission.clear();
  if (loader.any_emissive_texture) notes.notes.push_back("emissive textures are ignored; emission uses emissiveFactor");
  if (loader.primitives_without_normals > 0)
    raw.computed_normals_reason = std::to_string(loader.primitives_without_normals) + " primitives have no normals";
  raw.uv_set = std::uint32_t(std::max(loader.uv_set, 0));
  if (!loader.missing_uv.empty() || loader.uv_set < 0 || raw.corner_uv.size() != raw.indices.size()) {
    raw.corner_uv.clear();
    raw.missing_uv_reason = loader.uv_set < 0 ? "no primitive has TEXCOORD_0 or TEXCOORD_1" : loader.missing_uv;
  }
  return raw;
}

}  // namespace prt::mesh::detail
