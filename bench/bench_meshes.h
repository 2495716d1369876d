#pragma once
// Procedural meshes for benchmarks and tests, and the "bare Embree" baseline passes the baker is
// measured against. Everything here is deterministic: the same arguments give bit-identical meshes and
// results on every run and thread count.
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "mesh/mesh.h"
#include "sh/coefficients.h"
#include "trace/scene.h"

namespace prt::bench {

/// Icosahedron subdivided `levels` times (each level splits every triangle into 4; 10*4^levels + 2
/// vertices, 20*4^levels triangles), vertices on the sphere |p - center| = radius, radial unit normals,
/// counter-clockwise seen from outside. levels in [0, 10].
mesh::Mesh icosphere(int levels, float radius = 1.0f, const glm::vec3& center = glm::vec3(0.0f));

/// The icosphere of `levels` with each vertex moved radially to radius 1 + amplitude * bump(d), where
/// bump is a fixed sum of 12 ridged waves |sin(k_i . d + phase_i)| - 0.5 (frequencies 3..24 per unit,
/// weights ~ 1/frequency, in [-0.5, 0.5] in total): valleys with sharp concave creases and deep pits,
/// strongly self-shadowing for amplitude ~0.3. Normals area-weighted. Star-shaped (needs amplitude < 1),
/// so triangles keep their outward orientation.
mesh::Mesh bumpy_icosphere(int levels, float amplitude);

/// Lighting of `bands` bands: Gaussian coefficients (sigma 0.3 per channel, std::mt19937_64 seed 5) plus
/// 3 on every channel of the constant term, so the radiance it gives stays positive.
sh::RgbCoefficients random_lighting(int bands);
/// A latitude-longitude unit sphere of rings x segments vertices plus the two poles, radial normals
/// (lat_long_sphere(200, 250): the 50,002-vertex sphere of the frame-time benchmarks).
mesh::Mesh lat_long_sphere(int rings, int segments);
/// The benchmark mesh: bumpy_icosphere(8, 0.35): 655,362 vertices, 1,310,720 triangles, about 1.5
/// units across.
mesh::Mesh detailed_blob();

/// Closed axis-aligned box [lo, hi], each face a cells x cells grid of quads (2 triangles each),
/// outward normals. Each face has its own vertices (hard edges; 6 (cells+1)^2 vertices).
mesh::Mesh box(const glm::vec3& lo, const glm::vec3& hi, int cells);

/// Open box (a cup): the five faces of [lo, hi] other than the +Y face, cells x cells quads each,
/// normals pointing into the cup. Vertices on the cup's inner edges are shared by the faces meeting
/// there and carry the normalised mean of those faces' normals (smooth-shaded concave creases).
mesh::Mesh open_box(const glm::vec3& lo, const glm::vec3& hi, int cells);

/// Cornell-like box: the room [0,1]^3 without its +Z wall (an open box rotated so its opening faces
/// +Z, inward normals, shared crease vertices) and two closed blocks standing on the floor y = 0: a tall
/// one (0.3 x 0.6 x 0.3) and a short one (0.3 x 0.3 x 0.3), each rotated about Y. Walls cells x cells.
mesh::Mesh cornell_box(int cells);

/// Appends b's vertices and triangles to a (indices of b shifted; albedo dropped unless both have it).
void append(mesh::Mesh& a, const mesh::Mesh& b);

/// Area-weighted unit vertex normals (+Y for vertices of no triangle), accumulated in double.
std::vector<glm::vec3> vertex_normals(const std::vector<glm::vec3>& positions,
                                      const std::vector<std::uint32_t>& indices);

/// `count` directions on the hemisphere about +Z, uniform in solid angle: a spherical Fibonacci set
/// (z_i = 1 - (i + 0.5) / count, azimuth i * golden angle). Fixed, well spread.
std::vector<glm::vec3> hemisphere_directions(std::size_t count);

/// An orthonormal frame (t, b, n) for unit n (Duff et al. 2017, "Building an orthonormal basis,
/// revisited"); local (x, y, z) maps to x t + y b + z n.
void orthonormal_frame(const glm::vec3& n, glm::vec3& t, glm::vec3& b);

/// What a baseline pass did.
/// CPU seconds of the whole process so far (all threads; CLOCK_PROCESS_CPUTIME_ID).
double process_cpu_seconds();

struct PassResult {
  double seconds = 0.0;               ///< wall time of the pass (rays built and traced)
  double cpu_seconds = 0.0;           ///< CPU time of the whole process during the pass (all threads)
  std::size_t rays = 0;               ///< rays traced
  double mrays_per_second = 0.0;      ///< rays / seconds / 1e6
  double mrays_per_cpu_second = 0.0;  ///< rays / cpu_seconds / 1e6: per-core speed, robust to a busy machine
  std::vector<std::uint16_t> counts;  ///< per vertex (mesh order): unoccluded rays, or rays that hit
  std::uint64_t checksum = 0;         ///< sum over vertices of counts[v] * (v + 1), to compare runs
};

/// The frame in which a bare pass turns the local directions into vertex v's rays.
struct PassFrames {
  /// false: orthonormal_frame(n_v), the same for every vertex of a given normal. true: the bake's own,
  /// sh::vertex_frame(n_v, seed, v), turned about n_v by a hashed angle per vertex (bake/, trace/vertex_rays.h):
  /// the bake's rays exactly. On a mesh of large flat walls the two differ in cost: neighbouring vertices
  /// of a wall trace nearly the same rays in the first (Cornell box, 82k vertices: 1.10x faster).
  bool bake = false;
  std::uint32_t seed = 1;  ///< of sh::vertex_frame (BakeOptions::seed); used when bake is true
};

/// The bare Embree occlusion pass: for every vertex v in `order`, the rays from
/// scene.offset_origin(p_v, n_v) along `directions` (about +Z) rotated into v's frame (`frames`),
/// traced with Scene::occluded in batches of `batch_size` rays, vertices split over `threads` workers by
/// prt::parallel_for (chunks of 64 vertices). counts[v] = unoccluded rays. directions.size() <= 65535.
PassResult occlusion_pass(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<std::uint32_t>& order,
                          const std::vector<glm::vec3>& directions, int threads,
                          std::size_t batch_size = trace::kDefaultBatchCapacity, const PassFrames& frames = {});

/// The same rays through Scene::intersect (closest hit); counts[v] = rays that hit a triangle.
PassResult closest_hit_pass(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<std::uint32_t>& order,
                            const std::vector<glm::vec3>& directions, int threads,
                            std::size_t batch_size = trace::kDefaultBatchCapacity, const PassFrames& frames = {});

}  // namespace prt::bench
