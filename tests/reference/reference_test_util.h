#pragma once
// Helpers for the reference path tracer's tests: synthetic environments, planar grids, statistics.
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "image/image.h"
#include "light/environment.h"
#include "mesh/mesh.h"

namespace prt::test {

/// An equirect environment of width x height whose texel (x, y) holds value(x, y).
inline light::Environment equirect_environment(int width, int height,
                                               const std::function<glm::dvec3(int x, int y)>& value) {
  light::Environment env;
  env.layout = light::Environment::Layout::equirect;
  env.equirect = image::Image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 v = value(x, y);
      for (int c = 0; c < 3; ++c) env.equirect.at(x, y, c) = static_cast<float>(v[c]);
    }
  env.source = "synthetic";
  return env;
}

/// Constant radiance c everywhere.
inline light::Environment constant_environment(const glm::dvec3& c, int width = 64, int height = 32) {
  return equirect_environment(width, height, [&](int, int) { return c; });
}

/// Grid of cells x cells quads over [-size, size]^2 in x, z at y = 0, normal +Y, counter-clockwise
/// seen from above.
inline mesh::Mesh ground_grid(int cells, float size = 1.0f) {
  mesh::Mesh m;
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) {
      m.positions.push_back(glm::vec3(-size + 2 * size * j / cells, 0.0f, -size + 2 * size * i / cells));
      m.normals.push_back(glm::vec3(0, 1, 0));
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (cells + 1) + j); };
  // Rows i run along +z, columns j along +x: (+z) x (+x) = +y, so (i,j) -> (i+1,j) -> (i+1,j+1) is CCW from above.
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

/// Mean and sample standard deviation of one channel over a set of vertices.
struct Spread {
  double mean = 0.0, stddev = 0.0;
  std::size_t count = 0;
};
inline Spread spread(const std::vector<glm::vec3>& values, int channel) {
  Spread s;
  s.count = values.size();
  for (const glm::vec3& v : values) s.mean += v[channel];
  s.mean /= static_cast<double>(s.count);
  double sq = 0.0;
  for (const glm::vec3& v : values) sq += (v[channel] - s.mean) * (v[channel] - s.mean);
  s.stddev = std::sqrt(sq / static_cast<double>(s.count - 1));
  return s;
}

}  // namespace prt::test
