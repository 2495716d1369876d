#include "render_fixtures.h"

#include <cmath>
#include <algorithm>
#include <cstdint>

#include <glm/geometric.hpp>

#include "light/environment.h"
#include "light/light_file.h"
#include "mesh/writers.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::render_test {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Zonal coefficients of max(cos, 0): A_0 = pi, A_1 = 2pi/3, odd l > 1: 0, even l:
// A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2)  (Ramamoorthi & Hanrahan 2001).
double clamped_cosine(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  double factorial_ratio = 1.0;  // l! / (2^l ((l/2)!)^2)
  for (int k = 1; k <= l / 2; ++k) factorial_ratio *= (l / 2.0 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * factorial_ratio;
}

// A fixed pseudo-random number in [-1, 1) from an integer (splitmix64).
double hash_unit(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

}  // namespace

mesh::Mesh bumpy_sphere(int rings, int segments, const glm::vec3& centre) {
  mesh::Mesh m;
  auto point = [&centre](double theta, double phi) {
    const double r = 1.0 + 0.15 * std::sin(3.0 * theta) * std::cos(2.0 * phi);
    const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    return glm::vec3(glm::dvec3(centre) + r * d);
  };
  m.positions.push_back(point(0.0, 0.0));  // north pole
  for (int i = 0; i < rings; ++i) {
    const double theta = kPi * (i + 1.0) / (rings + 1.0);
    for (int j = 0; j < segments; ++j) m.positions.push_back(point(theta, 2.0 * kPi * j / segments));
  }
  m.positions.push_back(point(kPi, 0.0));  // south pole
  const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
  auto ring_vertex = [segments](int i, int j) { return static_cast<std::uint32_t>(1 + i * segments + (j % segments)); };
  // Counter-clockwise seen from outside (phi grows toward +Z, i.e. clockwise seen from +Y).
  for (int j = 0; j < segments; ++j) {
    m.indices.insert(m.indices.end(), {0u, ring_vertex(0, j + 1), ring_vertex(0, j)});
    m.indices.insert(m.indices.end(), {south, ring_vertex(rings - 1, j), ring_vertex(rings - 1, j + 1)});
  }
  for (int i = 0; i + 1 < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = ring_vertex(i, j), b = ring_vertex(i, j + 1), c = ring_vertex(i + 1, j),
                          d = ring_vertex(i + 1, j + 1);
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  }
  m.normals = mesh::area_weighted_normals(m.positions, m.indices);
  return m;
}

transfer::TransferData unshadowed_transfer(const mesh::Mesh& mesh, int bands, int channels, const glm::vec3& albedo) {
  transfer::TransferData data;
  data.header.kind = transfer::Kind::unshadowed;
  data.header.bands = static_cast<std::uint32_t>(bands);
  data.header.channels = static_cast<std::uint32_t>(channels);
  data.header.vertex_count = mesh.vertex_count();
  data.header.triangle_count = mesh.triangle_count();
  data.header.mesh_fingerprint = mesh::fingerprint(mesh);
  data.header.parameters_json = "{\"test\": \"unshadowed closed form\"}";
  const int count = bands * bands;
  data.values.resize(mesh.vertex_count() * static_cast<std::size_t>(channels * count));
  std::vector<double> y(static_cast<std::size_t>(count));
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    sh::eval(bands, glm::dvec3(mesh.normals[v]), y.data());
    for (int c = 0; c < channels; ++c) {
      for (int i = 0; i < count; ++i) {
        const double t = albedo[c] / kPi * clamped_cosine(sh::band_of(i)) * y[static_cast<std::size_t>(i)];
        data.values[(v * channels + c) * count + i] = static_cast<float>(t);
      }
    }
  }
  return data;
}

sh::RgbCoefficients test_lighting(int bands) {
  sh::RgbCoefficients L(bands);
  L.values[0] = glm::dvec3(3.0, 2.8, 2.5);
  for (int i = 1; i < bands * bands; ++i) {
    const double scale = 0.6 / (sh::band_of(i) + 1.0);
    for (int c = 0; c < 3; ++c) L.values[static_cast<std::size_t>(i)][c] = scale * hash_unit(static_cast<std::uint64_t>(3 * i + c));
  }
  return L;
}

image::Image smooth_environment(int width) {
  image::Image im(width, width / 2, 3);
  const glm::dvec3 lobe_x = glm::normalize(glm::dvec3(1.0, 0.3, 0.1)), lobe_z = glm::normalize(glm::dvec3(-0.2, 0.2, 1.0));
  for (int y = 0; y < im.height; ++y) {
    for (int x = 0; x < im.width; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / im.width, (y + 0.5) / im.height);
      const double sky = 0.5 + 0.4 * d.y;
      const double a = std::pow(std::max(0.0, glm::dot(d, lobe_x)), 4.0), b = std::pow(std::max(0.0, glm::dot(d, lobe_z)), 2.0);
      const glm::dvec3 radiance = sky * glm::dvec3(0.6, 0.7, 1.0) + a * glm::dvec3(4.0, 3.0, 1.5) + b * glm::dvec3(0.5, 1.5, 3.0);
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(radiance[c]);
    }
  }
  return im;
}

void write_fixture_files(const std::string& folder) {
  const mesh::Mesh generated = bumpy_sphere(24, 48);
  mesh::write_ply(folder + "/mesh.ply", generated.positions, {}, generated.indices);
  const mesh::Mesh loaded = mesh::load_mesh(folder + "/mesh.ply", nullptr, true);
  transfer::write_transfer(folder + "/transfer.prt", unshadowed_transfer(loaded, 5, 3, glm::vec3(0.8f, 0.6f, 0.4f)));
  transfer::write_transfer(folder + "/transfer_grey.prt", unshadowed_transfer(loaded, 3, 1, glm::vec3(0.7f)));
  transfer::write_transfer(folder + "/other.prt", unshadowed_transfer(bumpy_sphere(10, 20), 5, 3, glm::vec3(0.5f)));
  image::write(folder + "/env.exr", smooth_environment(64));
  light::LightFileInfo info;
  info.source = "render test lighting";
  light::write_light_file(folder + "/light.json", test_lighting(3), info);
}

render::FrameSettings black_frame(int transfer, int bands, const glm::dvec3& environment_ypr, const glm::dvec3& object_ypr) {
  render::FrameSettings settings;
  settings.transfer = transfer;
  settings.bands = bands;
  settings.background = render::Background::black;
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(environment_ypr.x, environment_ypr.y, environment_ypr.z);
  settings.object_rotation = sh::rotation_from_yaw_pitch_roll(object_ypr.x, object_ypr.y, object_ypr.z);
  return settings;
}

}  // namespace prt::render_test
