#include "compress/gltf_transfer.h"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "mesh/engine_gltf.h"
#include "transfer/ktx2.h"

namespace prt::compress {

namespace {

using nlohmann::json;

int integer_field(const std::string& path, const json& model, const char* name, int lo, int hi) {
  if (!model.contains(name) || !model[name].is_number_integer() || model[name].get<long long>() < lo ||
      model[name].get<long long>() > hi)
    fail_file(path, std::string("PRT_transfer model 0: \"") + name + "\" must be an integer in " + std::to_string(lo) +
                        ".." + std::to_string(hi));
  return model[name].get<int>();
}

void check_values(const std::string& path, const std::vector<float>& values, std::size_t size, const std::string& what) {
  if (values.size() != size)
    fail_file(path, "PRT_transfer " + what + " has " + std::to_string(values.size()) + " values, expected " + std::to_string(size));
  for (float v : values)
    if (!(std::fabs(v) <= transfer::kMaxTransferMagnitude)) fail_file(path, "PRT_transfer " + what + ": a value is not finite or too large");
}

// The header of model 0's transfer, for `mesh`.
transfer::Header model_header(const std::string& path, const json& model, const mesh::Mesh& mesh) {
  transfer::Header h;
  if (!model.contains("kind") || !model["kind"].is_string()) fail_file(path, "PRT_transfer model 0: no \"kind\"");
  h.kind = transfer::parse_kind(model["kind"].get<std::string>());
  if (transfer::is_glossy(h.kind)) fail_file(path, "PRT_transfer model 0: glossy transfer has no glTF form");
  h.bands = std::uint32_t(integer_field(path, model, "bands", 1, 32));
  h.channels = std::uint32_t(integer_field(path, model, "channels", 1, 3));
  if (h.channels == 2) fail_file(path, "PRT_transfer model 0: \"channels\" must be 1 or 3");
  h.vertex_count = mesh.vertex_count();
  h.triangle_count = mesh.triangle_count();
  h.mesh_fingerprint = mesh::fingerprint(mesh);
  h.parameters_json = model.contains("parameters") ? model["parameters"].dump() : "{}";
  h.bounce_only_section = model.value("bounce", false);
  if (h.bounce_only_section && h.kind != transfer::Kind::interreflected)
    fail_file(path, "PRT_transfer model 0: \"bounce\" is only for interreflected transfer");
  return h;
}

// The cluster index `c` of a point, checked: an integer in [0, k).
std::uint32_t cluster_index(const std::string& path, float c, std::size_t k, const char* what) {
  if (!(c >= 0.0f && c < float(k) && c == std::floor(c)))
    fail_file(path, std::string(what) + ": a value is not a cluster index in 0.." + std::to_string(k - 1));
  return std::uint32_t(c);
}

// Per vertex: _PRT_CLUSTER, _PRT_WEIGHTSn and _PRT_ALBEDO of every baked primitive, in vertex order.
void read_vertex_points(const std::string& path, const mesh::GltfExtras& extras, const mesh::Mesh& mesh,
                        CompressedTransfer* out, std::vector<glm::vec3>* albedo) {
  const std::size_t k = std::size_t(out->clusters), n = std::size_t(out->pca), v = mesh.vertex_count();
  for (float c : extras.vertex_attribute(mesh, "_PRT_CLUSTER", 1)) out->cluster.push_back(cluster_index(path, c, k, "_PRT_CLUSTER"));
  out->weights.assign(v * n, 0.0f);
  for (std::size_t a = 0; 4 * a < n; ++a) {
    const std::vector<float> w = extras.vertex_attribute(mesh, "_PRT_WEIGHTS" + std::to_string(a), 4);
    check_values(path, w, 4 * v, "_PRT_WEIGHTS" + std::to_string(a));
    for (std::size_t p = 0; p < v; ++p)
      for (std::size_t j = 0; j < 4 && 4 * a + j < n; ++j) out->weights[p * n + 4 * a + j] = w[4 * p + j];
  }
  const std::vector<float> rgb = extras.vertex_attribute(mesh, "_PRT_ALBEDO", 3);
  albedo->resize(v);
  for (std::size_t p = 0; p < v; ++p) {
    (*albedo)[p] = glm::vec3(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
    for (int c = 0; c < 3; ++c)
      if (!((*albedo)[p][c] >= 0.0f && (*albedo)[p][c] <= 1.0f)) fail_file(path, "_PRT_ALBEDO: a value is outside [0, 1]");
  }
}

// The PRT_transfer object of the first baked primitive when it is per texel (has "cluster"), else null.
const json* texel_extension(const std::string& path, const json& doc, const mesh::Mesh& mesh) {
  if (mesh.source_primitives.empty()) fail_file(path, "PRT_transfer: the file has no triangle primitive");
  const mesh::SourcePrimitive& sp = mesh.source_primitives[0];
  const json& prim = doc["meshes"][std::size_t(sp.mesh)]["primitives"][std::size_t(sp.primitive)];
  if (!prim.contains("extensions") || !prim["extensions"].contains("PRT_transfer"))
    fail_file(path, "mesh " + std::to_string(sp.mesh) + " primitive " + std::to_string(sp.primitive) + " has no PRT_transfer");
  const json& ext = prim["extensions"]["PRT_transfer"];
  return ext.is_object() && ext.contains("cluster") ? &ext : nullptr;
}

// prt reads one model per file: a mixed scene's (a per-texel model 0 and a per-vertex model 1 on
// different primitives, formats.md "Mixed scenes in the engine glTF") is refused, naming its pair.
void check_single_model(const std::string& path, const json& doc, const mesh::Mesh& mesh) {
  for (const mesh::SourcePrimitive& sp : mesh.source_primitives) {
    const json& prim = doc["meshes"][std::size_t(sp.mesh)]["primitives"][std::size_t(sp.primitive)];
    const json* ext = prim.contains("extensions") && prim["extensions"].contains("PRT_transfer") ? &prim["extensions"]["PRT_transfer"] : nullptr;
    if (ext && ext->is_object() && ext->contains("model") && (*ext)["model"] != json(0))
      fail_file(path, "PRT_transfer: mesh " + std::to_string(sp.mesh) + " primitive " + std::to_string(sp.primitive) +
                          " uses model " + (*ext)["model"].dump() +
                          "; prt reads one model per file (a mixed scene's engine glTF is for engines: render its .prt pair)");
  }
}

// Per texel: the size, UV set and images of the primitive extension `ext`; the points are the texels
// whose coverage code (the cluster image's G) is not empty, in row-major order.
void read_texel_points(const std::string& path, const mesh::GltfExtras& extras, const json& ext, const mesh::Mesh& mesh,
                       CompressedTransfer* out) {
  transfer::Header& h = out->source;
  h.texel_width = std::uint32_t(integer_field(path, ext, "width", 1, int(transfer::kMaxTexelSide)));
  h.texel_height = std::uint32_t(integer_field(path, ext, "height", 1, int(transfer::kMaxTexelSide)));
  h.uv_set = std::uint32_t(integer_field(path, ext, "texCoord", 0, 64));
  if (!mesh.has_lightmap_uv() || mesh.lightmap_uv_set != h.uv_set)
    fail_file(path, "PRT_transfer: the lightmap UV set TEXCOORD_" + std::to_string(h.uv_set) + " is not the mesh's lightmap UVs");
  h.uv_fingerprint = mesh::uv_fingerprint(mesh);
  const std::size_t texels = std::size_t(h.texel_width) * h.texel_height, n = std::size_t(out->pca);
  const transfer::Ktx2Image cluster = transfer::read_ktx2_rgba16f(extras.image(integer_field(path, ext, "cluster", 0, 1 << 20), "PRT_transfer cluster"), path);
  if (cluster.width != int(h.texel_width) || cluster.height != int(h.texel_height) || cluster.layers != 0 || cluster.depth != 0)
    fail_file(path, "PRT_transfer: the cluster texture is not a 2D texture of width x height");
  transfer::Ktx2Image weights;
  if (n > 0) {
    weights = transfer::read_ktx2_rgba16f(extras.image(integer_field(path, ext, "weights", 0, 1 << 20), "PRT_transfer weights"), path);
    if (weights.width != int(h.texel_width) || weights.height != int(h.texel_height) || weights.layers != int((n + 3) / 4))
      fail_file(path, "PRT_transfer: the weights texture is not a 2D array of width x height and ceil(terms / 4) layers");
  }
  out->coverage.assign(texels, transfer::kTexelEmpty);
  for (std::size_t t = 0; t < texels; ++t) {
    const float code = cluster.rgba[4 * t + 1];
    if (!(code == 0.0f || code == 1.0f || code == 2.0f)) fail_file(path, "PRT_transfer: a coverage code is not 0, 1 or 2");
    out->coverage[t] = std::uint8_t(code);
    if (code == 0.0f) continue;
    out->cluster.push_back(cluster_index(path, cluster.rgba[4 * t], std::size_t(out->clusters), "PRT_transfer cluster texture"));
    for (std::size_t j = 0; j < n; ++j) out->weights.push_back(weights.rgba[4 * ((j / 4) * texels + t) + j % 4]);
  }
  check_values(path, out->weights, out->cluster.size() * n, "weights texture");
  out->texel_points = out->cluster.size();
}

}  // namespace

bool is_glb_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::string(magic, 4) == "glTF";
}

CompressedTransfer read_gltf_transfer(const std::string& path, std::vector<glm::vec3>* albedo) {
  const mesh::GltfExtras extras(path);
  const json& doc = extras.document();
  if (!doc.contains("extensions") || !doc["extensions"].contains("PRT_transfer"))
    fail_file(path, "a glTF without the PRT_transfer extension holds no transfer");
  const json& root = doc["extensions"]["PRT_transfer"];
  if (!root.is_object() || root.value("version", 0) != 1 || !root.contains("models") || !root["models"].is_array() ||
      root["models"].empty() || !root["models"][0].is_object())
    fail_file(path, "PRT_transfer: expected {\"version\": 1, \"models\": [...]}");
  const json& model = root["models"][0];
  const mesh::Mesh mesh = mesh::load_mesh(path, nullptr, true);
  CompressedTransfer out;
  out.source = model_header(path, model, mesh);
  out.bounce = out.source.bounce_only_section;
  out.clusters = integer_field(path, model, "clusters", 1, 1 << 20);
  out.pca = integer_field(path, model, "terms", 0, int(out.point_dimension()));
  const std::size_t k = std::size_t(out.clusters), n = std::size_t(out.pca), d = out.point_dimension();
  out.means = extras.floats(integer_field(path, model, "means", 0, 1 << 30), 1, "PRT_transfer means");
  check_values(path, out.means, k * d, "means");
  out.bases = extras.floats(integer_field(path, model, "bases", 0, 1 << 30), 1, "PRT_transfer bases");
  check_values(path, out.bases, k * n * d, "bases");
  check_single_model(path, doc, mesh);
  const json* texel = texel_extension(path, doc, mesh);
  if (texel)
    read_texel_points(path, extras, *texel, mesh, &out);
  else
    read_vertex_points(path, extras, mesh, &out, albedo);
  if (out.cluster.empty() || k > out.cluster.size())
    fail_file(path, "PRT_transfer model 0: " + std::to_string(k) + " clusters for " + std::to_string(out.cluster.size()) + " points");
  out.per_cluster.resize(k);
  return out;
}

}  // namespace prt::compress
