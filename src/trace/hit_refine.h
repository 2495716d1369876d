#pragma once
// Closest hits recomputed from the triangle, the same bits whatever Embree's code path.
//
// Embree reports a hit's distance, barycentrics and geometric normal from its own SIMD kernels, and those
// differ in the last bits between its code paths (it picks SSE4.2, AVX, AVX2 or AVX-512 at run time, and
// its reciprocals are approximations refined per ISA): an interreflected bake on the same machine changed
// bits with the device's ISA forced from AVX2 to SSE4.2. Which triangle is nearest is what Embree is for;
// where on it the ray lands is recomputed here in double and rounded once to float, so hit points do not
// depend on the code path (docs/conventions.md, "Bits across Embree's code paths", which says what still
// can: Embree's choice of triangle for a ray within rounding of an edge). The file is compiled without
// floating-point contraction (src/trace/CMakeLists.txt), so the build's -march does not change it either.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace prt::trace {

struct RayHit;

/// For each of the `count` records that hit (hit.geom_id != kNoHit): sets ray.tfar to the hit distance t
/// along the ray (in units of |dir|), hit.u and hit.v to the barycentrics of origin + t dir in the
/// triangle (indices[3 prim_id ..]; point = (1-u-v) p0 + u p1 + v p2), and hit.ng to (p1 - p0) x (p2 - p0),
/// all computed in double (Moller-Trumbore) and rounded once. u and v are clamped to the triangle (u, v >= 0,
/// u + v <= 1) and t to at least the ray's tnear: an exact computation can land a ray that Embree counted
/// on an edge a rounding error outside it. A record whose triangle is degenerate in double keeps Embree's
/// values. Preconditions: every hit's prim_id indexes `indices`, whose entries index `positions`.
void refine_hits(RayHit* records, std::size_t count, const std::vector<glm::vec3>& positions,
                 const std::vector<std::uint32_t>& indices);

}  // namespace prt::trace
