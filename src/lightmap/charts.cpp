#include "lightmap/charts.h"

#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace prt::lightmap {

namespace {

std::uint64_t uv_bits(const glm::vec2& uv) {
  std::uint32_t u = 0, v = 0;
  std::memcpy(&u, &uv.x, 4);
  std::memcpy(&v, &uv.y, 4);
  return (std::uint64_t(u) << 32) | v;
}

struct EdgeKey {
  std::uint64_t a, b;  // the two corners' UV bits, a <= b
  bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b; }
};
struct EdgeHash {
  std::size_t operator()(const EdgeKey& k) const { return std::size_t(k.a * 0x9E3779B97F4A7C15ull ^ (k.b + (k.b << 17))); }
};

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t t) {
  while (parent[t] != t) t = parent[t] = parent[parent[t]];
  return t;
}

}  // namespace

std::vector<std::uint32_t> triangle_charts(const mesh::Mesh& mesh) {
  const std::size_t triangles = mesh.triangle_count();
  std::vector<std::uint32_t> parent(triangles);
  std::iota(parent.begin(), parent.end(), 0u);
  std::unordered_map<EdgeKey, std::uint32_t, EdgeHash> first;
  first.reserve(triangles * 3);
  for (std::uint32_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = uv_bits(mesh.lightmap_uv[3 * t + k]), b = uv_bits(mesh.lightmap_uv[3 * t + (k + 1) % 3]);
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      const auto [it, inserted] = first.emplace(EdgeKey{a, b}, t);
      if (inserted) continue;
      // Union by the lower root, so that every root is its chart's lowest triangle.
      const std::uint32_t ra = find_root(parent, it->second), rb = find_root(parent, t);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  std::vector<std::uint32_t> chart(triangles), id_of_root(triangles, ~0u);
  std::uint32_t next = 0;
  for (std::uint32_t t = 0; t < triangles; ++t) {
    const std::uint32_t r = find_root(parent, t);
    if (id_of_root[r] == ~0u) id_of_root[r] = next++;
    chart[t] = id_of_root[r];
  }
  return chart;
}

std::vector<float> texel_world_sizes(const mesh::Mesh& mesh, int width, int height) {
  std::vector<float> size(mesh.triangle_count(), 0.0f);
  for (std::size_t t = 0; t < size.size(); ++t) {
    const glm::dvec3 p0(mesh.positions[mesh.indices[3 * t]]), p1(mesh.positions[mesh.indices[3 * t + 1]]),
        p2(mesh.positions[mesh.indices[3 * t + 2]]);
    const glm::dvec2 u0(mesh.lightmap_uv[3 * t]), u1(mesh.lightmap_uv[3 * t + 1]), u2(mesh.lightmap_uv[3 * t + 2]);
    const glm::dvec2 e1 = (u1 - u0) * glm::dvec2(width, height), e2 = (u2 - u0) * glm::dvec2(width, height);
    const double uv_area = 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
    const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    if (uv_area > 0.0) size[t] = float(std::sqrt(area / uv_area));
  }
  return size;
}

}  // namespace prt::lightmap
