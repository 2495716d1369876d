#include "cpu_raster.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "brdf/frame.h"
#include "render/renderer.h"
#include "sh/basis.h"

namespace prt::render_test {

image::Image per_pixel_on_cpu(const mesh::Mesh& mesh, const glm::mat4& model_view_projection,
                              const std::vector<std::uint32_t>& triangle_ids, int width, int height,
                              const PixelFunction& value_at) {
  image::Image out(width, height, 3);
  const glm::dmat4 mvp(model_view_projection);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint32_t t = triangle_ids[static_cast<std::size_t>(y) * width + x];
      if (t == render::kNoTriangle) continue;
      const glm::dvec2 pixel((x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0);
      PixelPoint point;
      point.triangle = t;
      glm::dvec2 screen[3];
      double w[3];
      for (int k = 0; k < 3; ++k) {
        point.corner[k] = mesh.indices[3 * t + k];
        const glm::dvec4 clip = mvp * glm::dvec4(glm::dvec3(mesh.positions[point.corner[k]]), 1.0);
        w[k] = clip.w;
        screen[k] = glm::dvec2(clip) / clip.w;
      }
      // Screen-space barycentrics from signed areas.
      auto edge = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
        return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      };
      const double area = edge(screen[0], screen[1], screen[2]);
      const double l[3] = {edge(screen[1], screen[2], pixel) / area, edge(screen[2], screen[0], pixel) / area,
                           edge(screen[0], screen[1], pixel) / area};
      const double sum = l[0] / w[0] + l[1] / w[1] + l[2] / w[2];
      for (int k = 0; k < 3; ++k) {
        point.weight[k] = l[k] / w[k] / sum;
        point.position += point.weight[k] * glm::dvec3(mesh.positions[point.corner[k]]);
      }
      const glm::dvec3 value = value_at(point);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(value[c]);
    }
  }
  return out;
}

image::Image interpolate_on_cpu(const mesh::Mesh& mesh, const std::vector<glm::vec3>& vertex_values,
                                const glm::mat4& model_view_projection, const std::vector<std::uint32_t>& triangle_ids,
                                int width, int height) {
  return per_pixel_on_cpu(mesh, model_view_projection, triangle_ids, width, height, [&](const PixelPoint& p) {
    glm::dvec3 value(0.0);
    for (int k = 0; k < 3; ++k) value += p.weight[k] * glm::dvec3(vertex_values[p.corner[k]]);
    return value;
  });
}

glm::dvec3 glossy_prt_at(const mesh::Mesh& mesh, const std::vector<glm::vec3>& outgoing, int out_bands, const PixelPoint& p,
                         const glm::dvec3& view) {
  const int n = out_bands * out_bands;
  std::vector<double> y(static_cast<std::size_t>(n));
  glm::dvec3 value(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dmat3 frame = brdf::shading_frame(glm::dvec3(mesh.normals[p.corner[k]]));
    sh::eval(out_bands, glm::transpose(frame) * view, y.data());
    glm::dvec3 radiance(0.0);
    for (int i = 0; i < n; ++i) radiance += y[static_cast<std::size_t>(i)] * glm::dvec3(outgoing[p.corner[k] * n + i]);
    value += p.weight[k] * radiance;
  }
  return value;
}

double max_relative_error(const image::Image& gpu, const image::Image& cpu, const std::vector<std::uint32_t>& triangle_ids,
                          double floor, std::size_t& covered) {
  double worst = 0.0;
  covered = 0;
  for (int y = 0; y < gpu.height; ++y) {
    for (int x = 0; x < gpu.width; ++x) {
      if (triangle_ids[static_cast<std::size_t>(y) * gpu.width + x] == render::kNoTriangle) continue;
      ++covered;
      for (int c = 0; c < 3; ++c) {
        const double expected = cpu.at(x, y, c);
        const double error = std::fabs(gpu.at(x, y, c) - expected) / std::max(std::fabs(expected), floor);
        worst = std::max(worst, std::isfinite(error) ? error : 1e30);
      }
    }
  }
  return worst;
}

}  // namespace prt::render_test
