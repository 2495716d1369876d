#include "unwrap/lscm.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Sparse>
#include <glm/geometric.hpp>

namespace prt::unwrap {

namespace {

glm::dvec3 corner_position(const mesh::Mesh& mesh, std::uint32_t t, int k) {
  return glm::dvec3(mesh.positions[mesh.indices[3 * std::size_t(t) + std::size_t(k)]]);
}

// Area-weighted mean normal of the chart and two unit axes spanning its plane.
void chart_frame(const mesh::Mesh& mesh, const std::vector<std::uint32_t>& triangles, glm::dvec3& x, glm::dvec3& y) {
  glm::dvec3 n(0.0);
  for (std::uint32_t t : triangles)
    n += glm::cross(corner_position(mesh, t, 1) - corner_position(mesh, t, 0), corner_position(mesh, t, 2) - corner_position(mesh, t, 0));
  n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  x = glm::normalize(glm::cross(helper, n));
  y = glm::cross(n, x);
}

double signed_twice_area(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Local ids of the chart's welded vertices, in order of first use by its corners.
struct LocalVertices {
  std::vector<std::uint32_t> of_corner;  // per chart corner (3i + k)
  std::vector<glm::dvec3> position;      // per local vertex
};

LocalVertices local_vertices(const mesh::Mesh& mesh, const Surface& surface, const std::vector<std::uint32_t>& triangles) {
  LocalVertices out;
  std::unordered_map<std::uint32_t, std::uint32_t> id;
  id.reserve(triangles.size() * 2);
  for (std::uint32_t t : triangles)
    for (int k = 0; k < 3; ++k) {
      const auto found = id.emplace(surface.welded[3 * std::size_t(t) + std::size_t(k)], std::uint32_t(out.position.size()));
      if (found.second) out.position.push_back(corner_position(mesh, t, k));
      out.of_corner.push_back(found.first->second);
    }
  return out;
}

}  // namespace

bool lscm_chart(const mesh::Mesh& mesh, const Surface& surface, FlatChart& chart) {
  const LocalVertices local = local_vertices(mesh, surface, chart.triangles);
  const std::size_t vertices = local.position.size();
  glm::dvec3 ax, ay;
  chart_frame(mesh, chart.triangles, ax, ay);
  // Pins: the extremes along the longer side of the projected bounding box (lowest id on ties).
  std::vector<glm::dvec2> projected(vertices);
  glm::dvec2 lo(1e300), hi(-1e300);
  for (std::size_t v = 0; v < vertices; ++v) {
    projected[v] = {glm::dot(local.position[v], ax), glm::dot(local.position[v], ay)};
    lo = glm::min(lo, projected[v]);
    hi = glm::max(hi, projected[v]);
  }
  const int axis = hi.x - lo.x >= hi.y - lo.y ? 0 : 1;
  std::size_t pin0 = 0, pin1 = 0;
  for (std::size_t v = 1; v < vertices; ++v) {
    if (projected[v][axis] < projected[pin0][axis]) pin0 = v;
    if (projected[v][axis] > projected[pin1][axis]) pin1 = v;
  }
  if (pin0 == pin1) return false;
  // Unknowns: (u, v) of every vertex but the pins.
  std::vector<std::ptrdiff_t> column(vertices);
  std::ptrdiff_t free_count = 0;
  for (std::size_t v = 0; v < vertices; ++v) column[v] = (v == pin0 || v == pin1) ? -1 : free_count++;
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> entries;
  entries.reserve(chart.triangles.size() * 12);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(std::ptrdiff_t(2 * chart.triangles.size()));
  for (std::size_t i = 0; i < chart.triangles.size(); ++i) {
    const glm::dvec3 p0 = local.position[local.of_corner[3 * i]], p1 = local.position[local.of_corner[3 * i + 1]],
                     p2 = local.position[local.of_corner[3 * i + 2]];
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, n = glm::cross(e1, e2);
    const double twice_area = glm::length(n), l1 = glm::length(e1);
    if (!(twice_area > 0.0) || !(l1 > 0.0)) continue;  // no shape to keep
    const glm::dvec3 x = e1 / l1, y = glm::cross(n / twice_area, x);
    const glm::dvec2 q[3] = {{0.0, 0.0}, {l1, 0.0}, {glm::dot(e2, x), glm::dot(e2, y)}};
    const double weight = 1.0 / std::sqrt(twice_area);
    const std::ptrdiff_t row = std::ptrdiff_t(2 * i);
    for (int j = 0; j < 3; ++j) {
      const glm::dvec2 w = (q[(j + 2) % 3] - q[(j + 1) % 3]) * weight;  // W_j = a + i b
      const std::size_t v = local.of_corner[3 * i + std::size_t(j)];
      // Real part: a u - b v; imaginary part: b u + a v.
      if (column[v] < 0) {
        const glm::dvec2 pin = projected[v];
        rhs[row] -= w.x * pin.x - w.y * pin.y;
        rhs[row + 1] -= w.y * pin.x + w.x * pin.y;
      } else {
        const std::ptrdiff_t c = 2 * column[v];
        entries.insert(entries.end(), {Triplet(row, c, w.x), Triplet(row, c + 1, -w.y), Triplet(row + 1, c, w.y), Triplet(row + 1, c + 1, w.x)});
      }
    }
  }
  Eigen::VectorXd solution = Eigen::VectorXd::Zero(2 * free_count);
  if (free_count > 0) {
    Eigen::SparseMatrix<double> a(std::ptrdiff_t(2 * chart.triangles.size()), 2 * free_count);
    a.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SparseMatrix<double> normal = a.transpose() * a;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) return false;
    solution = solver.solve(a.transpose() * rhs);
    if (solver.info() != Eigen::Success || !solution.allFinite()) return false;
  }
  chart.corner_uv.resize(3 * chart.triangles.size());
  for (std::size_t c = 0; c < chart.corner_uv.size(); ++c) {
    const std::size_t v = local.of_corner[c];
    chart.corner_uv[c] = column[v] < 0 ? projected[v] : glm::dvec2(solution[2 * column[v]], solution[2 * column[v] + 1]);
  }
  normalize_area(mesh, chart);
  return true;
}

void planar_chart(const mesh::Mesh& mesh, FlatChart& chart) {
  glm::dvec3 ax, ay;
  chart_frame(mesh, chart.triangles, ax, ay);
  chart.corner_uv.resize(3 * chart.triangles.size());
  for (std::size_t i = 0; i < chart.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p = corner_position(mesh, chart.triangles[i], k);
      chart.corner_uv[3 * i + std::size_t(k)] = {glm::dot(p, ax), glm::dot(p, ay)};
    }
  normalize_area(mesh, chart);
}

void normalize_area(const mesh::Mesh& mesh, FlatChart& chart) {
  double uv_area = 0.0, area = 0.0;
  for (std::size_t i = 0; i < chart.triangles.size(); ++i) {
    const std::uint32_t t = chart.triangles[i];
    uv_area += signed_twice_area(chart.corner_uv[3 * i], chart.corner_uv[3 * i + 1], chart.corner_uv[3 * i + 2]);
    area += glm::length(glm::cross(corner_position(mesh, t, 1) - corner_position(mesh, t, 0), corner_position(mesh, t, 2) - corner_position(mesh, t, 0)));
  }
  if (uv_area == 0.0 || !std::isfinite(uv_area)) return;
  const double mirror = uv_area < 0.0 ? -1.0 : 1.0, scale = std::sqrt(area / std::abs(uv_area));
  for (glm::dvec2& uv : chart.corner_uv) uv = glm::dvec2(mirror * uv.x, uv.y) * scale;
}

}  // namespace prt::unwrap
