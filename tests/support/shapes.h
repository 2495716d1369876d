#pragma once
// Meshes generated in code for tests: shapes whose geometry gives known answers.
// All are counter-clockwise seen from the side their normals point to.
#include <vector>

#include "mesh/mesh.h"

namespace prt::test {

/// Unit sphere (UV sphere, `rings` x `segments`, poles without degenerate triangles), outward normals.
mesh::Mesh uv_sphere(int rings, int segments);

/// Torus about +Y with major radius R and minor radius r, outward normals (closed, concave inside).
mesh::Mesh torus(float major_radius, float minor_radius, int major_segments, int minor_segments);

/// Open box: floor y = 0 and four walls up to y = height over [-1,1]^2 in x,z, normals pointing inward
/// (into the box), each face a grid of cells x cells quads. No lid: concave, open to the sky.
mesh::Mesh open_box(float height, int cells);

/// The inside of the lower unit hemisphere (a bowl open toward +Y), `rings` x `segments` vertices plus
/// the pole (last), normals toward the centre: smooth and concave. Ring 0 is the rim.
mesh::Mesh bowl(int rings, int segments);

/// A unit-grid floor y = 0 over x in [-half, half], z in [-2, 2] (normal +Y), with a small square lid
/// (side 2 lid_half, facing down, normal -Y) lid_height above the floor vertex (x, 0, 0) for each x in
/// lid_x (integers in (-half, half)): each lid darkens its vertex far more than the surface around it.
mesh::Mesh floor_with_lids(int half, const std::vector<double>& lid_x, double lid_half, double lid_height);

/// The convex hull of `points` (incremental, orientation tests in double; points within 1e-9 of the
/// extent of a face's plane count as on it): its vertices only, triangles counter-clockwise seen from
/// outside, smooth normals (the normalised sum of the adjacent faces' area-weighted normals).
mesh::Mesh convex_hull(const std::vector<glm::vec3>& points);

/// The largest angle in degrees between a vertex normal and the geometric normal of a triangle of it.
double max_normal_tilt(const mesh::Mesh& mesh);

/// The share of the cosine-weighted hemisphere about unit n that lies strictly above the plane with
/// unit normal ng, by midpoint quadrature over the unit disc the hemisphere projects to (uniform there),
/// 512 x 512 polar cells (error below 1e-4).
double lobe_share_above(const glm::dvec3& n, const glm::dvec3& ng);

/// The triangles of vertex v (indices into mesh.indices / 3), in mesh order.
std::vector<std::size_t> triangles_of(const mesh::Mesh& mesh, std::uint32_t v);

/// (p1 - p0) x (p2 - p0) of triangle t in double: the geometric normal, twice the area long.
glm::dvec3 face_cross(const mesh::Mesh& mesh, std::size_t t);

/// The mean of lobe_share_above(n_v, ng_t) over vertex v's triangles t weighted by the integral of v's
/// hat function over each (area / 3): what a white furnace reflects over v's footprint when directions
/// below each point's own triangle carry no light.
double footprint_lobe_share(const mesh::Mesh& mesh, std::uint32_t v);

/// Gives every triangle its own lightmap chart (Mesh::lightmap_uv): a right triangle in its cell of
/// the smallest square grid of cells that holds them, a tenth of a cell from the cell's edges.
void add_triangle_charts(mesh::Mesh& mesh);

/// A closed mesh seen from inside is not something the baker handles (single-sided); these shapes
/// are all meant to be seen from the side of their normals.

}  // namespace prt::test
