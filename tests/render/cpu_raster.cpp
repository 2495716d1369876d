#include "cpu_raster.h"

#include <algorithm>
#include <cmath>

#include <glm/vec4.hpp>

#include "render/renderer.h"

namespace prt::render_test {

image::Image interpolate_on_cpu(const mesh::Mesh& mesh, const std::vector<glm::vec3>& vertex_values,
                                const glm::mat4& model_view_projection, const std::vector<std::uint32_t>& triangle_ids,
                                int width, int height) {
  image::Image out(width, height, 3);
  const glm::dmat4 mvp(model_view_projection);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint32_t t = triangle_ids[static_cast<std::size_t>(y) * width + x];
      if (t == render::kNoTriangle) continue;
      const glm::dvec2 pixel((x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0);
      glm::dvec2 screen[3];
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const glm::dvec4 clip = mvp * glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[3 * t + k]]), 1.0);
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
      glm::dvec3 value(0.0);
      for (int k = 0; k < 3; ++k) value += (l[k] / w[k] / sum) * glm::dvec3(vertex_values[mesh.indices[3 * t + k]]);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(value[c]);
    }
  }
  return out;
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
