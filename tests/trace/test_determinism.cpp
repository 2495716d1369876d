// Results of occluded / intersect are bit-identical across BVH build thread counts, repeated builds and
// the number of threads that trace.
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <glm/geometric.hpp>
#include <random>
#include <vector>

#include "bench_meshes.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "sh/sampling.h"
#include "trace/scene.h"
#include "trace/vertex_rays.h"
#include "support/random_draws.h"

using namespace prt;

namespace {

// Every result bit of a pass: occlusion flags and closest-hit (prim_id, t, u, v) per ray.
struct Results {
  std::vector<std::uint8_t> occluded;
  std::vector<std::uint32_t> prim_id;
  std::vector<float> t, u, v;
};

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Rays: from every vertex (offset origin) 4 directions in the upper hemisphere, and as many through
// the mesh's bounds in random directions; rays/1024 batches traced by `threads` workers.
Results trace_all(const trace::Scene& scene, const mesh::Mesh& m, int threads) {
  const std::size_t per_vertex = 4;
  const std::size_t count = m.positions.size() * per_vertex * 2;
  Results r;
  r.occluded.resize(count);
  r.prim_id.resize(count);
  r.t.resize(count);
  r.u.resize(count);
  r.v.resize(count);
  const auto dirs = bench::hemisphere_directions(per_vertex);
  const std::size_t batch_size = 1024;
  parallel_for((count + batch_size - 1) / batch_size, 1, threads, [&](std::size_t b0, std::size_t b1) {
    trace::RayBatch occlusion(batch_size), closest(batch_size);
    for (std::size_t b = b0; b < b1; ++b) {
      occlusion.clear();
      closest.clear();
      const std::size_t begin = b * batch_size, end = std::min(count, begin + batch_size);
      for (std::size_t i = begin; i < end; ++i) {
        glm::vec3 o, d;
        const std::size_t v = (i / per_vertex) % m.positions.size();
        if (i < count / 2) {
          glm::vec3 t, bt;
          bench::orthonormal_frame(m.normals[v], t, bt);
          const glm::vec3& l = dirs[i % per_vertex];
          o = scene.offset_origin(m.positions[v], m.normals[v]);
          d = t * l.x + bt * l.y + m.normals[v] * l.z;
        } else {
          // Counter-based random ray i: independent of which thread builds it.
          std::mt19937 rng(static_cast<std::uint32_t>(i));
          std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
          o = test::draw_vec3<float>(rng, unit);
          d = glm::normalize(test::draw_vec3<float>(rng, unit) + glm::vec3(1e-3f));
        }
        occlusion.push(o, d);
        closest.push(o, d);
      }
      scene.occluded(occlusion);
      scene.intersect(closest);
      for (std::size_t i = begin; i < end; ++i) {
        r.occluded[i] = occlusion.is_occluded(i - begin);
        const trace::HitResult h = closest.hit(i - begin);
        r.prim_id[i] = h.prim_id;
        r.t[i] = h.t;
        r.u[i] = h.u;
        r.v[i] = h.v;
      }
    }
  });
  return r;
}

}  // namespace

TEST_CASE("results are identical for 1 and 2 build threads, repeated builds and 1 or 2 tracing threads", "[trace]") {
  // 40,962 vertices, 81,920 triangles, 327,696 rays (half from the surface, half through the volume).
  const mesh::Mesh m = bench::bumpy_icosphere(6, 0.35f);
  trace::SceneOptions one, two;
  one.build_threads = 1;
  two.build_threads = 2;
  const trace::Scene scene1(m, one);
  const Results reference = trace_all(scene1, m, 1);
  std::size_t occluded = 0, hits = 0;
  for (std::size_t i = 0; i < reference.occluded.size(); ++i) {
    occluded += reference.occluded[i];
    hits += reference.prim_id[i] != trace::kNoHit;
  }
  CHECK(occluded == hits);  // occlusion and closest hit see the same triangles
  CHECK(occluded > reference.occluded.size() / 5);

  auto check_same = [&](const Results& r) {
    CHECK(r.occluded == reference.occluded);
    CHECK(r.prim_id == reference.prim_id);
    CHECK(same_bits(r.t, reference.t));
    CHECK(same_bits(r.u, reference.u));
    CHECK(same_bits(r.v, reference.v));
  };
  INFO("1 build thread, traced by 2 threads");
  check_same(trace_all(scene1, m, 2));
  {
    INFO("2 build threads, traced by 2 threads");
    const trace::Scene scene2(m, two);
    check_same(trace_all(scene2, m, 2));
  }
  {
    INFO("2 build threads, built again, traced by 1 thread");
    const trace::Scene scene2_again(m, two);
    check_same(trace_all(scene2_again, m, 1));
  }
  {
    INFO("all hardware threads");
    const trace::Scene scene_all(m);
    check_same(trace_all(scene_all, m, 2));
  }
}

TEST_CASE("without robust mode the per-vertex loop is identical for any thread count, contact points included", "[trace]") {
  // The Cornell box's contact vertices go through the robust scene that the first of them builds
  // (Scene::spawn_point): whichever thread builds it, every answer must be the same.
  const mesh::Mesh m = bench::cornell_box(12);
  const std::vector<glm::vec3> local = bench::hemisphere_directions(300);
  const std::vector<std::uint32_t> order = trace::morton_order(m.positions);
  auto trace_with = [&](int build_threads, int threads) {
    trace::SceneOptions options;
    options.build_threads = build_threads;
    options.robust = false;
    const trace::Scene scene(m, options);
    trace::VertexRays rays{&scene, &m, &order, &local, 7u, threads, trace::Query::occluded};
    std::vector<std::uint8_t> occluded(m.positions.size() * local.size());
    struct Worker {
      std::vector<std::uint8_t>* out;
      std::size_t samples;
      void start(std::uint32_t, const glm::mat3&) {}
      void batch(std::uint32_t v, const trace::RayBatch& b, std::size_t first) {
        for (std::size_t k = 0; k < b.size(); ++k) (*out)[v * samples + first + k] = b.is_occluded(k);
      }
      void finish(std::uint32_t, const glm::mat3&) {}
    };
    Progress progress("test", "vertices", order.size(), false);
    trace::trace_vertex_rays(rays, progress, [&] { return Worker{&occluded, local.size()}; });
    return occluded;
  };
  {
    trace::SceneOptions options;
    options.robust = false;
    const trace::Scene scene(m, options);
    std::size_t contacts = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) contacts += scene.spawn_point(m.positions[v], m.normals[v]).robust;
    CHECK(contacts == 24);  // the blocks' bottom-row side vertices (test_robust.cpp)
  }
  const std::vector<std::uint8_t> reference = trace_with(1, 1);
  std::size_t count = 0;
  for (std::uint8_t o : reference) count += o;
  CHECK(count > reference.size() / 4);  // the room (open at +Z) and the blocks shadow
  {
    // The loop's rays are each vertex's own: from its spawn point, in its frame (traced here one
    // vertex at a time).
    trace::SceneOptions options;
    options.robust = false;
    const trace::Scene scene(m, options);
    trace::RayBatch batch(local.size());
    std::size_t differ = 0;
    for (std::uint32_t v = 0; v < m.positions.size(); ++v) {
      const trace::SpawnPoint spawn = scene.spawn_point(m.positions[v], m.normals[v]);
      const glm::mat3 frame = sh::vertex_frame(m.normals[v], 7u, v);
      batch.clear();
      batch.set_robust(spawn.robust);
      for (const glm::vec3& d : local) batch.push(spawn.origin, frame * d);
      scene.occluded(batch);
      for (std::size_t k = 0; k < local.size(); ++k) differ += reference[v * local.size() + k] != batch.is_occluded(k);
    }
    CHECK(differ == 0);
  }
  CHECK(trace_with(2, 2) == reference);
  CHECK(trace_with(0, 5) == reference);
}
