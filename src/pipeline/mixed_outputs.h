#pragma once
// What `prt bake --lightmap SIZE --texel-parts ...` writes for a mixed scene (docs/formats.md "Mixed
// transfer pairs"): the texel transfer file at the output path and the per-vertex transfer file beside
// it, each with the "mixed" entry (transfer/mixed_parts.h) naming the other, committed together.
#include <string>
#include <vector>

#include "transfer/mixed_parts.h"
#include "transfer/transfer_file.h"

namespace prt::pipeline {

/// The per-vertex file's path for a mixed bake written to `texel_path`: "<stem>.vertices.prt" in the
/// same folder ("room.prt" -> "room.vertices.prt").
std::string mixed_vertex_path(const std::string& texel_path);

/// Adds the "mixed" entries (texel and vertex parts' names, the per-vertex triangles `vertex_triangle`)
/// to both files' parameters and writes them, each through its temporary, committing both only when
/// both are written (a failure leaves neither). `float16`: store both as IEEE float16. Throws
/// prt::Error naming the file.
void write_mixed_outputs(transfer::TransferData texels, transfer::TransferData vertices, const std::string& texel_path,
                         const std::string& vertex_path, const std::vector<std::uint8_t>& vertex_triangle,
                         const std::vector<std::string>& texel_parts, const std::vector<std::string>& vertex_parts, bool float16);

}  // namespace prt::pipeline
