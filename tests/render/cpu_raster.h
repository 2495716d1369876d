#pragma once
// The CPU side of the pixel-exact comparison: given the triangle the GPU found at each pixel, the
// perspective-correct interpolation of per-vertex values at the pixel centre, from the same
// model-view-projection matrix.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "image/image.h"
#include "mesh/mesh.h"

namespace prt::render_test {

/// For every pixel whose triangle id is not kNoTriangle: project the triangle's vertices with
/// `model_view_projection` (in double), take the pixel centre's NDC ((x + 0.5) / W * 2 - 1,
/// 1 - (y + 0.5) / H * 2), compute screen-space barycentrics l_i, correct them for perspective
/// (b_i = (l_i / w_i) / sum_j l_j / w_j) and interpolate `vertex_values`. Other pixels are 0.
image::Image interpolate_on_cpu(const mesh::Mesh& mesh, const std::vector<glm::vec3>& vertex_values,
                                const glm::mat4& model_view_projection, const std::vector<std::uint32_t>& triangle_ids,
                                int width, int height);

/// Largest per-channel relative error |gpu - cpu| / |cpu| over covered pixels (triangle id set), with
/// the denominator floored at `floor`; also counts covered pixels.
double max_relative_error(const image::Image& gpu, const image::Image& cpu, const std::vector<std::uint32_t>& triangle_ids,
                          double floor, std::size_t& covered);

}  // namespace prt::render_test
