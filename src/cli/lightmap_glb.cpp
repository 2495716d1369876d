#include "cli/lightmap_glb.h"

#include "mesh/writers.h"
#include "transfer/lightmap_gltf.h"

namespace prt::cli {

void write_lightmap_glb(const std::string& path, const mesh::Mesh& mesh, const transfer::TransferData& transfer) {
  std::vector<mesh::GlbImage> images;
  for (std::string& bytes : transfer::lightmap_ktx2_textures(transfer)) images.push_back({std::move(bytes), "image/ktx2"});
  mesh::write_glb_textured(path, mesh, images, transfer::kLightmapExtension,
                           transfer::lightmap_extension_json(transfer.header, 0, 0));
}

}  // namespace prt::cli
