#include "shade/surface_albedo.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace prt::shade {

bool baked_with_mesh_albedo(const mesh::Mesh& mesh, const transfer::Header& header) {
  const nlohmann::json params = nlohmann::json::parse(header.parameters_json, nullptr, false);
  if (!params.is_object() || !params.contains("albedo")) return !mesh.albedo.empty();
  return params["albedo"].is_string() && params["albedo"] == "mesh";
}

std::vector<glm::vec3> surface_albedo(const mesh::Mesh& mesh, const transfer::Header& header, const std::string& what) {
  const nlohmann::json params = nlohmann::json::parse(header.parameters_json, nullptr, false);
  const bool has_entry = params.is_object() && params.contains("albedo");
  if (baked_with_mesh_albedo(mesh, header)) {
    if (mesh.albedo.size() != mesh.positions.size()) fail_file(what, "transfer was baked with the mesh's albedo, but the mesh has none");
    return mesh.albedo;
  }
  glm::vec3 fallback(0.8f);
  if (has_entry) {
    const nlohmann::json& a = params["albedo"];
    if (!a.is_array() || a.size() != 3) fail_file(what, "bake parameters: \"albedo\" must be \"mesh\" or [r, g, b]");
    for (int c = 0; c < 3; ++c) {
      if (!a[c].is_number()) fail_file(what, "bake parameters: \"albedo\" must hold three numbers");
      const double x = a[c].get<double>();
      if (!(x >= 0.0 && x <= 1.0)) fail_file(what, "bake parameters: albedo components must lie in [0, 1]");
      fallback[c] = static_cast<float>(x);
    }
  }
  return std::vector<glm::vec3>(mesh.positions.size(), fallback);
}

mesh::Footprint baked_footprint(const transfer::Header& header, const std::string& what) {
  const nlohmann::json params = nlohmann::json::parse(header.parameters_json, nullptr, false);
  if (!params.is_object() || !params.contains("footprint")) return mesh::Footprint::vertex;
  const nlohmann::json& f = params["footprint"];
  if (f == "area") return mesh::Footprint::area;
  if (f == "vertex") return mesh::Footprint::vertex;
  fail_file(what, "bake parameters: \"footprint\" must be \"area\" or \"vertex\"");
}

}  // namespace prt::shade
