#include "compress/open_transfer.h"

#include "compress/cprt_file.h"
#include "compress/gltf_transfer.h"

namespace prt::compress {

transfer::Header TransferFile::header() const {
  if (!compressed()) return std::get<transfer::TransferData>(contents).header;
  transfer::Header header = std::get<CompressedTransfer>(contents).source;
  header.scalar = transfer::Scalar::float32;
  return header;
}

TransferFile open_transfer(const std::string& path) {
  TransferFile file;
  file.path = path;
  if (is_cprt_file(path))
    file.contents = read_cprt(path);
  else if (is_glb_file(path))
    file.contents = read_gltf_transfer(path, &file.baked_albedo);
  else
    file.contents = transfer::read_transfer(path);
  return file;
}

void use_baked_albedo(const TransferFile& file, mesh::Mesh* mesh) {
  if (!file.baked_albedo.empty() && file.baked_albedo.size() == mesh->vertex_count()) mesh->albedo = file.baked_albedo;
}

transfer::TransferData expand(TransferFile file) {
  if (file.compressed()) return decompress(std::get<CompressedTransfer>(file.contents));
  return std::move(std::get<transfer::TransferData>(file.contents));
}

}  // namespace prt::compress
