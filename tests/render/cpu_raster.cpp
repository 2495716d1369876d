#include "cpu_raster.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "brdf/frame.h"
#include "render/renderer.h"
#include "sh/basis.h"
#include <glm/mat3x3.hpp>

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

namespace prt::render_test {

namespace {

template <class Include>
double max_relative_error_where(const image::Image& gpu, const image::Image& cpu, double floor, std::size_t& compared,
                                Include include) {
  double worst = 0.0;
  compared = 0;
  for (int y = 0; y < gpu.height; ++y)
    for (int x = 0; x < gpu.width; ++x) {
      if (!include(x, y)) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) {
        const double expected = cpu.at(x, y, c);
        const double error = std::fabs(gpu.at(x, y, c) - expected) / std::max(std::fabs(expected), floor);
        worst = std::max(worst, std::isfinite(error) ? error : 1e30);
      }
    }
  return worst;
}

}  // namespace

}  // namespace prt::render_test

namespace prt::render_test {

std::vector<PixelHit> cast_pixels(const mesh::Mesh& mesh, double azimuth_degrees, double elevation_degrees,
                                  double distance, const glm::dmat3& object_rotation, int width, int height,
                                  glm::dvec3* eye_object) {
  glm::dvec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const glm::dvec3 c = 0.5 * (lo + hi);
  const double r = 0.5 * glm::length(hi - lo), aspect = double(width) / double(height);
  const double tan_y = std::tan(20.0 * M_PI / 180.0), tan_x = tan_y * aspect;
  const double half_narrow = std::min(20.0 * M_PI / 180.0, std::atan(tan_x));
  const double dist = distance > 0.0 ? distance : 1.05 * r / std::sin(half_narrow);
  const double az = azimuth_degrees * M_PI / 180.0, el = elevation_degrees * M_PI / 180.0;
  const glm::dvec3 back(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  const glm::dvec3 eye = c + dist * back;
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), back)), up = glm::cross(back, right);
  // Rays in the mesh's own coordinates: rotate the camera by R^-1 about c instead of the mesh by R.
  const glm::dmat3 inverse = glm::transpose(object_rotation);
  const glm::dvec3 eye_o = c + inverse * (eye - c);
  if (eye_object) *eye_object = eye_o;
  std::vector<PixelHit> hits(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / height * 2.0;
      const glm::dvec3 d = inverse * glm::normalize(-back + nx * tan_x * right + ny * tan_y * up);
      PixelHit& best = hits[static_cast<std::size_t>(y) * width + x];
      double best_t = 1e300;
      for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
        const glm::dvec3 p0(mesh.positions[mesh.indices[3 * t]]), p1(mesh.positions[mesh.indices[3 * t + 1]]),
            p2(mesh.positions[mesh.indices[3 * t + 2]]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (std::abs(det) < 1e-300) continue;
        const glm::dvec3 tv = eye_o - p0;
        const double u = glm::dot(tv, pv) / det;
        if (u < 0.0 || u > 1.0) continue;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(d, qv) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double dist_t = glm::dot(e2, qv) / det;
        if (dist_t <= 0.0 || dist_t >= best_t) continue;
        best_t = dist_t;
        best.triangle = static_cast<std::uint32_t>(t);
        best.b[0] = 1.0 - u - v;
        best.b[1] = u;
        best.b[2] = v;
        best.point = eye_o + dist_t * d;
      }
    }
  return hits;
}

bool interior_hit(const std::vector<PixelHit>& hits, int width, int height, int x, int y) {
  auto hit = [&](int px, int py) {
    return px >= 0 && py >= 0 && px < width && py < height && hits[static_cast<std::size_t>(py) * width + px].triangle != 0xFFFFFFFFu;
  };
  return hit(x, y) && hit(x - 1, y) && hit(x + 1, y) && hit(x, y - 1) && hit(x, y + 1);
}

image::Image interpolate_hits(const mesh::Mesh& mesh, const std::vector<glm::vec3>& vertex_values,
                              const std::vector<PixelHit>& hits, int width, int height) {
  image::Image out(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelHit& h = hits[static_cast<std::size_t>(y) * width + x];
      if (h.triangle == 0xFFFFFFFFu) continue;
      glm::dvec3 value(0.0);
      for (int k = 0; k < 3; ++k) value += h.b[k] * glm::dvec3(vertex_values[mesh.indices[3 * h.triangle + k]]);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(value[c]);
    }
  return out;
}

double max_relative_error_interior(const image::Image& gpu, const image::Image& cpu, const std::vector<PixelHit>& hits,
                                   double floor, std::size_t& compared) {
  return max_relative_error_where(gpu, cpu, floor, compared,
                                  [&](int x, int y) { return interior_hit(hits, gpu.width, gpu.height, x, y); });
}

}  // namespace prt::render_test

