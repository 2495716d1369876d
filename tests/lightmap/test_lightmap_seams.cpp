// Seam stitching (src/lightmap/seams.h): on a UV sphere resting on a floor (a lat-long chart whose
// longitude seam and pole rows split it) and on a scanned mesh (the Chinese dragon of CGAL's data, as
// guardian_lion_10k.ply, charts from prt unwrap), the lit values that bilinear lookups read on the two
// sides of every smooth seam edge agree within 2% of the local value after `--stitch`, and do not
// without it. The seams and the lookups are found here, independently of the stitcher's code.
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "light/environment.h"
#include "light/projection.h"
#include "lightmap/texel_bake.h"
#include "mesh/mesh.h"
#include "transfer/transfer_file.h"
#include "unwrap/unwrap.h"

namespace prt {

namespace {

// A UV sphere (radius 0.4, centre 0.42 above the floor) on a 2 x 2 floor. The sphere is welded (one
// vertex per ring point, one per pole) with exact normals; its lat-long chart is u in [0.02, 0.98]
// (the u = 0 and u = 1 columns are the same vertices: the longitude seam), v in [0.62, 0.98] (each
// pole triangle's pole corner at its own u: the pole rows are seams too). The floor chart is [0.02,
// 0.58]^2.
mesh::Mesh sphere_on_floor(int segments, int rings) {
  mesh::Mesh m;
  auto add = [&](const glm::vec3& p, const glm::vec3& n) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    return std::uint32_t(m.positions.size() - 1);
  };
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, glm::vec2 ua, glm::vec2 ub, glm::vec2 uc) {
    m.indices.insert(m.indices.end(), {a, b, c});
    m.lightmap_uv.insert(m.lightmap_uv.end(), {ua, ub, uc});
  };
  const std::uint32_t f0 = add({-1, 0, -1}, {0, 1, 0}), f1 = add({-1, 0, 1}, {0, 1, 0}), f2 = add({1, 0, 1}, {0, 1, 0}),
                      f3 = add({1, 0, -1}, {0, 1, 0});
  tri(f0, f1, f2, {0.02f, 0.02f}, {0.02f, 0.58f}, {0.58f, 0.58f});
  tri(f0, f2, f3, {0.02f, 0.02f}, {0.58f, 0.58f}, {0.58f, 0.02f});
  const glm::vec3 centre(0.0f, 0.42f, 0.0f);
  const float radius = 0.4f;
  auto point = [&](int ring, int seg) {  // ring 0 = north pole, rings = south pole
    const double theta = kPi * ring / rings, phi = 2.0 * kPi * (seg % segments) / segments;
    return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::sin(phi)));
  };
  std::vector<std::uint32_t> index;  // (ring, seg) for rings 1..rings-1
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) index.push_back(add(centre + radius * point(r, s), point(r, s)));
  const std::uint32_t north = add(centre + radius * point(0, 0), {0, 1, 0}), south = add(centre + radius * point(rings, 0), {0, -1, 0});
  auto at = [&](int r, int s) { return index[std::size_t((r - 1) * segments + (s % segments))]; };
  auto uv = [&](double r, double s) { return glm::vec2(float(0.02 + 0.96 * s / segments), float(0.62 + 0.36 * r / rings)); };
  for (int s = 0; s < segments; ++s) {
    tri(north, at(1, s), at(1, s + 1), uv(0, s + 0.5), uv(1, s), uv(1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      tri(at(r, s), at(r + 1, s), at(r + 1, s + 1), uv(r, s), uv(r + 1, s), uv(r + 1, s + 1));
      tri(at(r, s), at(r + 1, s + 1), at(r, s + 1), uv(r, s), uv(r + 1, s + 1), uv(r, s + 1));
    }
    tri(south, at(rings - 1, s + 1), at(rings - 1, s), uv(rings, s + 0.5), uv(rings - 1, s + 1), uv(rings - 1, s));
  }
  return m;
}

// Lit value of every texel (the transfer dotted with the environment's SH, the channels' mean).
std::vector<double> lit_texels(const transfer::TransferData& d, const sh::RgbCoefficients& env) {
  const std::size_t n = std::size_t(d.header.bands) * d.header.bands, channels = d.header.channels;
  std::vector<double> lit(d.coverage.size(), 0.0);
  for (std::size_t t = 0; t < lit.size(); ++t)
    for (std::size_t c = 0; c < 3; ++c) {
      const float* T = d.values.data() + t * n * channels + (channels == 1 ? 0 : c) * n;
      for (std::size_t i = 0; i < n; ++i) lit[t] += double(T[i]) * env.values[i][int(c)] / 3.0;
    }
  return lit;
}

struct SeamCheck {
  std::size_t edges = 0, points = 0, over = 0;
  double worst = 0.0;
};

// Every edge shared by two triangles (by end positions) whose UVs differ and whose vertex normals agree
// (dot >= 0.99): at 7 points along it, bilinear lookups (texel centres, clamped) of `lit` on both sides
// must differ by at most 2% of max(their mean, 5% of the mean lit texel).
SeamCheck check_seams(const mesh::Mesh& m, const std::vector<double>& lit, const std::vector<std::uint8_t>& coverage, int w, int h) {
  auto lookup = [&](glm::dvec2 uv, bool& filled) {
    const double x = uv.x * w - 0.5, y = uv.y * h - 0.5, fx = std::floor(x), fy = std::floor(y);
    double sum = 0.0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int i = std::clamp(int(fx) + dx, 0, w - 1), j = std::clamp(int(fy) + dy, 0, h - 1);
        const double weight = (dx ? x - fx : 1 - (x - fx)) * (dy ? y - fy : 1 - (y - fy));
        filled &= coverage[std::size_t(i + j * w)] != transfer::kTexelEmpty;
        sum += weight * lit[std::size_t(i + j * w)];
      }
    return sum;
  };
  double mean = 0.0;
  std::size_t covered = 0;
  for (std::size_t t = 0; t < lit.size(); ++t)
    if (coverage[t] == transfer::kTexelCovered) mean += lit[t], ++covered;
  mean /= double(std::max<std::size_t>(covered, 1));
  using Key = std::vector<float>;
  std::map<Key, std::vector<std::pair<std::uint32_t, int>>> edges;  // sorted end positions -> (triangle, corner of the lower end)
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = m.positions[m.indices[3 * t + k]], b = m.positions[m.indices[3 * t + (k + 1) % 3]];
      const bool swap = std::make_tuple(b.x, b.y, b.z) < std::make_tuple(a.x, a.y, a.z);
      const glm::vec3 lo = swap ? b : a, hi = swap ? a : b;
      edges[{lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}].push_back({t, swap ? (k + 1) % 3 : k});
    }
  SeamCheck out;
  for (const auto& [key, list] : edges) {
    if (list.size() != 2) continue;
    glm::dvec2 uv[2][2];
    bool smooth = true;
    for (int side = 0; side < 2; ++side) {
      const auto [t, lo] = list[std::size_t(side)];
      // The other end is whichever corner of t sits at the key's upper position.
      int hi = (lo + 1) % 3;
      if (m.positions[m.indices[3 * t + hi]] != glm::vec3(key[3], key[4], key[5])) hi = (lo + 2) % 3;
      uv[side][0] = m.lightmap_uv[3 * t + lo];
      uv[side][1] = m.lightmap_uv[3 * t + hi];
      const auto [t0, lo0] = list[0];
      smooth &= glm::dot(m.normals[m.indices[3 * t + lo]], m.normals[m.indices[3 * t0 + lo0]]) >= 0.99f;
    }
    if (!smooth || (uv[0][0] == uv[1][0] && uv[0][1] == uv[1][1])) continue;
    ++out.edges;
    for (int k = 0; k < 7; ++k) {
      const double s = (k + 0.5) / 7.0;
      bool filled = true;
      const double a = lookup(glm::mix(uv[0][0], uv[0][1], s), filled), b = lookup(glm::mix(uv[1][0], uv[1][1], s), filled);
      if (!filled) continue;
      ++out.points;
      const double rel = std::abs(a - b) / std::max(0.5 * (std::abs(a) + std::abs(b)), 0.05 * mean);
      out.worst = std::max(out.worst, rel);
      out.over += rel > 0.02;
    }
  }
  return out;
}

transfer::TransferData bake_stitched(const mesh::Mesh& m, int size, bool stitch) {
  bake::BakeOptions o;
  o.kind = transfer::Kind::shadowed;
  o.samples = 128;
  lightmap::LightmapOptions l;
  l.width = l.height = size;
  l.denoise = true;
  l.stitch = stitch;
  return lightmap::bake_lightmap(m, o, l);
}

void check_scene(const mesh::Mesh& m, int size) {
  const sh::RgbCoefficients env = light::project(light::load_environment(std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr"), 5);
  for (const bool stitch : {false, true}) {
    const transfer::TransferData d = bake_stitched(m, size, stitch);
    const SeamCheck c = check_seams(m, lit_texels(d, env), d.coverage, size, size);
    INFO((stitch ? "stitched: " : "not stitched: ") << c.edges << " seam edges, " << c.points << " points, " << c.over
                                                     << " over 2%, worst " << c.worst);
    REQUIRE(c.points > 100);
    if (stitch) CHECK(c.over == 0);
    else CHECK(c.over > c.points / 20);  // the check sees the seams a bake leaves
  }
}

}  // namespace

TEST_CASE("seams: a UV sphere on a floor, stitched: both sides of every seam within 2%", "[lightmap][seams]") {
  check_scene(sphere_on_floor(48, 24), 128);
}

TEST_CASE("seams: a scanned dragon with prt unwrap's charts, stitched: both sides of every seam within 2%", "[lightmap][seams]") {
  mesh::Mesh m = mesh::load_mesh(std::string(PRT_SOURCE_DIR) + "/assets/meshes/guardian_lion_10k.ply", {mesh::kDefaultScene, true});
  unwrap::UnwrapOptions u;
  u.width = u.height = 256;
  m.lightmap_uv = unwrap::unwrap(m, u);
  check_scene(m, 256);
}

}  // namespace prt
