// The table of BRDFs of a glossy bake and its runs of vertex indices in the bake parameters
// (vertex_brdfs.h).
#include "brdf/vertex_brdfs.h"

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace prt::brdf {

void write_vertex_brdfs(const VertexBrdfs& brdfs, nlohmann::ordered_json& j) {
  if (brdfs.table.size() == 1) {
    j["brdf"] = to_spec(brdfs.table[0]);
    return;
  }
  nlohmann::ordered_json specs = nlohmann::ordered_json::array(), runs = nlohmann::ordered_json::array();
  for (const Brdf& b : brdfs.table) specs.push_back(to_spec(b));
  for (std::size_t v = 0; v < brdfs.vertex.size();) {
    std::size_t end = v;
    while (end < brdfs.vertex.size() && brdfs.vertex[end] == brdfs.vertex[v]) ++end;
    runs.push_back({brdfs.vertex[v], end - v});
    v = end;
  }
  j["brdfs"] = specs;
  j["brdf_runs"] = runs;
}

VertexBrdfs read_vertex_brdfs(const nlohmann::json& j, std::size_t vertex_count, const std::string& what) {
  VertexBrdfs out;
  if (j.is_object() && j.contains("brdf") && j["brdf"].is_string()) {
    out.table.push_back(parse_brdf(j["brdf"].get<std::string>()));
    return out;
  }
  if (!j.is_object() || !j.contains("brdfs") || !j["brdfs"].is_array() || j["brdfs"].empty() || !j.contains("brdf_runs") ||
      !j["brdf_runs"].is_array())
    fail_file(what, "the transfer records no BRDF; give one");
  for (const nlohmann::json& spec : j["brdfs"]) {
    if (!spec.is_string()) fail_file(what, "\"brdfs\" holds a value that is not a BRDF spec");
    out.table.push_back(parse_brdf(spec.get<std::string>()));
  }
  for (const nlohmann::json& run : j["brdf_runs"]) {
    if (!run.is_array() || run.size() != 2 || !run[0].is_number_unsigned() || !run[1].is_number_unsigned() ||
        run[0].get<std::uint64_t>() >= out.table.size() || run[1].get<std::uint64_t>() > vertex_count - out.vertex.size())
      fail_file(what, "\"brdf_runs\" has a run that is not [index < " + std::to_string(out.table.size()) + ", count] within the vertices");
    out.vertex.insert(out.vertex.end(), run[1].get<std::size_t>(), run[0].get<std::uint32_t>());
  }
  if (out.vertex.size() != vertex_count)
    fail_file(what, "\"brdf_runs\" covers " + std::to_string(out.vertex.size()) + " of " + std::to_string(vertex_count) + " vertices");
  return out;
}

}  // namespace prt::brdf
