#pragma once
// The local frame of a surface point for glossy PRT: the frame that glossy transfer matrices
// (transferred incident radiance) and BRDF matrices live in. The same formula runs in the baker
// (bake/), the CPU shader (shade/) and the GPU shaders, so the frames agree everywhere.
//
// DEFINITION. For a unit normal n (world frame, +Y up):
//   t = normalize(Y x n)   (Y = (0, 1, 0); t is horizontal, tangent to the circle of latitude about +Y)
//   b = n x t
// and the frame is the rotation F = [t | b | n] (columns), taking local coordinates to world ones:
// w_world = F w_local, w_local = F^T w_world. Local +z is the normal.
// When |Y x n| < 1e-6 (n within ~1e-6 rad of +Y or -Y), t = (1, 0, 0) made orthogonal to n instead.
//
// SMOOTHNESS AND ITS SINGULARITY. F varies smoothly with n everywhere except at n = +Y and n = -Y
// (a continuous tangent field on the sphere must vanish somewhere: the hairy-ball theorem). Near
// those poles the frames of neighbouring vertices differ by large rotations ABOUT n. The per-vertex
// result does not depend on that rotation (every prt BRDF is isotropic, so the outgoing radiance
// sum_k (B T)_k Y_k(F^T v) is the same for F and F Rz(angle)), but interpolating local-frame
// coefficients between two vertices near a pole mixes different frames: renderers evaluate each
// vertex's coefficients in its own frame, or accept that error in the pole regions.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace prt::brdf {

/// F = [t | b | n] for a unit normal n (see above). The result is orthonormal with det +1.
glm::dmat3 shading_frame(const glm::dvec3& normal);
glm::mat3 shading_frame(const glm::vec3& normal);

}  // namespace prt::brdf
