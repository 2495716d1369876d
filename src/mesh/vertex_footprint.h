#pragma once
// The surface area that a vertex's value covers once it is interpolated across triangles: its one-ring,
// weighted by the vertex's hat function (1 at the vertex, falling linearly to 0 on the ring's outer
// edges; docs/conventions.md "Vertex footprint").
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/mesh.h"

namespace prt::mesh {

/// Where the rays (or paths) that estimate a vertex's value leave from: `area`, points of the vertex's
/// footprint below, so the value is the hat-weighted average over its one-ring that linear
/// interpolation stands for; `vertex`, the vertex itself (the value exactly there).
enum class Footprint { area, vertex };

/// "area" or "vertex".
const char* footprint_name(Footprint footprint);

/// Parses "area" or "vertex"; throws prt::Error("<option>: ...") otherwise.
Footprint parse_footprint(const std::string& text, const std::string& option);

/// How many footprint points the `samples` rays or paths of one vertex leave from: samples / 16 in
/// [1, kMaxFootprintPoints]. Point k takes the k-th of that many runs of consecutive samples (16 is an
/// aligned block of an Owen-scrambled Sobol set, itself spread over the whole hemisphere; 16 per point
/// gave less noise than 64, 4 or 1, docs/conventions.md "Vertex footprint").
inline constexpr int kSamplesPerFootprintPoint = 16;
inline constexpr int kMaxFootprintPoints = 1024;
/// VertexFootprints::point's triangle for a vertex on no triangle.
inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;
int footprint_point_count(int samples);

/// For every vertex, the triangles around it and their areas, to draw points of its footprint.
/// Vertices with bit-identical position and normal (one smooth vertex split for UVs or materials, as
/// glTF assets are along their UV seams) share the union of their triangles, so the copies on either
/// side of a seam stand for the same surface; a hard edge (normals differ) stays split. Read-only after
/// construction: one may serve every thread. Holds a reference to the mesh's positions and indices
/// (the mesh must outlive it).
class VertexFootprints {
 public:
  /// Lists each vertex's triangles (mesh.indices) with their areas. O(triangles) time and memory.
  explicit VertexFootprints(const Mesh& mesh);

  /// The point of vertex v's footprint at (u, w) in [0, 1)^2: over the whole one-ring the density is
  /// proportional to the hat function phi_v when (u, w) is uniform. u picks a triangle with probability
  /// proportional to its area (the hat's integral over it is area / 3) and, rescaled to [0, 1) within
  /// the triangle's share, gives v's barycentric weight b = beta22_quantile(.) ~ Beta(2, 2); w splits
  /// 1 - b between the other two corners. The map is continuous within each triangle, so stratified
  /// (u, w) give stratified points. A vertex on no triangle (or only zero-area ones) returns its own
  /// position. With `triangle` given, stores there the mesh triangle the point lies on (kNoTriangle
  /// for a vertex on no triangle). Precondition: v < vertex count.
  glm::vec3 point(std::uint32_t v, double u, double w, std::uint32_t* triangle = nullptr) const;

  /// Point k of a stratified set over v's footprint: point(v, sh::sobol_2d(k, scramble)) (the first K
  /// points of an Owen-scrambled Sobol sequence, K a power of two, are a (0, m, 2)-net).
  glm::vec3 stratified_point(std::uint32_t v, std::uint32_t k, std::uint32_t scramble, std::uint32_t* triangle = nullptr) const;

  /// The footprint's area: the sum of the areas of v's triangles (mesh units squared).
  double ring_area(std::uint32_t v) const;

  /// The triangle corners of v's footprint, each as 3 t + k (corner k of triangle t): the corners of v
  /// and of the vertices that share its position and normal, in triangle order. Empty for a vertex on
  /// no triangle.
  std::vector<std::uint32_t> footprint_corners(std::uint32_t v) const;

 private:
  const std::vector<glm::vec3>& positions_;
  std::vector<std::uint32_t> group_;        // the first vertex with v's position and normal
  std::vector<std::uint32_t> begin_;        // group g's corners are corners_[begin_[g] .. begin_[g + 1])
  std::vector<std::uint32_t> corners_;      // 3 t + k: corner k of triangle t, the corner in the group
  std::vector<double> cumulative_area_;     // per entry of corners_, the area of v's triangles up to it
  const std::vector<std::uint32_t>* indices_ = nullptr;  // the mesh's
};

/// The mesh's footprints when `footprint` is area; null for vertex (nothing to build).
std::unique_ptr<VertexFootprints> footprints_for(const Mesh& mesh, Footprint footprint);

/// The inverse of the Beta(2, 2) distribution function F(x) = 3 x^2 - 2 x^3 at u in [0, 1]:
/// 1/2 - sin(asin(1 - 2u) / 3). Beta(2, 2) is the law of the vertex's own barycentric weight of a point
/// drawn from a triangle with density proportional to that weight.
double beta22_quantile(double u);

}  // namespace prt::mesh
