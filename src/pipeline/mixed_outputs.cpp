#include "pipeline/mixed_outputs.h"

#include <filesystem>
#include <memory>

#include "core/atomic_file.h"
#include "pipeline/engine_export.h"
#include "pipeline/transfer_outputs.h"

namespace prt::pipeline {

std::string mixed_vertex_path(const std::string& texel_path) {
  const std::filesystem::path path(texel_path);
  return (path.parent_path() / (path.stem().string() + ".vertices.prt")).string();
}

void write_mixed_outputs(const mesh::Mesh& mesh, transfer::TransferData texels, transfer::TransferData vertices, const MixedOutputs& o) {
  if (o.float16) texels.header.scalar = vertices.header.scalar = transfer::Scalar::float16;
  std::unique_ptr<AtomicFile> gltf_file;
  if (!o.gltf_path.empty()) {  // the models before the "mixed" entries, which name the pair's files
    TransferOutputs model_outputs;
    model_outputs.gltf_path = o.gltf_path;
    model_outputs.seed = o.seed;
    model_outputs.threads = o.threads;
    const compress::CompressedTransfer texel_model = transfer_model(texels, model_outputs);
    const compress::CompressedTransfer vertex_model = transfer_model(vertices, model_outputs);
    gltf_file = std::make_unique<AtomicFile>(o.gltf_path);
    write_staged(*gltf_file, [&](const std::string& path) {
      write_mixed_engine_gltf(path, o.gltf_source, mesh, texel_model, vertex_model, o.vertex_triangle);
    });
  }
  transfer::MixedParts parts;
  parts.vertex_runs = transfer::vertex_runs_of(o.vertex_triangle);
  parts.texel_parts = o.texel_parts;
  parts.vertex_parts = o.vertex_parts;
  parts.role = "texel";
  parts.partner = std::filesystem::path(o.vertex_path).filename().string();
  texels.header.parameters_json = transfer::with_mixed_entry(texels.header.parameters_json, parts);
  parts.role = "vertex";
  parts.partner = std::filesystem::path(o.texel_path).filename().string();
  vertices.header.parameters_json = transfer::with_mixed_entry(vertices.header.parameters_json, parts);
  AtomicFile texel_file(o.texel_path), vertex_file(o.vertex_path);
  write_staged(texel_file, [&](const std::string& path) { transfer::write_transfer(path, texels); });
  write_staged(vertex_file, [&](const std::string& path) { transfer::write_transfer(path, vertices); });
  texel_file.commit();
  vertex_file.commit();
  if (gltf_file) gltf_file->commit();
}

}  // namespace prt::pipeline
