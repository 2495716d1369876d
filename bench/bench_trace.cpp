// bench_trace: the bare Embree passes that the shadowed PRT bake is measured against.
//
// Mesh: bench::detailed_blob() (655,362 vertices, 1,310,720 triangles, deep ridged valleys). For each
// vertex, in Morton order: 1024 Fibonacci hemisphere directions rotated to the vertex frame, origin
// lifted by the offset rule, traced with Scene::occluded (rtcOccluded1M) / Scene::intersect
// (rtcIntersect1M) in batches of 256 (4 calls per vertex), vertices split over threads by
// prt::parallel_for.
// Target (a figure measured once with a bare Embree 3 loop on the Stanford dragon, 871k triangles, 256
// rays per vertex, rtcOccluded1M, Morton order; a constant here): 8.3 Mrays/s on 1 thread, 16.4 on 2.
//
// Usage: bench_trace [--full] [benchmark flags]
//   default: the passes trace every 8th vertex of the Morton order (84M rays per pass);
//   --full:  every vertex (671M rays per pass, about a minute per pass and thread count).
// Every figure is printed as a counter and again in a summary table at the end, with ratios against
// the baseline pass (occlusion, 256 rays per call, Morton order, robust) of the same run.
// Mrays/s is wall-clock throughput; Mrays/cpu_s divides by the process's CPU time, which stays
// meaningful when other processes share the cores.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "bench_meshes.h"
#include "trace/scene.h"

using namespace prt;

namespace {

constexpr double kTarget1Thread = 8.3;  // Mrays/s, the constant above (dragon, 256 rays per vertex)
constexpr double kTarget2Threads = 16.4;

struct Fixture {
  mesh::Mesh mesh;
  std::vector<std::uint32_t> morton;      // vertices traced, Morton order (every `stride`-th)
  std::vector<std::uint32_t> file_order;  // the same vertices, in index order
  std::vector<glm::vec3> directions_1024, directions_256;
  std::unique_ptr<trace::Scene> scene, scene_not_robust, scene_single_calls;
  std::map<std::string, bench::PassResult> results;  // by benchmark name, in run order below
  std::vector<std::string> run_order;
};

double mib(std::size_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void report_pass(benchmark::State& state, Fixture& f, const std::string& name, const bench::PassResult& r,
                 int threads) {
  state.SetIterationTime(r.seconds);
  state.counters["Mrays/s"] = r.mrays_per_second;
  state.counters["Mrays/cpu_s"] = r.mrays_per_cpu_second;
  state.counters["rays"] = double(r.rays);
  state.counters["target_Mrays/s"] = threads == 1 ? kTarget1Thread : kTarget2Threads;
  const std::string baseline = "occlusion/threads:" + std::to_string(threads);
  auto found = f.results.find(baseline);
  if (found != f.results.end() && found->second.mrays_per_second > 0.0)
    state.counters["x_baseline"] = r.mrays_per_second / found->second.mrays_per_second;
  if (!f.results.count(name)) f.run_order.push_back(name);
  f.results[name] = r;
}

// Registers one pass as a benchmark (one iteration: a pass is long and its time is the figure).
template <typename Pass>
void register_pass(Fixture& f, const std::string& name, int threads, Pass pass) {
  benchmark::RegisterBenchmark(name.c_str(),
                               [&f, name, threads, pass](benchmark::State& state) {
                                 for (auto _ : state) {
                                   const bench::PassResult r = pass();
                                   benchmark::DoNotOptimize(r.checksum);
                                   report_pass(state, f, name, r, threads);
                                 }
                               })
      ->Iterations(1)
      ->UseManualTime()
      ->Unit(benchmark::kSecond);
}

// The blob mesh and the vertex subsets traced: every 8th vertex in Morton order, or all with `full`.
void load_fixture(Fixture& f, bool full) {
  f.mesh = bench::detailed_blob();
  const std::vector<std::uint32_t> order = trace::morton_order(f.mesh.positions);
  const std::size_t stride = full ? 1 : 8;
  for (std::size_t i = 0; i < order.size(); i += stride) f.morton.push_back(order[i]);
  f.file_order = f.morton;
  std::sort(f.file_order.begin(), f.file_order.end());
  f.directions_1024 = bench::hemisphere_directions(1024);
  f.directions_256 = bench::hemisphere_directions(256);
}

// Scene builds: 1 and 2 build threads; the 2-thread scene is the one traced.
void register_builds(Fixture& f, std::size_t mesh_bytes) {
  for (int threads : {1, 2}) {
    const std::string name = "build/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(
        name.c_str(),
        [&f, threads, mesh_bytes](benchmark::State& state) {
          for (auto _ : state) {
            trace::SceneOptions options;
            options.build_threads = threads;
            auto scene = std::make_unique<trace::Scene>(f.mesh, options);
            const trace::SceneStats& s = scene->stats();
            state.SetIterationTime(s.build_seconds);
            state.counters["build_s"] = s.build_seconds;
            state.counters["embree_MiB"] = mib(s.embree_bytes);
            state.counters["embree_peak_MiB"] = mib(s.embree_peak_bytes);
            state.counters["mesh+bvh_peak_MiB"] = mib(s.embree_peak_bytes + s.geometry_bytes + mesh_bytes);
            state.counters["shares_positions"] = s.shares_positions ? 1 : 0;
            state.counters["target_build_s"] = 0.7;  // a constant: 0.3-0.7 s for ~1M triangles (Embree 3 MEDIUM builder)
            if (threads == 2) f.scene = std::move(scene);
          }
        })
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
}

// The baseline passes and their variants.
void register_passes(Fixture& f) {
  auto scene = [&f]() -> const trace::Scene& {
    if (!f.scene) {
      trace::SceneOptions options;
      options.build_threads = 2;
      f.scene = std::make_unique<trace::Scene>(f.mesh, options);
    }
    return *f.scene;
  };

  // The baseline: occlusion, then closest hit, on 1 and 2 threads.
  for (int threads : {1, 2}) {
    register_pass(f, "occlusion/threads:" + std::to_string(threads), threads, [&f, scene, threads] {
      return bench::occlusion_pass(scene(), f.mesh, f.morton, f.directions_1024, threads);
    });
  }
  for (int threads : {1, 2}) {
    register_pass(f, "closest_hit/threads:" + std::to_string(threads), threads, [&f, scene, threads] {
      return bench::closest_hit_pass(scene(), f.mesh, f.morton, f.directions_1024, threads);
    });
  }
  // Variants on 1 thread, as ratios to the baseline: batch size, call kind, vertex order, robust flag,
  // rays per vertex (256: the setup of the target above).
  for (std::size_t batch : {64, 1024}) {
    register_pass(f, "occlusion/batch:" + std::to_string(batch) + "/threads:1", 1, [&f, scene, batch] {
      return bench::occlusion_pass(scene(), f.mesh, f.morton, f.directions_1024, 1, batch);
    });
  }
  register_pass(f, "occlusion/single_rays/threads:1", 1, [&f] {
    if (!f.scene_single_calls) {
      trace::SceneOptions options;
      options.batch_call = trace::BatchCall::single;
      f.scene_single_calls = std::make_unique<trace::Scene>(f.mesh, options);
    }
    return bench::occlusion_pass(*f.scene_single_calls, f.mesh, f.morton, f.directions_1024, 1);
  });
  register_pass(f, "closest_hit/single_rays/threads:1", 1, [&f] {
    if (!f.scene_single_calls) {
      trace::SceneOptions options;
      options.batch_call = trace::BatchCall::single;
      f.scene_single_calls = std::make_unique<trace::Scene>(f.mesh, options);
    }
    return bench::closest_hit_pass(*f.scene_single_calls, f.mesh, f.morton, f.directions_1024, 1);
  });
  register_pass(f, "occlusion/file_order/threads:1", 1,
                [&f, scene] { return bench::occlusion_pass(scene(), f.mesh, f.file_order, f.directions_1024, 1); });
  register_pass(f, "occlusion/not_robust/threads:1", 1, [&f] {
    if (!f.scene_not_robust) {
      trace::SceneOptions options;
      options.robust = false;
      f.scene_not_robust = std::make_unique<trace::Scene>(f.mesh, options);
    }
    return bench::occlusion_pass(*f.scene_not_robust, f.mesh, f.morton, f.directions_1024, 1);
  });
  register_pass(f, "occlusion/rays_per_vertex:256/threads:1", 1,
                [&f, scene] { return bench::occlusion_pass(scene(), f.mesh, f.morton, f.directions_256, 1); });

}

// The summary table: every pass against its baseline, thread scaling, the BVH's memory.
void print_summary(const Fixture& f, bool full, std::size_t mesh_bytes) {
  std::printf("\nSummary (%s; machine shared: compare ratios within this run)\n",
              full ? "all vertices" : "every 8th vertex");
  std::printf("%-42s %10s %10s %12s %10s %10s %14s\n", "pass", "rays", "seconds", "Mrays/s", "Mrays/cpu_s", "target",
              "x baseline");
  for (const std::string& name : f.run_order) {
    const bench::PassResult& r = f.results.at(name);
    const bool two = name.find("threads:2") != std::string::npos;
    const auto base = f.results.find(two ? "occlusion/threads:2" : "occlusion/threads:1");
    const double ratio = base != f.results.end() ? r.mrays_per_second / base->second.mrays_per_second : 0.0;
    std::printf("%-42s %10zu %10.2f %12.2f %10.2f %10.1f %14.2f   checksum %llu\n", name.c_str(), r.rays, r.seconds,
                r.mrays_per_second, r.mrays_per_cpu_second, two ? kTarget2Threads : kTarget1Thread, ratio,
                static_cast<unsigned long long>(r.checksum));
  }
  for (const char* kind : {"occlusion", "closest_hit"}) {
    const auto one = f.results.find(std::string(kind) + "/threads:1"),
               two = f.results.find(std::string(kind) + "/threads:2");
    if (one != f.results.end() && two != f.results.end())
      std::printf("%s: 2 threads / 1 thread = %.2f (wall), %.2f (per CPU second)\n", kind,
                  two->second.mrays_per_second / one->second.mrays_per_second,
                  two->second.mrays_per_cpu_second / one->second.mrays_per_cpu_second);
  }
  if (f.scene) {
    const trace::SceneStats& s = f.scene->stats();
    std::printf(
        "BVH (2 build threads): %.3f s, Embree holds %.1f MiB (peak %.1f MiB), scene geometry copy %.1f MiB, "
        "mesh %.1f MiB; process peak RSS %.1f MiB\n",
        s.build_seconds, mib(s.embree_bytes), mib(s.embree_peak_bytes), mib(s.geometry_bytes), mib(mesh_bytes),
        peak_rss_mib());
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool full = false;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--full") == 0)
      full = true;
    else
      args.push_back(argv[i]);
  }
  int bench_argc = static_cast<int>(args.size());
  benchmark::Initialize(&bench_argc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bench_argc, args.data())) return 1;

  Fixture f;
  load_fixture(f, full);
  const std::size_t mesh_bytes = f.mesh.positions.size() * 2 * sizeof(glm::vec3) + f.mesh.indices.size() * 4;
  std::printf(
      "bench_trace: blob mesh %zu vertices, %zu triangles (%.1f MiB positions+normals+indices); tracing "
      "%zu vertices (%s)\n",
      f.mesh.positions.size(), f.mesh.indices.size() / 3, mib(mesh_bytes), f.morton.size(),
      full ? "--full: all" : "every 8th in Morton order; --full for all");
  register_builds(f, mesh_bytes);
  register_passes(f);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary(f, full, mesh_bytes);
  return 0;
}
