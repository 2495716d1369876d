#include "bench_meshes.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>
#include <ctime>
#include <glm/geometric.hpp>
#include <map>
#include <tuple>
#include <unordered_map>

#include "core/parallel.h"
#include "sh/sampling.h"
#include "support/random_draws.h"

namespace prt::bench {
namespace {

// Midpoint of edge (a, b) on the unit sphere, created once per edge (key: ordered vertex pair).
std::uint32_t midpoint(std::uint32_t a, std::uint32_t b, std::vector<glm::vec3>& unit,
                       std::unordered_map<std::uint64_t, std::uint32_t>& cache) {
  const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
  auto found = cache.find(key);
  if (found != cache.end()) return found->second;
  const glm::dvec3 m = (glm::dvec3(unit[a]) + glm::dvec3(unit[b])) * 0.5;
  unit.push_back(glm::vec3(m / glm::length(m)));
  const auto index = static_cast<std::uint32_t>(unit.size() - 1);
  cache.emplace(key, index);
  return index;
}

// Unit-sphere icosphere: positions on the unit sphere, counter-clockwise triangles seen from outside.
void unit_icosphere(int levels, std::vector<glm::vec3>& unit, std::vector<std::uint32_t>& indices) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double corners[12][3] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  unit.clear();
  for (const auto& c : corners) unit.push_back(glm::vec3(glm::normalize(glm::dvec3(c[0], c[1], c[2]))));
  indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
             3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::unordered_map<std::uint64_t, std::uint32_t> cache;
    cache.reserve(indices.size());
    std::vector<std::uint32_t> finer;
    finer.reserve(indices.size() * 4);
    for (std::size_t i = 0; i < indices.size(); i += 3) {
      const std::uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
      const std::uint32_t ab = midpoint(a, b, unit, cache), bc = midpoint(b, c, unit, cache),
                          ca = midpoint(c, a, unit, cache);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    indices.swap(finer);
  }
}

// Ridged bump field on the unit sphere, in [-0.5, 0.5].
double bump(const glm::dvec3& d) {
  // 12 fixed waves: direction (unnormalised), frequency, phase.
  static constexpr double waves[12][5] = {
      {0.9, 0.3, -0.3, 3.0, 0.1},   {-0.2, 0.8, 0.5, 4.0, 1.3},   {0.4, -0.5, 0.8, 5.0, 2.2},
      {0.7, 0.7, 0.1, 6.5, 0.7},    {-0.6, 0.2, 0.8, 8.0, 2.9},   {0.1, -0.9, -0.4, 9.5, 1.1},
      {0.5, 0.5, -0.7, 11.0, 0.4},  {-0.8, -0.5, 0.3, 13.0, 2.5}, {0.3, 0.1, 0.95, 15.0, 1.7},
      {0.6, -0.6, -0.5, 18.0, 0.9}, {-0.3, 0.9, -0.3, 21.0, 2.0}, {0.8, -0.1, 0.6, 24.0, 0.3}};
  double sum = 0.0, weights = 0.0;
  for (const auto& w : waves) {
    const glm::dvec3 k = glm::normalize(glm::dvec3(w[0], w[1], w[2])) * w[3];
    const double weight = 1.0 / w[3];
    sum += weight * (std::fabs(std::sin(glm::dot(k, d) + w[4])) - 0.5);
    weights += weight;
  }
  return sum / weights;  // each term in [-0.5, 0.5] times its weight: total in [-0.5, 0.5]
}

// One face of an axis-aligned box: the grid over the two axes other than `axis`, at `side` (0: lo,
// 1: hi), cells x cells quads, triangles wound so that their normal is `normal_sign` * e_axis.
// Vertex indices come from `vertex_of` (which may share vertices between faces).
template <typename VertexOf>
void box_face(int axis, int side, float normal_sign, int cells, const glm::vec3& lo, const glm::vec3& hi,
              VertexOf vertex_of, std::vector<std::uint32_t>& indices) {
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  std::vector<std::uint32_t> grid(std::size_t(cells + 1) * (cells + 1));
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      // Coordinates computed identically on every face so that shared edges match exactly.
      glm::vec3 p;
      p[axis] = side ? hi[axis] : lo[axis];
      p[ua] = i == cells ? hi[ua] : lo[ua] + (hi[ua] - lo[ua]) * float(i) / float(cells);
      p[va] = j == cells ? hi[va] : lo[va] + (hi[va] - lo[va]) * float(j) / float(cells);
      grid[std::size_t(j) * (cells + 1) + i] = vertex_of(p);
    }
  // (ua, va, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
  const bool flip = normal_sign < 0.0f;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const std::uint32_t a = grid[std::size_t(j) * (cells + 1) + i], b = grid[std::size_t(j) * (cells + 1) + i + 1];
      const std::uint32_t c = grid[std::size_t(j + 1) * (cells + 1) + i + 1],
                          d = grid[std::size_t(j + 1) * (cells + 1) + i];
      if (!flip)
        indices.insert(indices.end(), {a, b, c, a, c, d});
      else
        indices.insert(indices.end(), {a, c, b, a, d, c});
    }
}

// Box faces other than `missing` (face index 2 axis + side, -1 for none), normals pointing inward,
// vertices shared between faces with the normalised mean of the distinct face normals.
mesh::Mesh open_box_faces(const glm::vec3& lo, const glm::vec3& hi, int cells, int missing) {
  mesh::Mesh m;
  std::map<std::tuple<float, float, float>, std::uint32_t> index_of;
  std::vector<glm::dvec3> normal_sums;
  std::vector<int> last_face;
  for (int face = 0; face < 6; ++face) {
    if (face == missing) continue;
    const int axis = face / 2, side = face % 2;
    const float inward = side ? -1.0f : 1.0f;
    glm::dvec3 face_normal(0.0);
    face_normal[axis] = inward;
    auto vertex_of = [&](const glm::vec3& p) {
      auto [it, inserted] = index_of.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(m.positions.size()));
      if (inserted) {
        m.positions.push_back(p);
        normal_sums.emplace_back(0.0);
        last_face.push_back(-1);
      }
      if (last_face[it->second] != face) {
        normal_sums[it->second] += face_normal;
        last_face[it->second] = face;
      }
      return it->second;
    };
    box_face(axis, side, inward, cells, lo, hi, vertex_of, m.indices);
  }
  for (const glm::dvec3& s : normal_sums) m.normals.push_back(glm::vec3(glm::normalize(s)));
  return m;
}

// Rotates a mesh about the Y axis through `pivot` by `radians`.
void rotate_y(mesh::Mesh& m, const glm::vec3& pivot, float radians) {
  const float c = std::cos(radians), s = std::sin(radians);
  auto rot = [&](const glm::vec3& v) { return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
  for (glm::vec3& p : m.positions) p = pivot + rot(p - pivot);
  for (glm::vec3& n : m.normals) n = rot(n);
}

}  // namespace

mesh::Mesh icosphere(int levels, float radius, const glm::vec3& center) {
  mesh::Mesh m;
  std::vector<glm::vec3> unit;
  unit_icosphere(std::clamp(levels, 0, 10), unit, m.indices);
  m.positions.reserve(unit.size() + 1);
  for (const glm::vec3& d : unit) m.positions.push_back(center + radius * d);
  m.normals = unit;
  return m;
}

mesh::Mesh bumpy_icosphere(int levels, float amplitude) {
  mesh::Mesh m;
  std::vector<glm::vec3> unit;
  unit_icosphere(std::clamp(levels, 0, 10), unit, m.indices);
  m.positions.reserve(unit.size() + 1);
  for (const glm::vec3& d : unit)
    m.positions.push_back(glm::vec3(glm::dvec3(d) * (1.0 + double(amplitude) * bump(glm::dvec3(d)))));
  m.normals = vertex_normals(m.positions, m.indices);
  return m;
}

mesh::Mesh detailed_blob() { return bumpy_icosphere(8, 0.35f); }

mesh::Mesh box(const glm::vec3& lo, const glm::vec3& hi, int cells) {
  mesh::Mesh m;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2, side = face % 2;
    const float outward = side ? 1.0f : -1.0f;
    glm::vec3 normal(0.0f);
    normal[axis] = outward;
    auto vertex_of = [&](const glm::vec3& p) {
      m.positions.push_back(p);
      m.normals.push_back(normal);
      return std::uint32_t(m.positions.size() - 1);
    };
    box_face(axis, side, outward, cells, lo, hi, vertex_of, m.indices);
  }
  return m;
}

mesh::Mesh open_box(const glm::vec3& lo, const glm::vec3& hi, int cells) {
  return open_box_faces(lo, hi, cells, /*missing: +Y*/ 3);
}

mesh::Mesh cornell_box(int cells) {
  mesh::Mesh room = open_box_faces(glm::vec3(0.0f), glm::vec3(1.0f), cells, /*missing: +Z*/ 5);
  mesh::Mesh tall = box(glm::vec3(0.2f, 0.0f, 0.25f), glm::vec3(0.5f, 0.6f, 0.55f), 2);
  rotate_y(tall, glm::vec3(0.35f, 0.0f, 0.4f), 0.3f);
  mesh::Mesh low = box(glm::vec3(0.55f, 0.0f, 0.5f), glm::vec3(0.85f, 0.3f, 0.8f), 2);
  rotate_y(low, glm::vec3(0.7f, 0.0f, 0.65f), -0.3f);
  append(room, tall);
  append(room, low);
  return room;
}

void append(mesh::Mesh& a, const mesh::Mesh& b) {
  const auto offset = static_cast<std::uint32_t>(a.positions.size());
  const bool keep_albedo = !a.albedo.empty() && !b.albedo.empty();
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  if (keep_albedo)
    a.albedo.insert(a.albedo.end(), b.albedo.begin(), b.albedo.end());
  else
    a.albedo.clear();
  for (std::uint32_t i : b.indices) a.indices.push_back(i + offset);
}

std::vector<glm::vec3> vertex_normals(const std::vector<glm::vec3>& positions,
                                      const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    const glm::dvec3 a(positions[indices[i]]), b(positions[indices[i + 1]]), c(positions[indices[i + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) sums[indices[i + k]] += n;
  }
  std::vector<glm::vec3> normals(positions.size());
  for (std::size_t v = 0; v < sums.size(); ++v) {
    const double length = glm::length(sums[v]);
    normals[v] = length > 0.0 ? glm::vec3(sums[v] / length) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

std::vector<glm::vec3> hemisphere_directions(std::size_t count) {
  std::vector<glm::vec3> dirs(count);
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < count; ++i) {
    const double z = 1.0 - (double(i) + 0.5) / double(count);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * double(i);
    dirs[i] = glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }
  return dirs;
}

void orthonormal_frame(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

namespace {

// Shared body of the two passes: per vertex, fills batches with the vertex's rays and calls `trace`,
// which returns how many rays of the batch count.
template <typename Trace>
PassResult run_pass(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<std::uint32_t>& order,
                    const std::vector<glm::vec3>& directions, int threads, std::size_t batch_size, const PassFrames& frames,
                    Trace trace) {
  PassResult result;
  result.counts.assign(mesh.positions.size(), 0);
  batch_size = std::max<std::size_t>(1, std::min(batch_size, directions.size()));
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  parallel_for(order.size(), 64, threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(batch_size);
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = order[k];
      const glm::vec3 n = mesh.normals[v];
      glm::vec3 t, b;
      if (frames.bake) {
        const glm::mat3 f = sh::vertex_frame(n, frames.seed, v);
        t = f[0];
        b = f[1];
      } else {
        orthonormal_frame(n, t, b);
      }
      const glm::vec3 origin = scene.offset_origin(mesh.positions[v], n);
      std::size_t count = 0;
      for (std::size_t d0 = 0; d0 < directions.size(); d0 += batch_size) {
        const std::size_t d1 = std::min(directions.size(), d0 + batch_size);
        batch.clear();
        for (std::size_t d = d0; d < d1; ++d) {
          const glm::vec3& l = directions[d];
          batch.push(origin, t * l.x + b * l.y + n * l.z);
        }
        count += trace(batch);
      }
      result.counts[v] = static_cast<std::uint16_t>(count);
    }
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.cpu_seconds = process_cpu_seconds() - cpu_start;
  result.rays = order.size() * directions.size();
  result.mrays_per_second = result.seconds > 0.0 ? double(result.rays) / result.seconds * 1e-6 : 0.0;
  result.mrays_per_cpu_second = result.cpu_seconds > 0.0 ? double(result.rays) / result.cpu_seconds * 1e-6 : 0.0;
  for (std::size_t v = 0; v < result.counts.size(); ++v) result.checksum += std::uint64_t(result.counts[v]) * (v + 1);
  return result;
}

}  // namespace

PassResult occlusion_pass(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<std::uint32_t>& order,
                          const std::vector<glm::vec3>& directions, int threads, std::size_t batch_size,
                          const PassFrames& frames) {
  return run_pass(scene, mesh, order, directions, threads, batch_size, frames, [&](trace::RayBatch& batch) {
    scene.occluded(batch);
    return batch.size() - batch.occluded_count();
  });
}

PassResult closest_hit_pass(const trace::Scene& scene, const mesh::Mesh& mesh, const std::vector<std::uint32_t>& order,
                            const std::vector<glm::vec3>& directions, int threads, std::size_t batch_size,
                            const PassFrames& frames) {
  return run_pass(scene, mesh, order, directions, threads, batch_size, frames, [&](trace::RayBatch& batch) {
    scene.intersect(batch);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < batch.size(); ++i) hits += batch.hit(i).hit() ? 1 : 0;
    return hits;
  });
}

// A latitude-longitude unit sphere of rings x segments vertices plus the two poles, radial normals.
mesh::Mesh lat_long_sphere(int rings, int segments) {
  mesh::Mesh m;
  m.positions.push_back({0, 1, 0});
  for (int i = 1; i <= rings; ++i) {
    const double theta = M_PI * i / (rings + 1);
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      m.positions.push_back(glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  m.positions.push_back({0, -1, 0});
  m.normals = m.positions;
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  const std::uint32_t bottom = static_cast<std::uint32_t>(m.positions.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.indices.insert(m.indices.end(), {0u, at(1, j + 1), at(1, j)});
    m.indices.insert(m.indices.end(), {bottom, at(rings, j), at(rings, j + 1)});
  }
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)});
      m.indices.insert(m.indices.end(), {at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  m.positions.reserve(m.positions.size() + 1);
  return m;
}

sh::RgbCoefficients random_lighting(int bands) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  sh::RgbCoefficients l(bands);
  for (glm::dvec3& v : l.values) v = prt::test::draw_vec3<double>(rng, gauss) * 0.3;
  l.values[0] += glm::dvec3(3.0);
  return l;
}

}  // namespace prt::bench
