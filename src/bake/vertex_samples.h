#pragma once
// The hemisphere sample set every vertex traces and per-vertex frames: internal to prt_bake, and
// turned_frame is also used by prt_probes' surface pass.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace prt::bake {

/// S hemisphere directions about +z (local frame) and the SH basis at each of them.
struct LocalSampleSet {
  int bands = 0;
  std::vector<glm::vec3> directions;  ///< S unit vectors, z >= 0
  std::vector<float> basis;           ///< S x bands^2, sample-major: basis[s * bands^2 + i] = Y_i(directions[s])
};

/// Builds the set for (samples, seed): sh::hemisphere_directions_cosine, basis in float.
LocalSampleSet make_local_sample_set(int samples, int bands, std::uint32_t seed);

/// S directions uniform on the hemisphere about +z (sh::hemisphere_directions_uniform) and the SH
/// basis of `bands` bands at each (the glossy passes, which weight by the BRDF rather than the cosine).
LocalSampleSet make_uniform_sample_set(int samples, int bands, std::uint32_t seed);

/// Rotation (columns t, b, n) taking local coordinates about +z to world ones about the unit normal n:
/// Duff et al. 2017's branchless basis turned about n by `angle` radians.
glm::mat3 turned_frame(const glm::vec3& normal, double angle);

/// Rotation (columns t, b, n) taking the local frame to the world frame at a vertex with unit normal n.
/// The tangent is Duff et al. 2017's branchless basis turned about n by an angle hashed from
/// (seed, vertex), so the sample pattern differs from vertex to vertex but not from run to run.
glm::mat3 vertex_frame(const glm::vec3& normal, std::uint32_t seed, std::uint64_t vertex);

}  // namespace prt::bake
