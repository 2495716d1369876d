// prt::trace::Scene against a brute-force double-precision tracer and closed-form answers.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/geometric.hpp>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench_meshes.h"
#include "core/error.h"
#include "trace/reference_tracer.h"
#include "trace/scene.h"
#include "support/random_draws.h"

using namespace prt;
using trace::testing::reference_closest_hit;

namespace {

glm::dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const glm::dvec3 d = test::draw_vec3<double>(rng, normal);
    const double length = glm::length(d);
    if (length > 1e-6) return d / length;
  }
}

// `triangles` random triangles with corners in [0,1]^3 (no degenerate ones).
mesh::Mesh random_scene(std::mt19937_64& rng, int triangles) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  mesh::Mesh m;
  while (m.indices.size() < std::size_t(3 * triangles)) {
    glm::vec3 p[3];
    for (auto& q : p) q = test::draw_vec3<float>(rng, unit);
    if (glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) < 1e-3f) continue;
    for (auto& q : p) {
      m.indices.push_back(static_cast<std::uint32_t>(m.positions.size()));
      m.positions.push_back(q);
    }
  }
  m.normals = bench::vertex_normals(m.positions, m.indices);
  return m;
}

}  // namespace

TEST_CASE("Ray, Hit and RayBatch hold Embree's layout and the rays pushed", "[trace]") {
  STATIC_REQUIRE(sizeof(trace::Ray) == 48);
  STATIC_REQUIRE(sizeof(trace::Hit) == 32);
  STATIC_REQUIRE(sizeof(trace::RayHit) == 80);
  trace::RayBatch batch(3);
  CHECK(batch.capacity() == 3);
  CHECK(batch.empty());
  CHECK(batch.push(glm::vec3(1, 2, 3), glm::vec3(0, 0, 1), 0.5f, 7.0f) == 0);
  CHECK(batch.push(glm::vec3(4, 5, 6), glm::vec3(0, 1, 0)) == 1);
  CHECK(batch.size() == 2);
  const trace::Ray& r = batch.data()[0].ray;
  CHECK(r.org_x == 1.0f);
  CHECK(r.org_z == 3.0f);
  CHECK(r.tnear == 0.5f);
  CHECK(r.dir_z == 1.0f);
  CHECK(r.tfar == 7.0f);
  CHECK(r.mask == 0xFFFFFFFFu);
  CHECK(batch.data()[1].ray.tfar == trace::kInfinity);
  batch.clear();
  CHECK(batch.size() == 0);
  CHECK(batch.capacity() == 3);
}

TEST_CASE("occluded and intersect agree with brute-force Moller-Trumbore on random scenes", "[trace]") {
  // Tolerances: Embree intersects in float, so which triangle is nearest is compared only where the
  // reference's closest hit is more than 1e-4 (in barycentrics) inside its triangle, more than 1e-4
  // (relative) before the next hit and away from tfar. The hit point is recomputed in double from the
  // triangle (trace/hit_refine.h), so t, u, v must then be the reference's double values rounded to float:
  // within 2 float ulps (Embree's own float values were up to ~1e-4 off at grazing angles).
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<float> box(-0.5f, 1.5f), length(0.2f, 3.0f), unit(0.0f, 1.0f);
  const bool robust = GENERATE(true, false);
  constexpr int kScenes = 30, kRays = 1024;
  std::size_t compared = 0, skipped = 0, hits = 0;
  for (int scene_index = 0; scene_index < kScenes; ++scene_index) {
    const mesh::Mesh m = random_scene(rng, 8 + 4 * scene_index);
    trace::SceneOptions options;
    options.robust = robust;
    options.build_threads = 1;
    const trace::Scene scene(m, options);
    trace::RayBatch occlusion(kRays), closest(kRays);
    std::vector<glm::dvec3> origins, dirs;
    std::vector<double> tfars;
    for (int ray = 0; ray < kRays; ++ray) {
      const glm::vec3 o = prt::test::draw_vec3<float>(rng, box);
      // Half the rays aim at a random point of a random triangle, half go anywhere; directions have
      // random lengths (t is in units of |dir|); half the rays end at a finite tfar.
      glm::vec3 d = glm::vec3(random_unit(rng));
      if (ray % 4 < 2) {
        const std::size_t tri = std::size_t(unit(rng) * float(m.indices.size() / 3)) % (m.indices.size() / 3);
        float a = unit(rng), b = unit(rng);
        if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
        const glm::vec3 target = m.positions[m.indices[3 * tri]] * (1.0f - a - b) +
                                 m.positions[m.indices[3 * tri + 1]] * a + m.positions[m.indices[3 * tri + 2]] * b;
        if (glm::length(target - o) > 1e-3f) d = glm::normalize(target - o);
      }
      d *= length(rng);
      const float tfar = ray % 2 ? trace::kInfinity : 2.0f * length(rng);
      occlusion.push(o, d, 0.0f, tfar);
      closest.push(o, d, 0.0f, tfar);
      origins.emplace_back(o);
      dirs.emplace_back(d);
      tfars.push_back(tfar);
    }
    scene.occluded(occlusion);
    scene.intersect(closest);
    for (int ray = 0; ray < kRays; ++ray) {
      const auto ref =
          reference_closest_hit(m, origins[ray], dirs[ray], 0.0, tfars[ray] == trace::kInfinity ? 1e300 : tfars[ray]);
      const auto ref_unbounded = reference_closest_hit(m, origins[ray], dirs[ray], 0.0, 1e300);
      const bool clear =
          ref_unbounded.edge_margin > 1e-4 && ref_unbounded.t_gap > 1e-4 * ref_unbounded.t &&
          (tfars[ray] == trace::kInfinity || std::fabs(ref_unbounded.t - tfars[ray]) > 1e-4 * tfars[ray]);
      if (ref_unbounded.hit() && !clear) {
        ++skipped;
        continue;
      }
      ++compared;
      REQUIRE(occlusion.is_occluded(ray) == ref.hit());
      const trace::HitResult h = closest.hit(ray);
      REQUIRE(h.hit() == ref.hit());
      if (!ref.hit()) continue;
      ++hits;
      REQUIRE(h.prim_id == ref.prim_id);
      REQUIRE(std::fabs(h.t - ref.t) <= 0x1p-22 * ref.t);
      REQUIRE(std::fabs(h.u - ref.u) <= 0x1p-23);
      REQUIRE(std::fabs(h.v - ref.v) <= 0x1p-23);
    }
  }
  INFO("compared " << compared << ", skipped near edges/ties " << skipped << ", hits " << hits);
  CHECK(compared == std::size_t(kScenes * kRays) - skipped);
  CHECK(skipped < std::size_t(kScenes * kRays / 100));  // edge grazes and ties are rare: < 1%
  CHECK(hits > std::size_t(kScenes * kRays / 3));       // the comparison includes plenty of hits
}

TEST_CASE("closest hits are the same bits whichever ISA Embree runs", "[trace]") {
  // Embree picks its SIMD code path at run time, and its hit distances and barycentrics differ in the last
  // bits from path to path; a bake must not. SSE4.2 runs on every x86-64 CPU this project builds for.
  const mesh::Mesh m = bench::bumpy_icosphere(3, 0.35f);
  trace::SceneOptions native, sse;
  sse.device_config = "isa=sse4.2";
  const trace::Scene a(m, native), b(m, sse);
  std::mt19937_64 rng(12);
  trace::RayBatch x(2000), y(2000);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 o(random_unit(rng) * (i % 2 ? 0.5 : 1.5)), dir(random_unit(rng) * (0.5 + 0.001 * i));
    x.push(o, dir);
    y.push(o, dir);
  }
  a.intersect(x);
  b.intersect(y);
  std::size_t hits = 0;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(std::memcmp(&x.data()[i], &y.data()[i], sizeof(trace::RayHit)) == 0);
    hits += x.hit(i).hit();
  }
  CHECK(hits > 1100);
}

TEST_CASE("stream and single-ray calls give bit-identical results", "[trace]") {
  const mesh::Mesh m = bench::bumpy_icosphere(3, 0.35f);
  trace::SceneOptions stream_options, single_options;
  single_options.batch_call = trace::BatchCall::single;
  const bool robust = GENERATE(true, false);
  stream_options.robust = single_options.robust = robust;
  const trace::Scene stream(m, stream_options), single(m, single_options);
  std::mt19937_64 rng(11);
  trace::RayBatch a(1000), b(1000), c(1000), d(1000);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 o(random_unit(rng) * (i % 2 ? 0.5 : 1.5)), dir(random_unit(rng));  // inside / outside
    for (trace::RayBatch* batch : {&a, &b, &c, &d}) batch->push(o, dir);
  }
  stream.occluded(a);
  single.occluded(b);
  stream.intersect(c);
  single.intersect(d);
  std::size_t hits = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(a.is_occluded(i) == b.is_occluded(i));
    REQUIRE(c.hit(i).prim_id == d.hit(i).prim_id);
    REQUIRE(std::memcmp(&c.data()[i], &d.data()[i], sizeof(trace::RayHit)) == 0);
    hits += c.hit(i).hit();
  }
  CHECK(hits > 550);
}

TEST_CASE("a ray from inside a closed box always hits the wall at the slab distance", "[trace]") {
  const glm::vec3 lo(-1.0f, -0.5f, -2.0f), hi(2.0f, 1.5f, 0.5f);
  const mesh::Mesh m = bench::box(lo, hi, 3);
  const trace::Scene scene(m);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  trace::RayBatch occlusion(1000), closest(1000);
  std::vector<double> expected_t(1000);
  std::vector<int> expected_axis(1000);
  for (int ray = 0; ray < 1000; ++ray) {
    const glm::dvec3 o = glm::dvec3(lo) + glm::dvec3(hi - lo) * test::draw_vec3<double>(rng, unit);
    const glm::dvec3 d = random_unit(rng);
    // Slab method: the exit distance is the smallest positive distance to a wall plane.
    expected_t[ray] = 1e300;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0) continue;
      const double t = ((d[a] > 0.0 ? hi[a] : lo[a]) - o[a]) / d[a];
      if (t < expected_t[ray]) {
        expected_t[ray] = t;
        expected_axis[ray] = a;
      }
    }
    occlusion.push(glm::vec3(o), glm::vec3(d));
    closest.push(glm::vec3(o), glm::vec3(d));
  }
  scene.occluded(occlusion);
  scene.intersect(closest);
  CHECK(occlusion.occluded_count() == 1000);
  for (int ray = 0; ray < 1000; ++ray) {
    const trace::HitResult h = closest.hit(ray);
    REQUIRE(h.hit());
    REQUIRE(h.t == Approx(expected_t[ray]).epsilon(1e-5));
    // Faces are emitted in order -X, +X, -Y, +Y, -Z, +Z with 2 * 3 * 3 triangles each.
    REQUIRE(int(h.prim_id / 18) / 2 == expected_axis[ray]);
  }
}

TEST_CASE("tnear and tfar bound the segment", "[trace]") {
  // A unit square at z = 1 (two triangles), rays along +z from the origin region.
  mesh::Mesh m;
  m.positions = {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  m.normals.assign(4, glm::vec3(0, 0, -1));
  m.indices = {0, 1, 2, 0, 2, 3};
  const trace::Scene scene(m);
  trace::RayBatch batch(4);
  const glm::vec3 o(0.2f, 0.1f, 0.0f);
  batch.push(o, glm::vec3(0, 0, 1), 0.0f, 0.999f);  // ends before the square
  batch.push(o, glm::vec3(0, 0, 1), 0.0f, 1.001f);  // reaches it
  batch.push(o, glm::vec3(0, 0, 1), 1.001f, 5.0f);  // starts past it
  batch.push(o, glm::vec3(0, 0, 2), 0.0f, 0.501f);  // t in units of |dir|
  trace::RayBatch closest = batch;
  scene.occluded(batch);
  CHECK_FALSE(batch.is_occluded(0));
  CHECK(batch.is_occluded(1));
  CHECK_FALSE(batch.is_occluded(2));
  CHECK(batch.is_occluded(3));
  CHECK(batch.occluded_count() == 2);
  scene.intersect(closest);
  CHECK_FALSE(closest.hit(0).hit());
  CHECK(closest.hit(0).prim_id == trace::kNoHit);
  CHECK(closest.hit(1).t == Approx(1.0f).epsilon(1e-6));
  CHECK(closest.hit(3).t == Approx(0.5f).epsilon(1e-6));
  // (0.2, 0.1) lies in triangle 0 (corners 0, 1, 2): point = (1-u-v) p0 + u p1 + v p2 gives
  // x = -1 + 2u + 2v = 0.2, y = -1 + 2v = 0.1, so u = 0.05, v = 0.55.
  CHECK(closest.hit(1).prim_id == 0);
  CHECK(closest.hit(1).u == Approx(0.05).margin(1e-6));
  CHECK(closest.hit(1).v == Approx(0.55).margin(1e-6));
  // Counter-clockwise seen from +z: the geometric normal points to +z, its length is twice the area.
  CHECK(closest.hit(1).ng.x == Approx(0.0).margin(1e-6));
  CHECK(closest.hit(1).ng.z == Approx(4.0));
}

TEST_CASE("the vertex buffer is shared when the positions have slack, else copied, results agree", "[trace]") {
  mesh::Mesh exact = bench::icosphere(2);
  exact.positions.shrink_to_fit();
  mesh::Mesh slack = exact;
  slack.positions.reserve(slack.positions.size() + 1);
  const trace::Scene copied(exact), shared(slack);
  if (exact.positions.capacity() == exact.positions.size()) CHECK_FALSE(copied.stats().shares_positions);
  CHECK(shared.stats().shares_positions);
  CHECK(copied.triangle_count() == 320);
  CHECK(copied.stats().embree_bytes > 0);
  CHECK(copied.stats().embree_peak_bytes >= copied.stats().embree_bytes);
  std::mt19937_64 rng(3);
  trace::RayBatch a(256), b(256);
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 d(random_unit(rng));
    a.push(glm::vec3(0.0f), d);
    b.push(glm::vec3(0.0f), d);
  }
  copied.intersect(a);
  shared.intersect(b);
  for (int i = 0; i < 256; ++i) {
    REQUIRE(a.hit(i).prim_id == b.hit(i).prim_id);
    REQUIRE(a.hit(i).t == b.hit(i).t);
    REQUIRE(a.hit(i).t == Approx(1.0).margin(0.1));  // level-2 icosphere: chords within 0.1 of radius 1
  }
}

TEST_CASE("invalid meshes are rejected with prt::Error, an empty mesh misses everything", "[trace]") {
  mesh::Mesh m = bench::icosphere(0);
  mesh::Mesh bad_index = m;
  bad_index.indices[5] = 12;
  CHECK_THROWS_WITH(trace::Scene(bad_index), Catch::Contains("trace: triangle 1 refers to vertex 12 of 12"));
  mesh::Mesh bad_count = m;
  bad_count.indices.pop_back();
  CHECK_THROWS_AS(trace::Scene(bad_count), prt::Error);
  mesh::Mesh bad_position = m;
  bad_position.positions[3].y = std::nanf("");
  CHECK_THROWS_WITH(trace::Scene(bad_position), Catch::Contains("vertex 3 has a non-finite position"));

  const mesh::Mesh empty;
  const trace::Scene scene(empty);
  CHECK(scene.triangle_count() == 0);
  CHECK(scene.ray_offset() == 0.0f);
  trace::RayBatch batch(2);
  batch.push(glm::vec3(0.0f), glm::vec3(1, 0, 0));
  trace::RayBatch closest = batch;
  scene.occluded(batch);
  scene.intersect(closest);
  CHECK_FALSE(batch.is_occluded(0));
  CHECK_FALSE(closest.hit(0).hit());
}

TEST_CASE("morton_order is a deterministic, spatially sorted permutation", "[trace]") {
  const glm::vec3 lo(0.0f), hi(1.0f);
  CHECK(trace::morton_code(lo, lo, hi) == 0u);
  CHECK(trace::morton_code(hi, lo, hi) == (1u << 30) - 1u);
  CHECK(trace::morton_code(glm::vec3(1, 0, 0), lo, hi) == 0x24924924u);  // x owns the top bit of each triple
  CHECK(trace::morton_code(glm::vec3(0, 1, 0), lo, hi) == 0x12492492u);
  CHECK(trace::morton_code(glm::vec3(0, 0, 1), lo, hi) == 0x09249249u);
  CHECK(trace::morton_code(glm::vec3(2, -1, 0.5f), lo, hi) == trace::morton_code(glm::vec3(1, 0, 0.5f), lo, hi));

  const mesh::Mesh m = bench::bumpy_icosphere(4, 0.3f);
  const auto order = trace::morton_order(m.positions);
  REQUIRE(order.size() == m.positions.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint32_t> identity(order.size());
  std::iota(identity.begin(), identity.end(), 0u);
  CHECK(sorted == identity);
  CHECK(trace::morton_order(m.positions) == order);
  glm::vec3 blo = m.positions[0], bhi = m.positions[0];
  for (const auto& p : m.positions) {
    blo = glm::min(blo, p);
    bhi = glm::max(bhi, p);
  }
  for (std::size_t i = 1; i < order.size(); ++i) {
    const auto c0 = trace::morton_code(m.positions[order[i - 1]], blo, bhi);
    const auto c1 = trace::morton_code(m.positions[order[i]], blo, bhi);
    REQUIRE(c0 <= c1);
    if (c0 == c1) REQUIRE(order[i - 1] < order[i]);  // stable: equal codes keep index order
  }
  // Spatial coherence: consecutive vertices are far closer than random pairs (mean distance).
  double consecutive = 0.0;
  for (std::size_t i = 1; i < order.size(); ++i)
    consecutive += glm::length(m.positions[order[i]] - m.positions[order[i - 1]]);
  consecutive /= double(order.size() - 1);
  CHECK(consecutive < 0.2);  // edges are ~0.06 long; random pairs on the sphere are ~1.3 apart
  CHECK(trace::morton_order({}).empty());
}
