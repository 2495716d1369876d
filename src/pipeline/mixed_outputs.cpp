#include "pipeline/mixed_outputs.h"

#include <filesystem>

#include "core/atomic_file.h"

namespace prt::pipeline {

std::string mixed_vertex_path(const std::string& texel_path) {
  const std::filesystem::path path(texel_path);
  return (path.parent_path() / (path.stem().string() + ".vertices.prt")).string();
}

void write_mixed_outputs(transfer::TransferData texels, transfer::TransferData vertices, const std::string& texel_path,
                         const std::string& vertex_path, const std::vector<std::uint8_t>& vertex_triangle,
                         const std::vector<std::string>& texel_parts, const std::vector<std::string>& vertex_parts, bool float16) {
  transfer::MixedParts parts;
  parts.vertex_runs = transfer::vertex_runs_of(vertex_triangle);
  parts.texel_parts = texel_parts;
  parts.vertex_parts = vertex_parts;
  parts.role = "texel";
  parts.partner = std::filesystem::path(vertex_path).filename().string();
  texels.header.parameters_json = transfer::with_mixed_entry(texels.header.parameters_json, parts);
  parts.role = "vertex";
  parts.partner = std::filesystem::path(texel_path).filename().string();
  vertices.header.parameters_json = transfer::with_mixed_entry(vertices.header.parameters_json, parts);
  if (float16) texels.header.scalar = vertices.header.scalar = transfer::Scalar::float16;
  AtomicFile texel_file(texel_path), vertex_file(vertex_path);
  write_staged(texel_file, [&](const std::string& path) { transfer::write_transfer(path, texels); });
  write_staged(vertex_file, [&](const std::string& path) { transfer::write_transfer(path, vertices); });
  texel_file.commit();
  vertex_file.commit();
}

}  // namespace prt::pipeline
