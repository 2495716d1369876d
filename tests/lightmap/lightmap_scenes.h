#pragma once
// Meshes with lightmap UVs, generated in code for the lightmap tests, and writers for them.
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "image/image.h"
#include "mesh/mesh.h"

namespace prt::test {

/// Builds meshes quad by quad: each quad gets its own 4 vertices (unwelded) and 2 triangles
/// (0,1,2), (0,2,3), with the given per-corner UVs (prt's v-down convention) and one flat normal.
struct QuadBuilder {
  mesh::Mesh mesh;
  /// Corners counter-clockwise seen from `normal`; uv[k] for corner k.
  void quad(const glm::vec3 (&corners)[4], const glm::vec3& normal, const glm::vec2 (&uv)[4]);
  /// An axis-aligned chart: corner k at uv0 + size * (0,0), (1,0), (1,1), (0,1).
  void quad(const glm::vec3 (&corners)[4], const glm::vec3& normal, const glm::vec2& uv0, const glm::vec2& size);
};

/// A 2 x 2 floor (y = 0, x, z in [-1, 1], two triangles, chart [0.01, 0.59]^2) and, if `with_box`,
/// a closed box [-a, a] x [bottom, bottom + height] x [-a, a] (a = 0.3, height 0.6) whose six faces
/// are charts in the rest of the UV square. bottom < 0: the box intersects the floor; 0: it rests on it.
mesh::Mesh floor_and_box(bool with_box, float bottom = 0.0f);

/// An unwelded unit cube [-0.5, 0.5]^3 lifted to y in [0.1, 1.1] above the floor of floor_and_box
/// (without its box): each cube face is split along its diagonal into two triangles that are
/// separate UV charts (so every face has a UV seam across a flat surface).
mesh::Mesh split_cube_on_floor();

/// Writes `mesh` as OBJ: v, vn per vertex; vt per triangle corner (v written as 1 - v, OBJ's v-up);
/// f v/vt/vn.
void write_obj_with_uv(const std::string& path, const mesh::Mesh& mesh);

/// A smooth synthetic sky (equirect, 128 x 64): a blue gradient above, brown below, a broad warm lobe.
void write_test_sky(const std::string& path);

/// The coverage mask of a lightmap file, its size and lit image helpers.
double bilinear(const image::Image& image, const glm::vec2& uv, int channel);

}  // namespace prt::test
