// The draw vertices of a textured mesh (textured_corners.h).
#include "render/textured_corners.h"

#include <cstring>
#include <unordered_map>

namespace prt::render {

namespace {

// What a textured corner's vertex-stage run reads: its vertex, its UV's bits and its material.
struct CornerKey {
  std::uint32_t vertex, u, v, material;
  bool operator==(const CornerKey& o) const { return vertex == o.vertex && u == o.u && v == o.v && material == o.material; }
};

struct CornerKeyHash {
  std::size_t operator()(const CornerKey& k) const {
    std::uint64_t h = k.vertex;
    for (std::uint32_t word : {k.u, k.v, k.material}) h = (h ^ word) * 0x9e3779b97f4a7c15ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

std::uint32_t bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

}  // namespace

TexturedCorners textured_corners(const mesh::Mesh& mesh) {
  TexturedCorners out;
  const std::size_t corners = mesh.indices.size();
  out.draw_vertex.resize(corners);
  std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> seen;
  seen.reserve(mesh.vertex_count() + mesh.vertex_count() / 4);
  for (std::size_t c = 0; c < corners; ++c) {
    const CornerKey key{mesh.indices[c], bits(mesh.base_color_uv[c].x), bits(mesh.base_color_uv[c].y),
                        mesh.triangle_material[c / 3]};
    const auto [it, inserted] = seen.try_emplace(key, static_cast<std::uint32_t>(out.first_corner.size()));
    if (inserted) out.first_corner.push_back(static_cast<std::uint32_t>(c));
    out.draw_vertex[c] = it->second;
  }
  return out;
}

}  // namespace prt::render
