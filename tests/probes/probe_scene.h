#pragma once
// The probe tests' scene, built in code: a floor, a closed box standing on it, a single-sided wall
// facing the box, per-vertex albedo, optional emission on the wall, and a smooth sky.
#include <vector>

#include <glm/vec3.hpp>

#include "light/environment.h"
#include "mesh/mesh.h"

namespace prt::test {

struct ProbeScene {
  mesh::Mesh mesh;                  ///< with albedo; normals per face (hard edges)
  std::vector<glm::vec3> emission;  ///< one per vertex: the wall's inner quarter glows when emissive
  std::vector<glm::dvec3> probes;   ///< test probe positions (index 0 is inside the box)
};

/// Floor [-2,2]^2 at y = 0 (normal +Y, 24x24 cells, albedo 0.7), box [-0.5,0.5] x [0.001,1] x
/// [-0.5,0.5] (outward normals, 6x6 cells per face, albedo (0.8,0.3,0.2)), wall x = 1.5, y in [0,1.5],
/// z in [-1.5,1.5] facing -X (12x12 cells, albedo 0.5). With `emissive`, wall vertices with |z| < 0.75
/// and y > 0.5 emit (2, 1.6, 1.2).
ProbeScene make_probe_scene(bool emissive);

/// A smooth sky, 256 x 128 equirect: a blue-white gradient above the horizon, dim brown below, and a
/// broad warm glow toward +X+Y (no sharp features: projections and lookups agree to ~1e-4).
light::Environment make_sky();

/// The same sky band-limited: its `bands`-band SH rendered back to an equirect map (so that the
/// transfer's band-limited view of the environment is exact).
light::Environment make_band_limited_sky(int bands);

}  // namespace prt::test
