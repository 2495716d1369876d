#include "probes/probe_scene.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "light/projection.h"

namespace prt::test {

namespace {

// Appends a grid quad: corner + s * u + t * v, s, t in [0,1], normal = normalize(u x v).
void add_quad(mesh::Mesh& m, const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int cells,
              const glm::vec3& albedo) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      m.positions.push_back(corner + u * (static_cast<float>(i) / cells) + v * (static_cast<float>(j) / cells));
      m.normals.push_back(normal);
      m.albedo.push_back(albedo);
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const std::uint32_t a = base + j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
}

}  // namespace

ProbeScene make_probe_scene(bool emissive) {
  ProbeScene s;
  mesh::Mesh& m = s.mesh;
  // Floor, normal +Y: u = +Z... u x v must be +Y: u = (0,0,4), v = (4,0,0).
  add_quad(m, {-2, 0, -2}, {0, 0, 4}, {4, 0, 0}, 24, glm::vec3(0.7f));
  // Box faces, outward normals.
  const glm::vec3 lo(-0.5f, 0.001f, -0.5f), hi(0.5f, 1.0f, 0.5f), size = hi - lo, box_albedo(0.8f, 0.3f, 0.2f);
  add_quad(m, {hi.x, lo.y, lo.z}, {0, size.y, 0}, {0, 0, size.z}, 6, box_albedo);        // +X
  add_quad(m, {lo.x, lo.y, lo.z}, {0, 0, size.z}, {0, size.y, 0}, 6, box_albedo);        // -X
  add_quad(m, {lo.x, hi.y, lo.z}, {0, 0, size.z}, {size.x, 0, 0}, 6, box_albedo);        // +Y
  add_quad(m, {lo.x, lo.y, lo.z}, {size.x, 0, 0}, {0, 0, size.z}, 6, box_albedo);        // -Y
  add_quad(m, {lo.x, lo.y, hi.z}, {size.x, 0, 0}, {0, size.y, 0}, 6, box_albedo);        // +Z
  add_quad(m, {lo.x, lo.y, lo.z}, {0, size.y, 0}, {size.x, 0, 0}, 6, box_albedo);        // -Z
  // Wall at x = 1.5 facing -X.
  const std::size_t wall_first = m.positions.size();
  add_quad(m, {1.5f, 0, -1.5f}, {0, 1.5f, 0}, {0, 0, 3}, 12, glm::vec3(0.5f));
  s.emission.assign(m.positions.size(), glm::vec3(0.0f));
  if (emissive)
    for (std::size_t v = wall_first; v < m.positions.size(); ++v)
      if (std::abs(m.positions[v].z) < 0.75f && m.positions[v].y > 0.5f) s.emission[v] = glm::vec3(2.0f, 1.6f, 1.2f);
  m.positions.reserve(m.positions.size() + 1);
  s.probes = {{0.0, 0.5, 0.0},   {-1.0, 0.4, 0.0}, {0.0, 1.5, 0.0},  {1.0, 0.6, 0.0},
              {0.9, 0.3, 0.9},   {-1.2, 1.0, 1.2}, {0.0, 0.2, -1.0}, {1.3, 1.2, -1.0}};
  return s;
}

light::Environment make_sky() {
  light::Environment env;
  env.layout = light::Environment::Layout::equirect;
  env.source = "test sky";
  const int w = 256, h = 128;
  env.equirect = image::Image(w, h, 3);
  const glm::dvec3 glow_direction = glm::normalize(glm::dvec3(1.0, 1.0, 0.3));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / w, (y + 0.5) / h);
      glm::dvec3 c;
      if (d.y >= 0.0) c = glm::mix(glm::dvec3(0.9, 0.95, 1.0), glm::dvec3(0.3, 0.5, 1.0), d.y);
      else c = glm::dvec3(0.25, 0.2, 0.15) * (1.0 + 0.5 * d.y);
      const double g = std::max(0.0, glm::dot(d, glow_direction));
      c += glm::dvec3(1.0, 0.7, 0.4) * (g * g * g);
      for (int k = 0; k < 3; ++k) env.equirect.at(x, y, k) = static_cast<float>(c[k]);
    }
  return env;
}

light::Environment make_band_limited_sky(int bands) {
  light::Environment env;
  env.layout = light::Environment::Layout::equirect;
  env.source = "band-limited test sky";
  env.equirect = light::render_equirect(light::project(make_sky(), bands), 512, 256);
  return env;
}

}  // namespace prt::test
