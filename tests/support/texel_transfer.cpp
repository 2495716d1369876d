#include "support/texel_transfer.h"

namespace prt::test {

transfer::TransferData empty_texel_transfer(const mesh::Mesh& mesh, int width, int height, int bands, int channels, bool bounce) {
  transfer::TransferData t;
  transfer::Header& h = t.header;
  h.kind = bounce ? transfer::Kind::interreflected : transfer::Kind::shadowed;
  h.bands = static_cast<std::uint32_t>(bands);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = mesh.vertex_count();
  h.triangle_count = mesh.triangle_count();
  h.mesh_fingerprint = mesh::fingerprint(mesh);
  h.texel_width = static_cast<std::uint32_t>(width);
  h.texel_height = static_cast<std::uint32_t>(height);
  h.uv_set = mesh.lightmap_uv_set;
  h.uv_fingerprint = mesh::uv_fingerprint(mesh);
  h.bounce_only_section = bounce;
  h.parameters_json = "{\"source\":\"tests/support/texel_transfer\"}";
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  t.values.assign(texels * h.values_per_vertex(), 0.0f);
  t.coverage.assign(texels, transfer::kTexelEmpty);
  if (bounce) t.bounce_only.assign(t.values.size(), 0.0f);
  return t;
}

}  // namespace prt::test
