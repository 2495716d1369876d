#pragma once
// Several BRDFs in one glossy bake (`prt bake --brdf mesh`): a small table of distinct BRDFs and the
// index of each vertex's, as a transfer file's bake parameters record them (docs/formats.md, "BRDFs in
// the bake parameters").
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "brdf/brdf.h"

namespace prt::brdf {

/// table[vertex[v]] is vertex v's BRDF. One entry and an empty `vertex`: every vertex has table[0].
struct VertexBrdfs {
  std::vector<Brdf> table;             ///< distinct BRDFs, at least one
  std::vector<std::uint32_t> vertex;   ///< per vertex an index into table, or empty (all 0)
  /// The index of vertex v's BRDF (0 when `vertex` is empty).
  std::uint32_t of(std::size_t v) const { return vertex.empty() ? 0u : vertex[v]; }
};

/// Writes `brdfs` into the bake parameters `j`: one BRDF as "brdf": SPEC (the single-BRDF form every
/// reader knows); several as "brdfs": [SPEC, ...] and "brdf_runs": [[index, count], ...] (runs of equal
/// index in vertex order) and no "brdf", so that a reader that knows one BRDF only refuses the file.
void write_vertex_brdfs(const VertexBrdfs& brdfs, nlohmann::ordered_json& j);

/// Reads what write_vertex_brdfs wrote from the bake parameters `j` of a file with `vertex_count`
/// vertices. Throws prt::Error("<what>: <problem>") if neither form is there, a spec does not parse,
/// an index is out of the table or the runs do not cover exactly `vertex_count` vertices.
VertexBrdfs read_vertex_brdfs(const nlohmann::json& j, std::size_t vertex_count, const std::string& what);

}  // namespace prt::brdf
