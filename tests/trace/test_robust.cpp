// RTC_SCENE_FLAG_ROBUST and the ray-origin rule (scene.h, RAY OFFSET): what robust mode changes in the
// occlusion answers of vertex rays, against the exact double-precision answers (leak_count.h).
//
// The hidden test "[.leaks]" prints the leak study of docs/conventions.md ("Robust mode"):
//   test_trace "[.leaks]"
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_meshes.h"
#include "mesh/mesh.h"
#include "sh/sampling.h"
#include "trace/leak_count.h"
#include "trace/scene.h"

using namespace prt;
using trace::testing::Spawn;

namespace {

trace::Scene make_scene(const mesh::Mesh& m, bool robust) {
  trace::SceneOptions options;
  options.robust = robust;
  return trace::Scene(m, options);
}

mesh::Mesh asset(const char* name) {
  mesh::Mesh m = mesh::load_mesh(std::string(PRT_SOURCE_DIR) + "/assets/meshes/" + name, nullptr, true);
  m.positions.reserve(m.positions.size() + 1);
  return m;
}

}  // namespace

TEST_CASE("leak study: robust mode and origin rules against the exact answers", "[.leaks]") {
  const auto dirs = trace::testing::test_directions(64);
  std::vector<trace::testing::StudyCase> cases;
  cases.push_back({"icosphere L4", bench::icosphere(4), 1});
  cases.push_back({"bumpy icosphere L4", bench::bumpy_icosphere(4, 0.35f), 1});
  cases.push_back({"cup (open box, smooth creases)", bench::open_box(glm::vec3(0.0f), glm::vec3(1.0f), 8), 1});
  cases.push_back({"Cornell box (blocks on the floor)", bench::cornell_box(6), 1});
  {
    mesh::Mesh moved = bench::cornell_box(6);
    for (glm::vec3& p : moved.positions) p += glm::vec3(3.0f, 5.0f, -7.0f);
    cases.push_back({"Cornell box moved to (3, 5, -7)", std::move(moved), 1});
  }
  cases.push_back({"guardian lion 10k", asset("guardian_lion_10k.ply"), 4});
  cases.push_back({"armadillo", asset("armadillo.ply"), 20});
  cases.push_back({"bumpy icosphere L6 (blob class)", bench::bumpy_icosphere(6, 0.35f), 40});
  struct Rule {
    const char* name;
    bool robust, own_rule;
    double pullback;  // of every ray, in ray offsets (own_rule false)
  };
  const Rule rules[] = {{"robust, lift (main)", true, false, 0.0},
                        {"fast, lift", false, false, 0.0},
                        {"fast, contacts robust (prt)", false, true, 0.0},
                        {"fast, lift + pullback eps/16", false, false, 1.0 / 16},
                        {"fast, lift + pullback eps/4", false, false, 0.25},
                        {"fast, lift + pullback eps", false, false, 1.0}};
  for (const trace::testing::StudyCase& c : cases) {
    const trace::Scene robust = make_scene(c.m, true), fast = make_scene(c.m, false);
    const double D = trace::testing::diagonal(robust);
    const auto exact = trace::testing::exact_occlusion(c.m, dirs, D, c.stride);
    std::size_t contacts = 0;
    for (std::size_t v = 0; v < c.m.positions.size(); ++v) contacts += fast.spawn_point(c.m.positions[v], c.m.normals[v]).robust;
    std::printf("%s (%zu vertices, every %zu-th; %zu traced robust by the contact rule)\n", c.name.c_str(),
                c.m.positions.size(), c.stride, contacts);
    for (const Rule& r : rules) {
      Spawn s;
      s.own_rule = r.own_rule;
      s.lift = robust.ray_offset();
      s.pullback = float(r.pullback * robust.ray_offset());
      const auto d = trace::testing::compare(r.robust ? robust : fast, c.m, dirs, exact, s, c.stride);
      std::printf("  %-32s self-hits %8.5f%%   leaks %8.5f%%   (%zu rays, %zu truly occluded)\n", r.name,
                  100.0 * double(d.self_hits) / double(d.rays), 100.0 * double(d.leaks) / double(d.rays), d.rays,
                  d.truly_occluded);
    }
    // Every vertex, against main's rule: exact answers only where the two differ.
    Spawn main_rule;
    main_rule.own_rule = false;
    main_rule.lift = robust.ray_offset();
    const auto all = trace::testing::compare_all(robust, main_rule, fast, Spawn{}, c.m, dirs);
    std::printf("  all %zu rays, prt against main: %zu answers differ; %+lld self-hits, %+lld leaks\n", all.rays,
                all.differing, all.extra_self_hits, all.extra_leaks);
    std::fflush(stdout);
  }
  SUCCEED();
}

TEST_CASE("without robust mode, the contact rule keeps the exact answers where a block stands on a floor", "[trace]") {
  // Truth: the double-precision brute-force tracer (leak_count.h). The Cornell box's blocks stand on
  // the floor y = 0: the lifted origins of their 24 bottom-row side vertices (4 faces x 3 per block)
  // lie exactly in the floor's plane, inside it, and half their rays enter the floor at t = 0. Moved
  // off the origin (the floor at y = 5) the same holds at float resolution.
  const auto dirs = trace::testing::test_directions(64);
  for (const glm::vec3 shift : {glm::vec3(0.0f), glm::vec3(3.0f, 5.0f, -7.0f)}) {
    mesh::Mesh m = bench::cornell_box(6);
    for (glm::vec3& p : m.positions) p += shift;
    INFO("shifted by " << shift.x << ", " << shift.y << ", " << shift.z);
    const trace::Scene with_rule = make_scene(m, false);
    trace::SceneOptions off;
    off.robust = false;
    off.contact_rule = false;
    const trace::Scene without_rule(m, off);
    std::size_t contacts = 0, on_floor = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      const bool robust = with_rule.spawn_point(m.positions[v], m.normals[v]).robust;
      contacts += robust;
      // The bottom rows of the blocks' side faces: y on the floor, normal horizontal.
      const bool side_bottom = m.positions[v].y == shift.y && m.normals[v].y == 0.0f;
      on_floor += robust && side_bottom;
      CHECK_FALSE(without_rule.spawn_point(m.positions[v], m.normals[v]).robust);
    }
    CHECK(contacts == 24);
    CHECK(on_floor == 24);
    const auto exact = trace::testing::exact_occlusion(m, dirs, trace::testing::diagonal(with_rule), 1);
    const auto rule = trace::testing::compare(with_rule, m, dirs, exact, Spawn{}, 1);
    const auto none = trace::testing::compare(without_rule, m, dirs, exact, Spawn{}, 1);
    INFO("rays " << rule.rays << ", truly occluded " << rule.truly_occluded << "; leaks with the rule " << rule.leaks
                 << ", without " << none.leaks);
    REQUIRE(rule.truly_occluded > rule.rays / 2);
    CHECK(rule.self_hits == 0);
    CHECK(rule.leaks == 0);
    CHECK(none.leaks > rule.rays / 50);  // what the rule buys: 24 vertices x half their rays
  }
}

TEST_CASE("a contact point's batches, traced ray by ray, give a robust scene's answers", "[trace]") {
  // Scene::occluded traces a robust batch of a scene without robust mode (a contact point's) with one
  // rtcOccluded1 per ray: rtcOccluded1M is pathologically slow for rays that start in a surface. The
  // answers must be those of a robust scene's stream and single calls, ray for ray. The Cornell box's
  // 24 contact vertices start in the floor's plane: robust mode finds the floor at t = 0 for every ray.
  const std::vector<glm::vec3> dirs = trace::testing::test_directions(248);  // + 8 grazing: 256 rays
  for (const glm::vec3 shift : {glm::vec3(0.0f), glm::vec3(3.0f, 5.0f, -7.0f)}) {
    mesh::Mesh m = bench::cornell_box(12);
    for (glm::vec3& p : m.positions) p += shift;
    INFO("shifted by " << shift.x << ", " << shift.y << ", " << shift.z);
    const trace::Scene fast = make_scene(m, false), robust = make_scene(m, true);
    trace::SceneOptions single_options;
    single_options.batch_call = trace::BatchCall::single;
    const trace::Scene robust_single(m, single_options);
    trace::RayBatch contact(dirs.size()), stream(dirs.size()), single(dirs.size()), not_robust(dirs.size());
    std::size_t contacts = 0, occluded = 0, differ_from_fast = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      const trace::SpawnPoint s = fast.spawn_point(m.positions[v], m.normals[v]);
      if (!s.robust) continue;
      ++contacts;
      for (trace::RayBatch* b : {&contact, &stream, &single, &not_robust}) {
        b->clear();
        for (const glm::vec3& d : dirs) b->push(s.origin, trace::testing::vertex_direction(m, v, d));
      }
      contact.set_robust(true);
      fast.occluded(contact);
      robust.occluded(stream);
      robust_single.occluded(single);
      fast.occluded(not_robust);
      for (std::size_t i = 0; i < dirs.size(); ++i) {
        REQUIRE(contact.is_occluded(i) == stream.is_occluded(i));
        REQUIRE(contact.is_occluded(i) == single.is_occluded(i));
        occluded += contact.is_occluded(i);
        differ_from_fast += contact.is_occluded(i) != not_robust.is_occluded(i);
      }
    }
    CHECK(contacts == 24);
    CHECK(occluded == contacts * dirs.size());
    CHECK(differ_from_fast > contacts * dirs.size() / 4);  // robust mode changes these answers
  }
}

TEST_CASE("the contact rule flags few vertices of meshes without contacts and loses nothing to robust mode", "[trace]") {
  // On meshes without contacts (nearly) every vertex is traced without robust mode (the lion: 4 of
  // 10,000 vertices flagged, at folds where the normal grazes a face of its own); the answers must be no
  // worse than those of a robust scene: where the two differ the exact answer decides which is wrong.
  const auto dirs = trace::testing::test_directions(32);
  struct Case {
    const char* name;
    mesh::Mesh m;
  };
  std::vector<Case> cases;
  cases.push_back({"bumpy icosphere level 4", bench::bumpy_icosphere(4, 0.35f)});
  cases.push_back({"cup (smooth creases)", bench::open_box(glm::vec3(0.0f), glm::vec3(1.0f), 8)});
  cases.push_back({"guardian lion", asset("guardian_lion_10k.ply")});
  for (const Case& c : cases) {
    INFO(c.name);
    const trace::Scene robust = make_scene(c.m, true), fast = make_scene(c.m, false);
    std::size_t contacts = 0;
    for (std::size_t v = 0; v < c.m.positions.size(); ++v) contacts += fast.spawn_point(c.m.positions[v], c.m.normals[v]).robust;
    INFO(contacts << " of " << c.m.positions.size() << " vertices traced robust");
    CHECK(contacts <= c.m.positions.size() / 1000);
    Spawn main_rule;
    main_rule.own_rule = false;
    main_rule.lift = robust.ray_offset();
    const auto diff = trace::testing::compare_all(robust, main_rule, fast, Spawn{}, c.m, dirs);
    INFO(diff.rays << " rays, " << diff.differing << " answers differ: " << diff.extra_self_hits << " more self-hits, "
                   << diff.extra_leaks << " more leaks");
    CHECK(diff.extra_leaks <= 0);
    CHECK(diff.extra_self_hits <= 0);
  }
}

TEST_CASE("closest-hit study: what robust mode changes in the hits of vertex rays", "[.leaks]") {
  // Closest hits (the bounce passes) of the same rays in a robust and a non-robust scene; where they
  // name different triangles, the exact closest hit decides which one is wrong.
  const auto dirs = trace::testing::test_directions(64);
  struct Case {
    std::string name;
    mesh::Mesh m;
  };
  std::vector<Case> cases;
  cases.push_back({"guardian lion 10k", asset("guardian_lion_10k.ply")});
  cases.push_back({"armadillo", asset("armadillo.ply")});
  cases.push_back({"bumpy icosphere L6", bench::bumpy_icosphere(6, 0.35f)});
  for (const Case& c : cases) {
    const trace::Scene robust = make_scene(c.m, true), fast = make_scene(c.m, false);
    const double D = trace::testing::diagonal(robust);
    trace::RayBatch br(dirs.size()), bf(dirs.size());
    std::size_t rays = 0, differ = 0, robust_wrong = 0, fast_wrong = 0, fast_miss = 0;
    for (std::size_t v = 0; v < c.m.positions.size(); ++v) {
      trace::testing::push_vertex_rays(robust, c.m, v, dirs, Spawn{}, br);
      trace::testing::push_vertex_rays(fast, c.m, v, dirs, Spawn{}, bf);
      robust.intersect(br);
      fast.intersect(bf);
      rays += dirs.size();
      for (std::size_t k = 0; k < dirs.size(); ++k) {
        const trace::HitResult hr = br.hit(k), hf = bf.hit(k);
        if (hr.prim_id == hf.prim_id) continue;
        ++differ;
        const glm::dvec3 o = glm::dvec3(c.m.positions[v]) + glm::dvec3(c.m.normals[v]) * (1e-9 * D);
        const auto truth = trace::testing::reference_closest_hit(c.m, o, glm::dvec3(br.direction(k)), 0.0, 1e300);
        // Wrong: not the exact triangle and not at the exact distance (an edge hit may name either side).
        auto wrong = [&](const trace::HitResult& h) {
          if (h.prim_id == truth.prim_id) return false;
          return !h.hit() || std::abs(double(h.t) - truth.t) > 1e-6 * D;
        };
        robust_wrong += wrong(hr);
        fast_wrong += wrong(hf);
        fast_miss += !hf.hit() && truth.hit();
      }
    }
    std::printf("%s: %zu rays, %zu name different triangles; wrong: robust %zu, not robust %zu (%zu of them misses)\n",
                c.name.c_str(), rays, differ, robust_wrong, fast_wrong, fast_miss);
    std::fflush(stdout);
  }
  SUCCEED();
}

TEST_CASE("bake-ray study: where robust mode and the contact rule disagree on a scan's bake rays", "[.leaks]") {
  // The diffuse bake's own rays (1024 cosine directions, seed 1, sh::vertex_frame per vertex, the
  // area-weighted normals `prt bake` computes for a PLY without normals) on the armadillo scan.
  mesh::Mesh m = asset("armadillo.ply");
  const std::vector<glm::dvec3> cosine = sh::hemisphere_directions_cosine(1024, 1);
  std::vector<glm::vec3> local(cosine.begin(), cosine.end());
  const trace::Scene robust = make_scene(m, true), fast = make_scene(m, false);
  const double D = trace::testing::diagonal(robust);
  trace::RayBatch br(local.size()), bf(local.size());
  std::size_t differ = 0, robust_right = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const glm::mat3 frame = sh::vertex_frame(m.normals[v], 1, v);
    const trace::SpawnPoint s = fast.spawn_point(m.positions[v], m.normals[v]);
    br.clear();
    bf.clear();
    bf.set_robust(s.robust);
    for (const glm::vec3& l : local) {
      br.push(robust.offset_origin(m.positions[v], m.normals[v]), frame * l);
      bf.push(s.origin, frame * l);
    }
    robust.occluded(br);
    fast.occluded(bf);
    for (std::size_t k = 0; k < local.size(); ++k) {
      if (br.is_occluded(k) == bf.is_occluded(k)) continue;
      ++differ;
      const glm::dvec3 o = glm::dvec3(m.positions[v]) + glm::dvec3(m.normals[v]) * (1e-9 * D);
      const glm::dvec3 d(br.direction(k));
      const bool truth = trace::testing::reference_occluded(m, o, d, 0.0, 1e300);
      robust_right += br.is_occluded(k) == truth;
      const auto hit = trace::testing::reference_closest_hit(m, o, d, 0.0, 1e300);
      std::printf("vertex %zu ray %zu: robust %d, prt %d, exact %d (exact hit t = %.3g D, edge margin %.3g, d.n = %.3g)\n", v, k,
                  int(br.is_occluded(k)), int(bf.is_occluded(k)), int(truth), hit.t / D, hit.edge_margin,
                  double(glm::dot(br.direction(k), m.normals[v])));
    }
  }
  std::printf("armadillo bake rays: %zu of %zu differ, robust right in %zu\n", differ, m.positions.size() * local.size(),
              robust_right);
  SUCCEED();
}
