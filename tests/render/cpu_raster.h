#pragma once
// The CPU side of the pixel-exact comparison: given the triangle the GPU found at each pixel, the
// perspective-correct interpolation of per-vertex values at the pixel centre, from the same
// model-view-projection matrix.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "image/image.h"
#include "mesh/mesh.h"

namespace prt::render_test {

/// A pixel's point on the triangle the GPU found there: its corners (vertex indices), perspective-
/// correct barycentrics and the point itself (mesh coordinates).
struct PixelPoint {
  std::uint32_t triangle = 0;
  std::uint32_t corner[3] = {0, 0, 0};
  double weight[3] = {0.0, 0.0, 0.0};
  glm::dvec3 position{0.0};
};
using PixelFunction = std::function<glm::dvec3(const PixelPoint&)>;

/// For every pixel whose triangle id is not kNoTriangle: project the triangle's vertices with
/// `model_view_projection` (in double), take the pixel centre's NDC ((x + 0.5) / W * 2 - 1,
/// 1 - (y + 0.5) / H * 2), compute screen-space barycentrics l_i, correct them for perspective
/// (b_i = (l_i / w_i) / sum_j l_j / w_j), and write value(point). Other pixels are 0.
image::Image per_pixel_on_cpu(const mesh::Mesh& mesh, const glm::mat4& model_view_projection,
                              const std::vector<std::uint32_t>& triangle_ids, int width, int height,
                              const PixelFunction& value);

/// per_pixel_on_cpu interpolating `vertex_values` with the barycentrics.
image::Image interpolate_on_cpu(const mesh::Mesh& mesh, const std::vector<glm::vec3>& vertex_values,
                                const glm::mat4& model_view_projection, const std::vector<std::uint32_t>& triangle_ids,
                                int width, int height);

/// Glossy PRT at a pixel: sum_i b_i sum_k O_i[k] Y_k(F_i^T view) in each corner's own frame F_i
/// (brdf::shading_frame of its normal); `outgoing` holds out_bands^2 coefficients per vertex.
glm::dvec3 glossy_prt_at(const mesh::Mesh& mesh, const std::vector<glm::vec3>& outgoing, int out_bands, const PixelPoint& p,
                         const glm::dvec3& view);

/// Largest per-channel relative error |gpu - cpu| / |cpu| over covered pixels (triangle id set), with
/// the denominator floored at `floor`; also counts covered pixels.
double max_relative_error(const image::Image& gpu, const image::Image& cpu, const std::vector<std::uint32_t>& triangle_ids,
                          double floor, std::size_t& covered);

}  // namespace prt::render_test
