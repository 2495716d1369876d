#pragma once
// Relighting with glossy transfer on the CPU: the reference for what the glossy shaders compute.
//
// For vertex p with transfer matrices M_p,c (bands_out^2 x bands^2; 1 or 3 channels), the BRDF matrix
// B_c (bands_out bands; brdf/projection.h), world lighting L_c and a view direction v (world, from the
// vertex toward the viewer):
//   T = M_p,c L_c  (transferred incident radiance, local frame F_p = brdf::shading_frame(n_p))
//   O = B_c T      (outgoing radiance coefficients, local frame)
//   L_o,c(p, v) = sum_k O_k Y_k(F_p^T v)
// with c' = c for 3-channel transfer or BRDF matrices and 0 for 1-channel ones. A view direction below
// the tangent plane gets the value of its mirror image in that plane (the BRDF's mirror extension,
// brdf/brdf.h), so shading stays continuous across silhouettes. Lighting with more bands than the
// transfer is truncated; with fewer, the missing coefficients count as zero. Accumulates in double.
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "brdf/vertex_brdfs.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::shade {

/// Outgoing radiance coefficients O_p (bands_out^2 RGB triples per vertex, vertex-major, local frame):
/// what a renderer evaluates at the view direction. Throws prt::Error unless the transfer is glossy and
/// the BRDF matrix has its bands_out bands.
std::vector<glm::vec3> glossy_outgoing_coefficients(const transfer::TransferData& transfer, const brdf::BrdfMatrix& brdf_matrix,
                                                    const sh::RgbCoefficients& lighting);

/// As above with each vertex's own BRDF: vertex v takes matrices[vertex[v]] (`vertex` empty: every
/// vertex matrices[0]; brdf::VertexBrdfs's layout). Throws prt::Error also for an index out of range.
std::vector<glm::vec3> glossy_outgoing_coefficients(const transfer::TransferData& transfer, const std::vector<brdf::BrdfMatrix>& matrices,
                                                    const std::vector<std::uint32_t>& vertex, const sh::RgbCoefficients& lighting);

/// Per-vertex outgoing radiance (linear RGB, the lighting's units) toward per-vertex view directions
/// `view` (unit, world frame). `normals` are the mesh's (they define the local frames). Throws
/// prt::Error as glossy_outgoing_coefficients, or if the sizes differ from the vertex count.
std::vector<glm::vec3> shade_glossy(const transfer::TransferData& transfer, const brdf::BrdfMatrix& brdf_matrix,
                                    const sh::RgbCoefficients& lighting, const std::vector<glm::vec3>& normals,
                                    const std::vector<glm::vec3>& view);

/// As shade_glossy, toward the eye point `eye`: view = normalize(eye - position) per vertex (a vertex
/// exactly at the eye gets its normal as view direction).
std::vector<glm::vec3> shade_glossy_eye(const transfer::TransferData& transfer, const brdf::BrdfMatrix& brdf_matrix,
                                        const sh::RgbCoefficients& lighting, const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals, const glm::vec3& eye);

/// The BRDFs a glossy transfer was baked with, from its parameters JSON (brdf/vertex_brdfs.h: one
/// "brdf", or a "brdfs" table with each vertex's index). Throws prt::Error("<what>: ...") naming `what`
/// (e.g. the file) if the header has none or they are malformed.
brdf::VertexBrdfs baked_brdfs(const transfer::Header& header, const std::string& what);

}  // namespace prt::shade
