#pragma once
// Mixed scenes (docs/formats.md "Mixed transfer pairs", docs/conventions.md "Mixed scenes"): one bake
// whose texel parts go into a texel transfer file and whose per-vertex parts into a per-vertex transfer
// file, baked together for the same mesh. Each file of the pair names the other and lists the triangles
// drawn from the per-vertex file, in a "mixed" entry of its bake parameters (Header::parameters_json):
//   "mixed": {"role": "texel" | "vertex", "partner": "<file name, same folder>",
//             "vertex_triangles": [[first, count], ...], "texel_parts": [...], "vertex_parts": [...]}
// `vertex_triangles` are runs of mesh triangle indices in increasing order, not overlapping; every
// other triangle is drawn from the texel file. This header writes and reads that entry (no mesh here).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "transfer/transfer_file.h"

namespace prt::transfer {

struct MixedParts {
  std::string role;     ///< "texel" (the lightmap of the pair) or "vertex"
  std::string partner;  ///< the other file's name (no folder: it lies beside this one)
  /// Runs [first, first + count) of triangles drawn from the per-vertex file, increasing, disjoint.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> vertex_runs;
  std::vector<std::string> texel_parts, vertex_parts;  ///< the parts' names, for messages
};

/// The runs of the triangles `per_vertex` marks (one entry per triangle, 1: per vertex).
std::vector<std::pair<std::uint64_t, std::uint64_t>> vertex_runs_of(const std::vector<std::uint8_t>& per_vertex);

/// Per triangle (triangle_count of them): 1 if `parts` draws it from the per-vertex file. Throws
/// prt::Error("<path>: ...") if a run reaches past triangle_count.
std::vector<std::uint8_t> vertex_triangle_mask(const MixedParts& parts, std::uint64_t triangle_count, const std::string& path);

/// `parameters_json` (a JSON object's text) with the "mixed" entry of `parts` added.
std::string with_mixed_entry(const std::string& parameters_json, const MixedParts& parts);

/// The "mixed" entry of `header`'s bake parameters; nullopt when it has none (a file of one kind).
/// Throws prt::Error("<path>: ...") for a malformed entry (role, partner a plain file name, runs).
std::optional<MixedParts> read_mixed_entry(const Header& header, const std::string& path);

/// The partner's path: `parts.partner` in the folder of `path`.
std::string partner_path(const std::string& path, const MixedParts& parts);

}  // namespace prt::transfer
