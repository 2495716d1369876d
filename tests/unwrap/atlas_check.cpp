#include "unwrap/atlas_check.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

namespace prt::test {

namespace {

constexpr double kTouchEpsilon = 1e-7;

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Interiors of the triangle and the unit square at (i, j) overlap: no separating axis among x, y and
// the triangle's three edge normals, with a margin of kTouchEpsilon.
bool touches(const glm::dvec2 (&p)[3], int i, int j) {
  const glm::dvec2 square[4] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
  auto separated = [&](const glm::dvec2& axis) {
    double t0 = 1e300, t1 = -1e300, s0 = 1e300, s1 = -1e300;
    for (const glm::dvec2& q : p) t0 = std::min(t0, glm::dot(q, axis)), t1 = std::max(t1, glm::dot(q, axis));
    for (const glm::dvec2& q : square) s0 = std::min(s0, glm::dot(q, axis)), s1 = std::max(s1, glm::dot(q, axis));
    const double scale = std::max(glm::length(axis), 1e-300);
    return std::min(t1, s1) - std::max(t0, s0) <= kTouchEpsilon * scale;
  };
  if (separated({1.0, 0.0}) || separated({0.0, 1.0})) return false;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec2 e = p[(k + 1) % 3] - p[k];
    if (separated({-e.y, e.x})) return false;
  }
  return true;
}

bool strictly_inside(const glm::dvec2 (&p)[3], const glm::dvec2& c) {
  const double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
  if (area == 0.0) return false;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec2 a = p[(k + 1) % 3], b = p[(k + 2) % 3];
    const double w = ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / area;
    if (!(w > 1e-6)) return false;
  }
  return true;
}

}  // namespace

AtlasCheck check_atlas(const mesh::Mesh& mesh, int width, int height, int padding) {
  AtlasCheck out;
  const std::size_t triangles = mesh.triangle_count();
  UnionFind sets(mesh.vertex_count());
  for (std::size_t t = 0; t < triangles; ++t) {
    sets.join(mesh.indices[3 * t], mesh.indices[3 * t + 1]);
    sets.join(mesh.indices[3 * t], mesh.indices[3 * t + 2]);
  }
  std::vector<std::int64_t> owner(std::size_t(width) * std::size_t(height), -1);  // chart root, or -2: two charts
  std::vector<std::uint32_t> centre_count(owner.size(), 0);
  std::vector<double> world_per_texel(owner.size(), 0.0);  // world area / texel area of the last triangle there
  std::vector<std::uint8_t> is_root(mesh.vertex_count(), 0);
  for (std::size_t t = 0; t < triangles; ++t) {
    glm::dvec2 p[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 uv = mesh.lightmap_uv[3 * t + std::size_t(k)];
      for (int c = 0; c < 2; ++c) out.outside += !(uv[c] >= 0.0f && uv[c] <= 1.0f);
      p[k] = {double(uv.x) * width, double(uv.y) * height};
    }
    const std::uint32_t chart = sets.find(mesh.indices[3 * t]);
    is_root[chart] = 1;
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    const double uv_area = 0.5 * std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x));
    const int i0 = std::max(0, int(std::floor(std::min({p[0].x, p[1].x, p[2].x})))), i1 = std::min(width - 1, int(std::floor(std::max({p[0].x, p[1].x, p[2].x}))));
    const int j0 = std::max(0, int(std::floor(std::min({p[0].y, p[1].y, p[2].y})))), j1 = std::min(height - 1, int(std::floor(std::max({p[0].y, p[1].y, p[2].y}))));
    bool any = false;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        if (!touches(p, i, j)) continue;
        any = true;
        std::int64_t& o = owner[std::size_t(j) * std::size_t(width) + std::size_t(i)];
        o = (o == -1 || o == std::int64_t(chart)) ? std::int64_t(chart) : -2;
        if (strictly_inside(p, {i + 0.5, j + 0.5})) {
          ++centre_count[std::size_t(j) * std::size_t(width) + std::size_t(i)];
          if (uv_area > 0.0) world_per_texel[std::size_t(j) * std::size_t(width) + std::size_t(i)] = area / uv_area;
        }
      }
    out.triangles_without_texel += !any;
  }
  out.charts = std::size_t(std::count(is_root.begin(), is_root.end(), std::uint8_t(1)));
  std::vector<double> samples;
  for (std::size_t k = 0; k < owner.size(); ++k) {
    out.touched += owner[k] != -1;
    out.shared_texels += owner[k] == -2;
    out.double_centres += centre_count[k] > 1;
    if (world_per_texel[k] > 0.0) samples.push_back(world_per_texel[k]);
    if (owner[k] < 0) continue;
    const int i = int(k % std::size_t(width)), j = int(k / std::size_t(width)), r = 2 * padding;
    bool bad = false;
    for (int y = std::max(0, j - r); y <= std::min(height - 1, j + r) && !bad; ++y)
      for (int x = std::max(0, i - r); x <= std::min(width - 1, i + r) && !bad; ++x) {
        const std::int64_t o = owner[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        bad = o != -1 && o != owner[k];
      }
    out.padding_violations += bad;
  }
  if (!samples.empty()) {
    const double mean = std::accumulate(samples.begin(), samples.end(), 0.0) / double(samples.size());
    std::nth_element(samples.begin(), samples.begin() + std::ptrdiff_t(samples.size() * 95 / 100), samples.end());
    out.p95_over_mean = samples[samples.size() * 95 / 100] / mean;
  }
  return out;
}

}  // namespace prt::test
