#include "support/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

namespace prt::test {

mesh::Mesh uv_sphere(int rings, int segments) {
  mesh::Mesh m;
  m.positions.push_back({0, 1, 0});
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      m.positions.push_back(glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back({0, -1, 0});
  const auto ring = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  const std::uint32_t bottom = static_cast<std::uint32_t>(m.positions.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.indices.insert(m.indices.end(), {0u, ring(1, j + 1), ring(1, j)});
    m.indices.insert(m.indices.end(), {bottom, ring(rings - 1, j), ring(rings - 1, j + 1)});
  }
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < segments; ++j) {
      m.indices.insert(m.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j)});
      m.indices.insert(m.indices.end(), {ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)});
    }
  for (const glm::vec3& p : m.positions) m.normals.push_back(glm::normalize(p));
  return m;
}

mesh::Mesh torus(float major_radius, float minor_radius, int major_segments, int minor_segments) {
  mesh::Mesh m;
  for (int i = 0; i < major_segments; ++i) {
    const double u = 2 * M_PI * i / major_segments;
    const glm::dvec3 centre(major_radius * std::cos(u), 0, major_radius * std::sin(u));
    const glm::dvec3 radial(std::cos(u), 0, std::sin(u));
    for (int j = 0; j < minor_segments; ++j) {
      const double v = 2 * M_PI * j / minor_segments;
      const glm::dvec3 n = radial * std::cos(v) + glm::dvec3(0, 1, 0) * std::sin(v);
      m.positions.push_back(glm::vec3(centre + n * static_cast<double>(minor_radius)));
      m.normals.push_back(glm::vec3(n));
    }
  }
  const auto at = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % major_segments) * minor_segments + (j % minor_segments));
  };
  for (int i = 0; i < major_segments; ++i)
    for (int j = 0; j < minor_segments; ++j) {
      // Orientation: (d/dv) x (d/du) points along +n for this parametrisation.
      m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)});
      m.indices.insert(m.indices.end(), {at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  return m;
}

namespace {
// Appends a grid quad face: corner origin, edge vectors a and b (cells x cells), normal = a x b.
void add_face(mesh::Mesh& m, const glm::vec3& origin, const glm::vec3& a, const glm::vec3& b, int cells) {
  const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size());
  const glm::vec3 n = glm::normalize(glm::cross(a, b));
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) {
      m.positions.push_back(origin + a * (static_cast<float>(i) / cells) + b * (static_cast<float>(j) / cells));
      m.normals.push_back(n);
    }
  const auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(i * (cells + 1) + j); };
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}
}  // namespace

mesh::Mesh open_box(float height, int cells) {
  mesh::Mesh m;
  const float h = height;
  add_face(m, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, cells);   // floor, normal +Y
  add_face(m, {-1, 0, -1}, {2, 0, 0}, {0, h, 0}, cells);   // wall z = -1, normal +Z
  add_face(m, {1, 0, 1}, {-2, 0, 0}, {0, h, 0}, cells);    // wall z = +1, normal -Z
  add_face(m, {-1, 0, 1}, {0, 0, -2}, {0, h, 0}, cells);   // wall x = -1, normal +X
  add_face(m, {1, 0, -1}, {0, 0, 2}, {0, h, 0}, cells);    // wall x = +1, normal -X
  return m;
}

mesh::Mesh bowl(int rings, int segments) {
  mesh::Mesh m;
  for (int i = 0; i < rings; ++i) {
    const double theta = M_PI / 2 + (M_PI / 2) * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      m.positions.push_back(glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back(glm::vec3(0, -1, 0));
  for (const glm::vec3& p : m.positions) m.normals.push_back(-glm::normalize(p));
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * segments + (j % segments)); };
  const std::uint32_t pole = static_cast<std::uint32_t>(m.positions.size() - 1);
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      m.indices.insert(m.indices.end(), {at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.indices.insert(m.indices.end(), {at(rings - 1, j), pole, at(rings - 1, j + 1)});
  return m;
}

mesh::Mesh floor_with_lids(int half, const std::vector<double>& lid_x, double lid_half, double lid_height) {
  mesh::Mesh m;
  for (int r = -2; r <= 2; ++r)
    for (int i = -half; i <= half; ++i) {
      m.positions.emplace_back(i, 0, r);
      m.normals.emplace_back(0, 1, 0);
    }
  const int columns = 2 * half + 1;
  auto at = [columns, half](int i, int r) { return std::uint32_t((r + 2) * columns + i + half); };
  for (int r = -2; r < 2; ++r)
    for (int i = -half; i < half; ++i)
      m.indices.insert(m.indices.end(), {at(i, r), at(i, r + 1), at(i + 1, r + 1), at(i, r), at(i + 1, r + 1), at(i + 1, r)});
  for (double x : lid_x) {
    const auto first = std::uint32_t(m.positions.size());
    for (int k = 0; k < 4; ++k) {
      const double dx = (k == 1 || k == 2) ? lid_half : -lid_half, dz = k >= 2 ? lid_half : -lid_half;
      m.positions.emplace_back(x + dx, lid_height, dz);
      m.normals.emplace_back(0, -1, 0);
    }
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
  }
  return m;
}

namespace {

using Face = std::array<std::uint32_t, 3>;

glm::dvec3 face_normal(const std::vector<glm::dvec3>& p, const Face& f) {
  return glm::cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
}

// Four points of `p` spanning a tetrahedron (indices), the first counter-clockwise from outside.
std::array<std::uint32_t, 4> hull_seed(const std::vector<glm::dvec3>& p, double eps) {
  std::uint32_t a = 0, b = 0, c = 0, d = 0;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (p[i].x < p[a].x) a = i;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (glm::length(p[i] - p[a]) > glm::length(p[b] - p[a])) b = i;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (glm::length(glm::cross(p[i] - p[a], p[b] - p[a])) > glm::length(glm::cross(p[c] - p[a], p[b] - p[a]))) c = i;
  const glm::dvec3 n = glm::cross(p[b] - p[a], p[c] - p[a]);
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (std::abs(glm::dot(p[i] - p[a], n)) > std::abs(glm::dot(p[d] - p[a], n))) d = i;
  if (std::abs(glm::dot(p[d] - p[a], n)) <= eps * glm::length(n)) throw std::runtime_error("convex_hull: flat point set");
  if (glm::dot(p[d] - p[a], n) > 0.0) std::swap(b, c);  // d must lie behind face (a, b, c)
  return {a, b, c, d};
}

}  // namespace

mesh::Mesh convex_hull(const std::vector<glm::vec3>& points) {
  std::vector<glm::dvec3> p(points.begin(), points.end());
  double extent = 0.0;
  for (const glm::dvec3& q : p) extent = std::max({extent, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  const double eps = 1e-9 * extent;
  const auto s = hull_seed(p, eps);
  std::vector<Face> faces = {{s[0], s[1], s[2]}, {s[0], s[3], s[1]}, {s[1], s[3], s[2]}, {s[2], s[3], s[0]}};
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    std::vector<Face> kept;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;  // directed edges of visible faces
    for (const Face& f : faces) {
      const glm::dvec3 n = face_normal(p, f);
      if (glm::dot(p[i] - p[f[0]], n) > eps * glm::length(n)) {
        for (int k = 0; k < 3; ++k) edges[{f[k], f[(k + 1) % 3]}] = 1;
      } else {
        kept.push_back(f);
      }
    }
    if (edges.empty()) continue;  // inside (or on) the hull so far
    for (const auto& e : edges)   // the horizon: visible edges whose twin is not
      if (!edges.count({e.first.second, e.first.first})) kept.push_back({e.first.first, e.first.second, i});
    faces = std::move(kept);
  }
  mesh::Mesh m;
  std::map<std::uint32_t, std::uint32_t> index;
  for (const Face& f : faces)
    for (std::uint32_t v : f)
      if (index.emplace(v, static_cast<std::uint32_t>(m.positions.size())).second) m.positions.push_back(points[v]);
  std::vector<glm::dvec3> normal_sum(m.positions.size(), glm::dvec3(0.0));
  for (const Face& f : faces) {
    const glm::dvec3 n = face_normal(p, f);  // length 2 x area
    for (std::uint32_t v : f) {
      m.indices.push_back(index[v]);
      normal_sum[index[v]] += n;
    }
  }
  for (const glm::dvec3& n : normal_sum) m.normals.push_back(glm::vec3(glm::normalize(n)));
  return m;
}

double max_normal_tilt(const mesh::Mesh& mesh) {
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t* tri = mesh.indices.data() + 3 * t;
    const glm::dvec3 ng = glm::normalize(face_cross(mesh, t));
    for (int k = 0; k < 3; ++k) {
      const double c = std::clamp(glm::dot(ng, glm::normalize(glm::dvec3(mesh.normals[tri[k]]))), -1.0, 1.0);
      worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
    }
  }
  return worst;
}

double lobe_share_above(const glm::dvec3& n, const glm::dvec3& ng) {
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), b = glm::cross(n, t);
  constexpr int kCells = 512;
  double above = 0.0;
  for (int i = 0; i < kCells; ++i) {
    const double r = (i + 0.5) / kCells;
    for (int j = 0; j < kCells; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / kCells;
      const glm::dvec3 w = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1.0 - r * r) * n;
      if (glm::dot(w, ng) > 0.0) above += r;  // the cell's area is proportional to r
    }
  }
  return above / (kCells * kCells * 0.5);  // sum of r over all cells: kCells^2 / 2
}

std::vector<std::size_t> triangles_of(const mesh::Mesh& mesh, std::uint32_t v) {
  std::vector<std::size_t> out;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    if (mesh.indices[3 * t] == v || mesh.indices[3 * t + 1] == v || mesh.indices[3 * t + 2] == v) out.push_back(t);
  return out;
}

glm::dvec3 face_cross(const mesh::Mesh& mesh, std::size_t t) {
  const std::uint32_t* tri = mesh.indices.data() + 3 * t;
  const glm::dvec3 p0(mesh.positions[tri[0]]);
  return glm::cross(glm::dvec3(mesh.positions[tri[1]]) - p0, glm::dvec3(mesh.positions[tri[2]]) - p0);
}

double footprint_lobe_share(const mesh::Mesh& mesh, std::uint32_t v) {
  double weighted = 0.0, total = 0.0;
  for (std::size_t t : triangles_of(mesh, v)) {
    const glm::dvec3 c = face_cross(mesh, t);
    const double area = 0.5 * glm::length(c);
    weighted += area * lobe_share_above(glm::normalize(glm::dvec3(mesh.normals[v])), glm::normalize(c));
    total += area;
  }
  return weighted / total;
}

void add_triangle_charts(mesh::Mesh& mesh) {
  const std::size_t triangles = mesh.triangle_count();
  const int grid = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(triangles))));
  const float cell = 1.0f / static_cast<float>(grid), margin = 0.1f * cell;
  mesh.lightmap_uv.clear();
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::vec2 origin(static_cast<float>(t % grid) * cell, static_cast<float>(t / grid) * cell);
    const float side = cell - 2.0f * margin;
    mesh.lightmap_uv.push_back(origin + glm::vec2(margin, margin));
    mesh.lightmap_uv.push_back(origin + glm::vec2(margin + side, margin));
    mesh.lightmap_uv.push_back(origin + glm::vec2(margin, margin + side));
  }
}

}  // namespace prt::test
