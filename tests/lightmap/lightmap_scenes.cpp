#include "lightmap/lightmap_scenes.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <glm/geometric.hpp>

#include "light/environment.h"

namespace prt::test {

void QuadBuilder::quad(const glm::vec3 (&corners)[4], const glm::vec3& normal, const glm::vec2 (&uv)[4]) {
  const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int k = 0; k < 4; ++k) {
    mesh.positions.push_back(corners[k]);
    mesh.normals.push_back(normal);
  }
  for (int k : {0, 1, 2, 0, 2, 3}) {
    mesh.indices.push_back(base + std::uint32_t(k));
    mesh.lightmap_uv.push_back(uv[k]);
  }
}

void QuadBuilder::quad(const glm::vec3 (&corners)[4], const glm::vec3& normal, const glm::vec2& uv0, const glm::vec2& size) {
  const glm::vec2 uv[4] = {uv0, uv0 + glm::vec2(size.x, 0.0f), uv0 + size, uv0 + glm::vec2(0.0f, size.y)};
  quad(corners, normal, uv);
}

namespace {

void add_floor(QuadBuilder& b) {
  b.quad({{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}}, {0, 1, 0}, {0.01f, 0.01f}, {0.58f, 0.58f});
}

// The six faces of [lo, hi], outward, each a quad from `corners_of`; uv slots given per face.
void add_box(QuadBuilder& b, const glm::vec3& lo, const glm::vec3& hi, const glm::vec2 (&slots)[6], float slot_size) {
  const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  const glm::vec2 size(slot_size);
  b.quad({{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}}, {0, 1, 0}, slots[0], size);
  b.quad({{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}, {0, -1, 0}, slots[1], size);
  b.quad({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, {0, 0, 1}, slots[2], size);
  b.quad({{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}}, {0, 0, -1}, slots[3], size);
  b.quad({{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}}, {1, 0, 0}, slots[4], size);
  b.quad({{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}, {-1, 0, 0}, slots[5], size);
}

}  // namespace

mesh::Mesh floor_and_box(bool with_box, float bottom) {
  QuadBuilder b;
  add_floor(b);
  if (with_box) {
    const glm::vec2 slots[6] = {{0.61f, 0.01f}, {0.61f, 0.41f}, {0.01f, 0.61f}, {0.41f, 0.61f}, {0.61f, 0.61f}, {0.81f, 0.81f}};
    add_box(b, {-0.3f, bottom, -0.3f}, {0.3f, bottom + 0.6f, 0.3f}, slots, 0.18f);
  }
  return b.mesh;
}

mesh::Mesh split_cube_on_floor() {
  QuadBuilder b;
  add_floor(b);
  // Each face: two triangles (0,1,2) and (0,2,3) of the quad, placed in two separate UV slots.
  const glm::vec3 lo(-0.5f, 0.1f, -0.5f), hi(0.5f, 1.1f, 0.5f);
  QuadBuilder faces;
  const glm::vec2 none[6] = {};
  add_box(faces, lo, hi, none, 0.0f);
  for (int f = 0; f < 6; ++f) {
    const glm::vec2 slot(0.62f + 0.19f * float(f % 2), 0.02f + 0.16f * float(f / 2));
    const glm::vec2 slot2(0.02f + 0.16f * float(f), 0.62f + 0.19f * float(f % 2));
    for (int t = 0; t < 2; ++t) {
      const std::uint32_t* idx = &faces.mesh.indices[6 * f + 3 * t];
      const std::uint32_t base = std::uint32_t(b.mesh.positions.size());
      const glm::vec2 origin = t == 0 ? slot : slot2;
      // Triangle (0,1,2) maps to the slot's lower-left half, (0,2,3) to the upper-left half.
      const glm::vec2 uv0[3] = {{0, 0}, {0.15f, 0}, {0.15f, 0.15f}};
      const glm::vec2 uv1[3] = {{0, 0}, {0.15f, 0.15f}, {0, 0.15f}};
      for (int k = 0; k < 3; ++k) {
        b.mesh.positions.push_back(faces.mesh.positions[idx[k]]);
        b.mesh.normals.push_back(faces.mesh.normals[idx[k]]);
        b.mesh.indices.push_back(base + std::uint32_t(k));
        b.mesh.lightmap_uv.push_back(origin + (t == 0 ? uv0[k] : uv1[k]));
      }
    }
  }
  return b.mesh;
}

void write_obj_with_uv(const std::string& path, const mesh::Mesh& m) {
  std::ofstream out(path);
  out.precision(9);
  for (const glm::vec3& p : m.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const glm::vec3& n : m.normals) out << "vn " << n.x << " " << n.y << " " << n.z << "\n";
  for (const glm::vec2& uv : m.lightmap_uv) out << "vt " << uv.x << " " << 1.0f - uv.y << "\n";
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    out << "f";
    for (int k = 0; k < 3; ++k) {
      const std::size_t c = 3 * t + std::size_t(k);
      out << " " << m.indices[c] + 1 << "/" << c + 1 << "/" << m.indices[c] + 1;
    }
    out << "\n";
  }
}

void write_test_sky(const std::string& path) {
  image::Image im(128, 64, 3);
  const glm::dvec3 lobe = glm::normalize(glm::dvec3(0.4, 0.7, -0.6));
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / im.width, (y + 0.5) / im.height);
      glm::dvec3 v = d.y > 0 ? glm::dvec3(0.35, 0.45, 0.7) * (0.4 + 0.6 * d.y) : glm::dvec3(0.2, 0.15, 0.1);
      v += glm::dvec3(3.0, 2.6, 2.0) * std::exp(6.0 * (glm::dot(d, lobe) - 1.0));
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(v[c]);
    }
  image::write(path, im);
}

double bilinear(const image::Image& image, const glm::vec2& uv, int channel) {
  const double x = uv.x * image.width - 0.5, y = uv.y * image.height - 0.5;
  const int i = int(std::floor(x)), j = int(std::floor(y));
  const double ax = x - i, ay = y - j;
  auto at = [&](int a, int b) {
    return double(image.at(std::clamp(a, 0, image.width - 1), std::clamp(b, 0, image.height - 1), channel));
  };
  return (1 - ax) * (1 - ay) * at(i, j) + ax * (1 - ay) * at(i + 1, j) + (1 - ax) * ay * at(i, j + 1) + ax * ay * at(i + 1, j + 1);
}

}  // namespace prt::test
