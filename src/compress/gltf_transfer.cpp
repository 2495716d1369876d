#include "compress/gltf_transfer.h"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "mesh/engine_gltf.h"

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
  out.clusters = integer_field(path, model, "clusters", 1, int(std::min<std::uint64_t>(mesh.vertex_count(), 1u << 20)));
  out.pca = integer_field(path, model, "terms", 0, int(out.point_dimension()));
  const std::size_t k = std::size_t(out.clusters), n = std::size_t(out.pca), d = out.point_dimension(), v = mesh.vertex_count();
  out.means = extras.floats(integer_field(path, model, "means", 0, 1 << 30), 1, "PRT_transfer means");
  check_values(path, out.means, k * d, "means");
  out.bases = extras.floats(integer_field(path, model, "bases", 0, 1 << 30), 1, "PRT_transfer bases");
  check_values(path, out.bases, k * n * d, "bases");
  for (float c : extras.vertex_attribute(mesh, "_PRT_CLUSTER", 1)) {
    if (!(c >= 0.0f && c < float(k) && c == std::floor(c)))
      fail_file(path, "_PRT_CLUSTER: a value is not a cluster index in 0.." + std::to_string(k - 1));
    out.cluster.push_back(std::uint32_t(c));
  }
  out.weights.assign(v * n, 0.0f);
  for (std::size_t a = 0; 4 * a < n; ++a) {
    const std::vector<float> w = extras.vertex_attribute(mesh, "_PRT_WEIGHTS" + std::to_string(a), 4);
    check_values(path, w, 4 * v, "_PRT_WEIGHTS" + std::to_string(a));
    for (std::size_t p = 0; p < v; ++p)
      for (std::size_t j = 0; j < 4 && 4 * a + j < n; ++j) out.weights[p * n + 4 * a + j] = w[4 * p + j];
  }
  const std::vector<float> rgb = extras.vertex_attribute(mesh, "_PRT_ALBEDO", 3);
  albedo->resize(v);
  for (std::size_t p = 0; p < v; ++p) {
    (*albedo)[p] = glm::vec3(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
    for (int c = 0; c < 3; ++c)
      if (!((*albedo)[p][c] >= 0.0f && (*albedo)[p][c] <= 1.0f)) fail_file(path, "_PRT_ALBEDO: a value is outside [0, 1]");
  }
  out.per_cluster.resize(k);
  return out;
}

}  // namespace prt::compress
