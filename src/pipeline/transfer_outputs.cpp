#include "pipeline/transfer_outputs.h"

#include <algorithm>
#include <memory>

#include "compress/cprt_file.h"
#include "compress/shaded_compression.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/engine_export.h"

namespace prt::pipeline {

compress::CompressedTransfer transfer_model(const transfer::TransferData& transfer, const TransferOutputs& o) {
  compress::CompressionRequest request;
  const std::size_t points = compress::point_blocks(transfer.header, transfer.coverage).size();
  const std::size_t dimension = std::size_t(transfer.header.values_per_vertex()) * (transfer.bounce_only.empty() ? 1 : 2);
  const int clusters = o.clusters > 0 ? o.clusters : int(std::min<std::size_t>(kExportClusters, points));
  const int pca = o.clusters > 0 ? o.pca : int(std::min<std::size_t>(kExportPca, dimension));
  request.options = {clusters, pca, o.rounds, o.seed, o.threads, o.fit_points};
  request.scalar = transfer.header.scalar;
  request.metric_sky = o.metric_sky;
  return compress::compress_for_shading(transfer, o.clusters > 0 ? o.transfer_path : o.gltf_path, request);
}

void write_transfer_outputs(const mesh::Mesh& mesh, transfer::TransferData transfer, const TransferOutputs& o) {
  if (transfer::is_glossy(transfer.header.kind) && !o.gltf_path.empty())
    fail_file(o.gltf_path, "glTF export of glossy transfer matrices is not supported; use the .prt file");
  if (o.float16) transfer.header.scalar = transfer::Scalar::float16;
  std::unique_ptr<compress::CompressedTransfer> model;
  if (o.clusters > 0 || !o.gltf_path.empty()) model = std::make_unique<compress::CompressedTransfer>(transfer_model(transfer, o));
  AtomicFile transfer_file(o.transfer_path);
  write_staged(transfer_file, [&](const std::string& path) {
    if (o.clusters == 0) return transfer::write_transfer(path, transfer);
    compress::write_cprt(path, *model);
  });
  std::unique_ptr<AtomicFile> gltf_file;
  if (!o.gltf_path.empty()) {
    gltf_file = std::make_unique<AtomicFile>(o.gltf_path);
    write_staged(*gltf_file, [&](const std::string& path) {
      write_engine_gltf(path, o.source_path, mesh, *model, o.uv_generated);
    });
  }
  transfer_file.commit();
  if (gltf_file) gltf_file->commit();
}

}  // namespace prt::pipeline
