#include "transfer/mixed_parts.h"

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace prt::transfer {

std::vector<std::pair<std::uint64_t, std::uint64_t>> vertex_runs_of(const std::vector<std::uint8_t>& per_vertex) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> runs;
  for (std::size_t t = 0; t < per_vertex.size(); ++t) {
    if (!per_vertex[t]) continue;
    if (!runs.empty() && runs.back().first + runs.back().second == t) ++runs.back().second;
    else runs.emplace_back(t, 1);
  }
  return runs;
}

std::vector<std::uint8_t> vertex_triangle_mask(const MixedParts& parts, std::uint64_t triangle_count, const std::string& path) {
  std::vector<std::uint8_t> mask(triangle_count, 0);
  for (const auto& [first, count] : parts.vertex_runs) {
    if (first > triangle_count || count > triangle_count - first)
      fail_file(path, "the \"mixed\" entry's vertex_triangles run [" + std::to_string(first) + ", +" + std::to_string(count) +
                          ") reaches past the mesh's " + std::to_string(triangle_count) + " triangles");
    std::fill(mask.begin() + std::ptrdiff_t(first), mask.begin() + std::ptrdiff_t(first + count), std::uint8_t(1));
  }
  return mask;
}

std::string with_mixed_entry(const std::string& parameters_json, const MixedParts& parts) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(parameters_json);
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const auto& [first, count] : parts.vertex_runs) runs.push_back({first, count});
  j["mixed"] = {{"role", parts.role},
                {"partner", parts.partner},
                {"vertex_triangles", runs},
                {"texel_parts", parts.texel_parts},
                {"vertex_parts", parts.vertex_parts}};
  return j.dump();
}

namespace {

std::vector<std::string> names(const nlohmann::json& j, const char* key) {
  std::vector<std::string> out;
  if (!j.contains(key) || !j[key].is_array()) return out;
  for (const nlohmann::json& name : j[key])
    if (name.is_string()) out.push_back(name.get<std::string>());
  return out;
}

}  // namespace

std::optional<MixedParts> read_mixed_entry(const Header& header, const std::string& path) {
  const nlohmann::json j = nlohmann::json::parse(header.parameters_json, nullptr, false);
  if (!j.is_object() || !j.contains("mixed")) return std::nullopt;
  const nlohmann::json& m = j["mixed"];
  auto bad = [&](const std::string& what) { fail_file(path, "the bake parameters' \"mixed\" entry " + what); };
  if (!m.is_object()) bad("is not an object");
  MixedParts parts;
  if (!m.contains("role") || !m["role"].is_string() || (m["role"] != "texel" && m["role"] != "vertex"))
    bad("has no role \"texel\" or \"vertex\"");
  parts.role = m["role"].get<std::string>();
  if (parts.role != (header.is_texel() ? "texel" : "vertex")) bad("has role \"" + parts.role + "\" for a file of the other kind");
  if (!m.contains("partner") || !m["partner"].is_string()) bad("names no partner file");
  parts.partner = m["partner"].get<std::string>();
  const std::filesystem::path partner(parts.partner);
  if (parts.partner.empty() || partner.has_parent_path() || partner.is_absolute() || parts.partner == "." || parts.partner == "..")
    bad("names partner '" + parts.partner + "', not a plain file name");
  if (!m.contains("vertex_triangles") || !m["vertex_triangles"].is_array()) bad("has no vertex_triangles list");
  std::uint64_t end = 0;
  for (const nlohmann::json& run : m["vertex_triangles"]) {
    if (!run.is_array() || run.size() != 2 || !run[0].is_number_unsigned() || !run[1].is_number_unsigned())
      bad("has a vertex_triangles run that is not [first, count]");
    const std::uint64_t first = run[0].get<std::uint64_t>(), count = run[1].get<std::uint64_t>();
    if (first < end || count == 0 || count > header.triangle_count) bad("has vertex_triangles runs out of order, empty or too long");
    parts.vertex_runs.emplace_back(first, count);
    end = first + count;
  }
  parts.texel_parts = names(m, "texel_parts");
  parts.vertex_parts = names(m, "vertex_parts");
  return parts;
}

std::string partner_path(const std::string& path, const MixedParts& parts) {
  return (std::filesystem::path(path).parent_path() / parts.partner).string();
}

}  // namespace prt::transfer
