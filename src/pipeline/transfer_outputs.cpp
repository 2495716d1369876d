#include "pipeline/transfer_outputs.h"

#include <algorithm>
#include <memory>

#include "compress/cprt_file.h"
#include "compress/shaded_compression.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/writers.h"
#include "pipeline/engine_export.h"
#include "transfer/lightmap_gltf.h"

namespace prt::pipeline {

void write_lightmap_glb(const std::string& path, const mesh::Mesh& mesh, const transfer::TransferData& transfer) {
  std::vector<mesh::GlbImage> images;
  for (std::string& bytes : transfer::lightmap_ktx2_textures(transfer)) images.push_back({std::move(bytes), "image/ktx2"});
  mesh::write_glb_textured(path, mesh, images, transfer::kLightmapExtension,
                           transfer::lightmap_extension_json(transfer.header, 0, 0));
}

namespace {

// The CPCA model of `transfer` as the .cprt file and the engine glTF carry it: the bake's --compress
// K,N, else (glTF only) the export's defaults (engine_export.h).
compress::CompressedTransfer compressed_model(const transfer::TransferData& transfer, const TransferOutputs& o) {
  compress::CompressionRequest request;
  const std::size_t points = compress::point_blocks(transfer.header, transfer.coverage).size();
  const std::size_t dimension = std::size_t(transfer.header.values_per_vertex()) * (transfer.bounce_only.empty() ? 1 : 2);
  const int clusters = o.clusters > 0 ? o.clusters : int(std::min<std::size_t>(kExportClusters, points));
  const int pca = o.clusters > 0 ? o.pca : int(std::min<std::size_t>(kExportPca, dimension));
  request.options = {clusters, pca, 20, o.seed, o.threads};
  request.scalar = transfer.header.scalar;
  return compress::compress_for_shading(transfer, o.clusters > 0 ? o.transfer_path : o.gltf_path, request);
}

}  // namespace

void write_transfer_outputs(const mesh::Mesh& mesh, transfer::TransferData transfer, const TransferOutputs& o) {
  if (transfer::is_glossy(transfer.header.kind) && !o.gltf_path.empty())
    fail_file(o.gltf_path, "glTF export of glossy transfer matrices is not supported; use the .prt file");
  if (o.float16) transfer.header.scalar = transfer::Scalar::float16;
  const bool vertex_gltf = !o.gltf_path.empty() && !transfer.header.is_texel();
  std::unique_ptr<compress::CompressedTransfer> model;
  if (o.clusters > 0 || vertex_gltf) model = std::make_unique<compress::CompressedTransfer>(compressed_model(transfer, o));
  AtomicFile transfer_file(o.transfer_path);
  write_staged(transfer_file, [&](const std::string& path) {
    if (o.clusters == 0) return transfer::write_transfer(path, transfer);
    compress::write_cprt(path, *model);
  });
  std::unique_ptr<AtomicFile> gltf_file;
  if (!o.gltf_path.empty()) {
    gltf_file = std::make_unique<AtomicFile>(o.gltf_path);
    write_staged(*gltf_file, [&](const std::string& path) {
      if (transfer.header.is_texel()) return write_lightmap_glb(path, mesh, transfer);
      write_engine_gltf(path, o.source_path, mesh, *model);
    });
  }
  transfer_file.commit();
  if (gltf_file) gltf_file->commit();
}

}  // namespace prt::pipeline
