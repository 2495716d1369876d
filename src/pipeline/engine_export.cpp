#include "pipeline/engine_export.h"

#include <functional>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "mesh/engine_gltf.h"
#include "shade/surface_albedo.h"
#include "transfer/ktx2.h"

namespace prt::pipeline {

namespace {

using nlohmann::json;

// _PRT_ALBEDO: per vertex the albedo baked into the transfer (shade::surface_albedo), which the discs'
// direct light takes as `prt render` does (per vertex and per texel).
mesh::EngineAttribute albedo_attribute(const mesh::Mesh& mesh, const compress::CompressedTransfer& model, const std::string& path) {
  const std::size_t n = mesh.vertex_count();
  mesh::EngineAttribute albedo{"_PRT_ALBEDO", 3, std::vector<float>(3 * n)};
  const std::vector<glm::vec3> baked = shade::surface_albedo(mesh, model.source, path);
  for (std::size_t v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) albedo.values[3 * v + std::size_t(c)] = baked[v][c];
  return albedo;
}

// The per-vertex attributes of `model`: the cluster index, the weights four per VEC4.
std::vector<mesh::EngineAttribute> transfer_attributes(const mesh::Mesh& mesh, const compress::CompressedTransfer& model) {
  const std::size_t n = mesh.vertex_count(), terms = std::size_t(model.pca);
  std::vector<mesh::EngineAttribute> out;
  mesh::EngineAttribute cluster{"_PRT_CLUSTER", 1, std::vector<float>(n)};
  for (std::size_t v = 0; v < n; ++v) cluster.values[v] = float(model.cluster[v]);
  out.push_back(std::move(cluster));
  for (std::size_t a = 0; a * 4 < terms; ++a) {
    mesh::EngineAttribute weights{"_PRT_WEIGHTS" + std::to_string(a), 4, std::vector<float>(4 * n, 0.0f)};
    for (std::size_t v = 0; v < n; ++v)
      for (std::size_t j = 0; j < 4 && 4 * a + j < terms; ++j) weights.values[4 * v + j] = model.weights[v * terms + 4 * a + j];
    out.push_back(std::move(weights));
  }
  return out;
}

// Per texel: the cluster texture (R the cluster index, G the texel's coverage code, B = A = 0) and the
// weights texture (a 2D array, 4 weights per layer, zero-padded); empty texels 0 throughout.
std::vector<mesh::GlbImage> texel_images(const compress::CompressedTransfer& model) {
  const transfer::Header& h = model.source;
  const std::size_t texels = std::size_t(h.texel_width) * h.texel_height, terms = std::size_t(model.pca);
  const std::size_t layers = (terms + 3) / 4;
  transfer::Ktx2Image cluster{int(h.texel_width), int(h.texel_height), 0, 0, std::vector<float>(4 * texels, 0.0f)};
  transfer::Ktx2Image weights{int(h.texel_width), int(h.texel_height), 0, int(layers), std::vector<float>(4 * texels * layers, 0.0f)};
  std::size_t p = 0;
  for (std::size_t t = 0; t < texels; ++t) {
    if (model.coverage[t] == transfer::kTexelEmpty) continue;
    cluster.rgba[4 * t] = float(model.cluster[p]);
    cluster.rgba[4 * t + 1] = float(model.coverage[t]);
    for (std::size_t j = 0; j < terms; ++j) weights.rgba[4 * ((j / 4) * texels + t) + j % 4] = model.weights[p * terms + j];
    ++p;
  }
  std::vector<mesh::GlbImage> images{{transfer::write_ktx2_rgba16f(cluster), "image/ktx2"}};
  if (layers > 0) images.push_back({transfer::write_ktx2_rgba16f(weights), "image/ktx2"});
  return images;
}

// Model `index` of the root extension; its means and bases are arrays 2 index and 2 index + 1.
json model_json(const compress::CompressedTransfer& model, const mesh::EngineIndices& added, int index) {
  const transfer::Header& h = model.source;
  json parameters = json::parse(h.parameters_json, nullptr, false);
  if (!parameters.is_object()) parameters = json::object();
  return {{"kind", transfer::kind_name(h.kind)},
          {"bands", h.bands},
          {"channels", h.channels},
          {"clusters", model.clusters},
          {"terms", model.pca},
          {"bounce", model.bounce},
          {"means", added.arrays[std::size_t(2 * index)]},
          {"bases", added.arrays[std::size_t(2 * index + 1)]},
          {"layout", model.bounce ? "per point [T, T_bounce], each channel-major then SH index (prt basis)"
                                  : "per point T, channel-major then SH index (prt basis)"},
          {"parameters", parameters}};
}

void check_model(const std::string& path, const mesh::Mesh& mesh, const compress::CompressedTransfer& model) {
  const transfer::Header& h = model.source;
  if (transfer::is_glossy(h.kind)) fail_file(path, "cannot write glTF: the engine glTF carries diffuse transfer only");
  transfer::check_mesh_match(path, h, mesh.vertex_count(), mesh.triangle_count(), mesh::fingerprint(mesh));
}

using PrimitiveObject = std::function<json(const mesh::EngineIndices&)>;

// Adds model `index` to `extras` for the primitives of `group` (-1: all): its means and bases, per texel
// its images, per vertex its attributes. Returns its primitives' extension object.
PrimitiveObject add_model(mesh::EngineExtras& extras, const mesh::Mesh& mesh, const compress::CompressedTransfer& model, int index,
                          int group) {
  const transfer::Header& h = model.source;
  extras.arrays.push_back(model.means);
  extras.arrays.push_back(model.bases);
  if (!h.is_texel()) {
    for (mesh::EngineAttribute& a : transfer_attributes(mesh, model)) {  // (_PRT_ALBEDO: the caller's, on every primitive)
      a.group = group;
      extras.attributes.push_back(std::move(a));
    }
    return [index](const mesh::EngineIndices&) { return json{{"model", index}}; };
  }
  const std::size_t first = extras.images.size();
  for (mesh::GlbImage& image : texel_images(model)) extras.images.push_back(std::move(image));
  const bool weights = extras.images.size() > first + 1;
  extras.lightmap_set = int(h.uv_set);
  return [index, first, weights, &h](const mesh::EngineIndices& added) {
    json ext = {{"model", index}, {"texCoord", h.uv_set}, {"width", h.texel_width}, {"height", h.texel_height},
                {"cluster", added.images[first]}};
    if (weights) ext["weights"] = added.images[first + 1];
    return ext;
  };
}

}  // namespace

void write_engine_gltf(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
                       const compress::CompressedTransfer& model, bool uv_generated) {
  check_model(path, mesh, model);
  mesh::EngineExtras extras;
  extras.extension = kTransferExtension;
  extras.corner_uvs = uv_generated;
  const PrimitiveObject primitive = add_model(extras, mesh, model, 0, -1);
  extras.attributes.push_back(albedo_attribute(mesh, model, path));
  extras.root = [&](const mesh::EngineIndices& added) { return json{{"version", 1}, {"models", {model_json(model, added, 0)}}}; };
  extras.primitive = [&](const mesh::EngineIndices& added, int) { return primitive(added); };
  mesh::write_engine_glb(path, source_path, mesh, extras);
}

void write_mixed_engine_gltf(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
                             const compress::CompressedTransfer& texels, const compress::CompressedTransfer& vertices,
                             const std::vector<std::uint8_t>& vertex_triangle) {
  check_model(path, mesh, texels);
  check_model(path, mesh, vertices);
  if (!texels.source.is_texel() || vertices.source.is_texel())
    fail_file(path, "cannot write glTF: a mixed scene needs a per-texel and a per-vertex model");
  mesh::EngineExtras extras;
  extras.extension = kTransferExtension;
  extras.triangle_group = vertex_triangle;  // group 0: per texel (model 0), 1: per vertex (model 1)
  const PrimitiveObject texel = add_model(extras, mesh, texels, 0, 0);
  const PrimitiveObject vertex = add_model(extras, mesh, vertices, 1, 1);
  extras.attributes.push_back(albedo_attribute(mesh, vertices, path));
  extras.root = [&](const mesh::EngineIndices& added) {
    return json{{"version", 1}, {"models", {model_json(texels, added, 0), model_json(vertices, added, 1)}}};
  };
  extras.primitive = [&](const mesh::EngineIndices& added, int group) { return group == 0 ? texel(added) : vertex(added); };
  mesh::write_engine_glb(path, source_path, mesh, extras);
}

}  // namespace prt::pipeline
