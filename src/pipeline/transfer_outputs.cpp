#include "pipeline/transfer_outputs.h"

#include <memory>

#include "bake/bake.h"
#include "compress/cprt_file.h"
#include "compress/shaded_compression.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/writers.h"
#include "transfer/lightmap_gltf.h"

namespace prt::pipeline {

void write_lightmap_glb(const std::string& path, const mesh::Mesh& mesh, const transfer::TransferData& transfer) {
  std::vector<mesh::GlbImage> images;
  for (std::string& bytes : transfer::lightmap_ktx2_textures(transfer)) images.push_back({std::move(bytes), "image/ktx2"});
  mesh::write_glb_textured(path, mesh, images, transfer::kLightmapExtension,
                           transfer::lightmap_extension_json(transfer.header, 0, 0));
}

void write_transfer_outputs(const mesh::Mesh& mesh, transfer::TransferData transfer, const TransferOutputs& o) {
  if (transfer::is_glossy(transfer.header.kind) && !o.gltf_path.empty())
    fail_file(o.gltf_path, "glTF export of glossy transfer matrices is not supported; use the .prt file");
  if (o.float16) transfer.header.scalar = transfer::Scalar::float16;
  AtomicFile transfer_file(o.transfer_path);
  write_staged(transfer_file, [&](const std::string& path) {
    if (o.clusters == 0) return transfer::write_transfer(path, transfer);
    compress::CompressionRequest request;
    request.options = {o.clusters, o.pca, 20, o.seed, o.threads};
    request.scalar = transfer.header.scalar;
    request.metric_sky = o.metric_sky;
    compress::write_cprt(path, compress::compress_for_shading(transfer, o.transfer_path, request));
  });
  std::unique_ptr<AtomicFile> gltf_file;
  if (!o.gltf_path.empty()) {
    gltf_file = std::make_unique<AtomicFile>(o.gltf_path);
    write_staged(*gltf_file, [&](const std::string& path) {
      if (transfer.header.is_texel()) return write_lightmap_glb(path, mesh, transfer);
      mesh::write_glb(path, mesh, bake::pack_transfer_attributes(transfer));
    });
  }
  transfer_file.commit();
  if (gltf_file) gltf_file->commit();
}

}  // namespace prt::pipeline
