// bench_bake: the diffuse PRT bake against the bare Embree passes over the same rays, in one run.
//
// Mesh: bench::detailed_blob() (655,362 vertices, 1,310,720 triangles, deep ridged valleys), or
// bench::bumpy_icosphere(L, 0.35) with --level L < 8, or the Cornell box with --cornell C.
// Rays: the baker's own: S cosine-weighted Owen-scrambled Sobol directions per vertex, turned into the
// vertex's frame sh::vertex_frame (turned about the normal by a hashed angle per vertex), Morton order,
// batches of 256. The bare passes trace exactly these (bench::PassFrames::bake). One frame per normal
// instead (bench::orthonormal_frame, what they traced until issue 15's second round) makes neighbouring
// vertices of a flat wall trace nearly the same rays, which Embree's caches reward: on the Cornell box
// at 437k vertices that bare pass takes 1/1.33 of the CPU time of the bake's rays (paired per block of
// 2048 vertices, 1 thread), on the blob class 1/1.01 (issue 15's first round measured the bake at
// 1.19-1.61x that pass on the Cornell box).
// Targets (issue 3):
//   shadowed bake <= 1.25 x the bare occlusion pass (rtcOccluded1M) over the same rays, and (issue 15)
//   <= 1.15 x the same bare pass without RTC_SCENE_FLAG_ROBUST (both bare baselines are printed);
//   each interreflection pass <= 1.5 x a bare closest-hit pass (rtcIntersect1M) over its rays;
//   peak memory of `prt bake --transfer shadowed` <= 1.3 x (mesh + BVH + output), measured by running
//   the real binary on the mesh written as PLY (ru_maxrss of the child).
// Usage: bench_bake [--samples S] [--bands N] [--threads T] [--level L | --cornell C] [--no-memory] [--no-bounce]
//                   [--paired B]
//   --cornell C: bench::cornell_box(C) instead of the blob (blocks standing on the floor: contact vertices;
//   C = 295 gives 435,824 vertices, the 437k class).
//   --no-bounce: no closest-hit passes and no interreflected bake (the 437k class takes minutes a pass).
//   --paired B: instead of all that, the shadowed pass against the bare non-robust loop over the same rays,
//   alternated per block of B vertices on one thread (paired_blocks below; B = 2048 for the figures).
// The bake's scene is built without RTC_SCENE_FLAG_ROBUST (bake::bake_scene_options; robust mode only for
// the rays of points that touch another surface, trace/scene.h ROBUST MODE); the bare passes are the same
// rays without any per-point work. The robust bare pass traces the contact vertices' rays with
// rtcOccluded1M, pathologically slow for them (the last line of the output; 1.7 CPU seconds at 437k).
// A timed program, not Google Benchmark: each pass takes tens of seconds and is run once; the machine
// is shared, so the figures that matter are the ratios of passes measured back to back.
//
// Issue 15 figures, shadowed bake / bare non-robust occlusion over the same rays (1024 samples, 5 bands;
// Intel Xeon (Emerald Rapids, 2 vCPUs under KVM), shared with other builds: load 2-4). Whole process,
// 2 threads, medians of 5 runs (4 at 437k), wall / CPU; and paired per block of Morton-ordered vertices,
// 1 thread, whole mesh (the load drifts the same for both; spread of 2-3 runs):
//   mesh                          before (main's bake)           after
//   Cornell C = 64 (20,717 v.)    1.22 / 1.17; paired 1.13-1.17  1.04 / 1.06; paired 1.03-1.07
//   Cornell C = 295 (435,824 v.)  1.16 / 1.11; paired 1.06-1.08  1.00 / 1.03; paired 1.03-1.04
//   blob, level 6 (40,962 v.)     1.03 / 1.04; paired 1.02-1.03  0.97 / 1.02; paired 1.02
// Whole-process single runs spread by +-15% at this load (0.86-1.41 wall at 437k); the paired figures
// are the ones to compare. What changed: contact batches ray by ray (1.7 CPU s of 24 vertices at 437k,
// trace/scene.h), the occluded rows summed without a branch (bake/vertex_samples.h), the chunk's spawn
// points queried before its rays (trace/vertex_rays.h).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <string>

#include "bake/bake.h"
#include "bake/passes.h"
#include "bake/vertex_samples.h"
#include "bench_meshes.h"
#include "mesh/writers.h"
#include "sh/sampling.h"
#include "trace/scene.h"

using namespace prt;

namespace {

struct Args {
  int samples = 1024, bands = 5, threads = 2, level = 8, cornell = 0, paired = 0;
  bool memory = true, bounce = true;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    auto value = [&](int& out) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_bake: %s needs a value\n", argv[i]);
        std::exit(2);
      }
      out = std::atoi(argv[++i]);
    };
    if (!std::strcmp(argv[i], "--samples")) value(a.samples);
    else if (!std::strcmp(argv[i], "--bands")) value(a.bands);
    else if (!std::strcmp(argv[i], "--threads")) value(a.threads);
    else if (!std::strcmp(argv[i], "--level")) value(a.level);
    else if (!std::strcmp(argv[i], "--cornell")) value(a.cornell);
    else if (!std::strcmp(argv[i], "--no-memory")) a.memory = false;
    else if (!std::strcmp(argv[i], "--no-bounce")) a.bounce = false;
    else if (!std::strcmp(argv[i], "--paired")) value(a.paired);
    else {
      std::fprintf(stderr,
                   "usage: bench_bake [--samples S] [--bands N] [--threads T] [--level L | --cornell C] [--no-memory] "
                   "[--no-bounce] [--paired B]\n");
      std::exit(2);
    }
  }
  return a;
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

// Runs `prt bake` on `mesh_path` and returns the child's peak resident set in bytes.
double peak_rss_of_bake(const std::string& prt, const std::string& mesh_path, const std::string& out, const Args& a) {
  pid_t pid = fork();
  if (pid == 0) {
    const std::string samples = std::to_string(a.samples), bands = std::to_string(a.bands), threads = std::to_string(a.threads);
    execl(prt.c_str(), "prt", "bake", mesh_path.c_str(), "--transfer", "shadowed", "--samples", samples.c_str(), "--bands",
          bands.c_str(), "--threads", threads.c_str(), "-q", "-o", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// Traces on one thread the rays of the points `indices` of (positions, normals) as the bake's loop
// does, without its per-point work: frames sh::vertex_frame(n_i, seed, i), origins
// Scene::offset_origin, batches of 256, RayBatch::set_robust(robust_batch). Returns the CPU seconds.
double trace_points(const trace::Scene& scene, const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                    const std::vector<std::uint32_t>& indices, const std::vector<glm::vec3>& directions, std::uint32_t seed,
                    bool robust_batch) {
  trace::RayBatch batch;
  const double start = bench::process_cpu_seconds();
  for (const std::uint32_t i : indices) {
    const glm::mat3 frame = sh::vertex_frame(normals[i], seed, i);
    const glm::vec3 origin = scene.offset_origin(positions[i], normals[i]);
    for (std::size_t first = 0; first < directions.size(); first += batch.capacity()) {
      batch.clear();
      batch.set_robust(robust_batch);
      for (std::size_t s = first; s < std::min(directions.size(), first + batch.capacity()); ++s) batch.push(origin, frame * directions[s]);
      scene.occluded(batch);
    }
  }
  return bench::process_cpu_seconds() - start;
}

// --paired B: the shadowed pass (bake::shadowed_geometric, the bake's own code) against the bare
// non-robust loop over the same rays (trace_points), on one thread, alternated per block of B
// Morton-ordered vertices, which goes first swapped from block to block: on a shared machine the load
// drifts alike for both, where whole passes minutes apart differ by +-15%. Each block is handed to
// the pass as sample points (bake/passes.h, SamplePoints), so both trace the frames of the block's
// point indices. Prints the CPU seconds of each and their ratio.
void paired_blocks(const mesh::Mesh& mesh, const Args& a) {
  const bake::BakeOptions options;
  const bake::LocalSampleSet samples = bake::make_local_sample_set(a.samples, a.bands, options.seed);
  const std::vector<std::uint32_t> order = trace::morton_order(mesh.positions);
  const trace::Scene scene(mesh, bake::bake_scene_options(1));
  const std::size_t block = static_cast<std::size_t>(a.paired);
  double bare = 0.0, pass = 0.0;
  std::vector<float> out;
  for (std::size_t begin = 0, b = 0; begin < order.size(); begin += block, ++b) {
    std::vector<glm::vec3> positions, normals;
    for (std::size_t k = begin; k < std::min(order.size(), begin + block); ++k) {
      positions.push_back(mesh.positions[order[k]]);
      normals.push_back(mesh.normals[order[k]]);
    }
    std::vector<std::uint32_t> points(positions.size());
    std::iota(points.begin(), points.end(), 0u);
    for (int turn = 0; turn < 2; ++turn) {
      if ((turn + b) % 2 == 1) {
        bare += trace_points(scene, positions, normals, points, samples.directions, options.seed, false);
        continue;
      }
      bake::PassContext ctx{&mesh, &scene, &samples, &points, options.seed, 1, false};
      ctx.points = bake::SamplePoints{&positions, &normals};
      const double start = bench::process_cpu_seconds();
      bake::shadowed_geometric(ctx, out);
      pass += bench::process_cpu_seconds() - start;
    }
  }
  std::printf("\npaired per block of %zu vertices, 1 thread, CPU seconds: bare non-robust %.2f, shadowed pass %.2f, ratio %.3f (target <=1.15)\n",
              block, bare, pass, pass / bare);
}

// The bare passes over the baker's rays, robust and not, the shadowed bake between two non-robust
// occlusion passes (their mean is its baseline: the machine's load drifts), then the bounce pass.
struct Measured {
  bench::PassResult occlusion, closest, occlusion_fast_before, occlusion_fast_after, closest_fast;
  bake::BakeReport shadowed, inter;
  std::size_t contact_vertices = 0, output_bytes = 0;
  // CPU seconds per ray of the contact vertices' rays: as the bake traces them (robust mode in its
  // non-robust scene: ray by ray), and by rtcOccluded1M in a robust scene (trace/scene.h, BATCH SIZE).
  double contact_ray_seconds = 0.0, contact_ray_seconds_stream = 0.0;
  // CPU seconds of the process: one BVH build (of the non-robust scene), the whole shadowed bake call.
  double build_cpu = 0.0, shadowed_cpu = 0.0;
  double occlusion_fast_seconds() const { return 0.5 * (occlusion_fast_before.seconds + occlusion_fast_after.seconds); }
  double occlusion_fast_cpu() const { return 0.5 * (occlusion_fast_before.cpu_seconds + occlusion_fast_after.cpu_seconds); }
};

Measured measure(const mesh::Mesh& mesh, const trace::Scene& scene, const Args& a) {
  Measured r;
  bake::BakeOptions options;
  const bake::LocalSampleSet samples = bake::make_local_sample_set(a.samples, a.bands, options.seed);
  const std::vector<std::uint32_t> order = trace::morton_order(mesh.positions);
  double cpu = bench::process_cpu_seconds();
  const trace::Scene fast_scene(mesh, bake::bake_scene_options(a.threads));
  r.build_cpu = bench::process_cpu_seconds() - cpu;
  // The bake traces these vertices' rays with robust mode (trace/scene.h, ROBUST MODE).
  std::vector<std::uint32_t> contacts;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v)
    if (fast_scene.spawn_point(mesh.positions[v], mesh.normals[v]).robust) contacts.push_back(v);
  r.contact_vertices = contacts.size();
  const double contact_rays = std::max(1.0, static_cast<double>(contacts.size() * samples.directions.size()));
  trace_points(fast_scene, mesh.positions, mesh.normals, contacts, samples.directions, options.seed, true);  // builds the robust BVH
  r.contact_ray_seconds =
      trace_points(fast_scene, mesh.positions, mesh.normals, contacts, samples.directions, options.seed, true) / contact_rays;
  r.contact_ray_seconds_stream =
      trace_points(scene, mesh.positions, mesh.normals, contacts, samples.directions, options.seed, false) / contact_rays;
  // The bake's own rays: its per-vertex frames (sh::vertex_frame), not one frame per normal.
  const bench::PassFrames frames{true, options.seed};
  const std::size_t batch = trace::kDefaultBatchCapacity;
  r.occlusion = bench::occlusion_pass(scene, mesh, order, samples.directions, a.threads, batch, frames);
  // The same pass without RTC_SCENE_FLAG_ROBUST (trace/scene.h, SceneOptions::robust), the best-practice
  // bare Embree loop, just before and after the bake.
  r.occlusion_fast_before = bench::occlusion_pass(fast_scene, mesh, order, samples.directions, a.threads, batch, frames);
  options.kind = transfer::Kind::shadowed;
  options.bands = a.bands;
  options.samples = a.samples;
  options.threads = a.threads;
  cpu = bench::process_cpu_seconds();
  r.output_bytes = bake::bake(mesh, options, &r.shadowed).values.size() * sizeof(float);
  r.shadowed_cpu = bench::process_cpu_seconds() - cpu;
  r.occlusion_fast_after = bench::occlusion_pass(fast_scene, mesh, order, samples.directions, a.threads, batch, frames);
  if (!a.bounce) return r;
  r.closest = bench::closest_hit_pass(scene, mesh, order, samples.directions, a.threads, batch, frames);
  r.closest_fast = bench::closest_hit_pass(fast_scene, mesh, order, samples.directions, a.threads, batch, frames);
  options.kind = transfer::Kind::interreflected;
  options.bounces = 1;
  bake::bake(mesh, options, &r.inter);
  return r;
}

void print_table(const Measured& m, std::size_t vertices, bool bounce) {
  const double rays = static_cast<double>(m.occlusion.rays);
  const double shadowed = m.shadowed.seconds_visibility, bounce_seconds = m.inter.seconds_bounces;
  const double fast = m.occlusion_fast_seconds();
  auto row = [&](const char* name, double seconds, double ratio, const char* target) {
    std::printf("%-46s %10.2f %10.2f %8.3f %8s\n", name, seconds, rays / seconds / 1e6, ratio, target);
  };
  std::printf("\n%-46s %10s %10s %8s %8s\n", "pass", "seconds", "Mrays/s", "ratio", "target");
  row("bare occlusion (rtcOccluded1M), robust", m.occlusion.seconds, 1.0, "");
  row("bare occlusion, not robust (before the bake)", m.occlusion_fast_before.seconds,
      m.occlusion_fast_before.seconds / m.occlusion.seconds, "");
  row("bare occlusion, not robust (after the bake)", m.occlusion_fast_after.seconds,
      m.occlusion_fast_after.seconds / m.occlusion.seconds, "");
  row("shadowed bake (visibility pass)", shadowed, shadowed / m.occlusion.seconds, "<=1.25");
  std::printf("%-46s %10s %10s %8.3f %8s\n", "  shadowed bake / non-robust bare (mean)", "", "", shadowed / fast, "<=1.15");
  // CPU time: on a shared machine the wall times drift with the load; the CPU seconds the passes take
  // drift far less. The bake's call includes its BVH build, taken off as measured for the same scene.
  const double bake_cpu = m.shadowed_cpu - m.build_cpu, fast_cpu = m.occlusion_fast_cpu();
  std::printf("%-46s %10s %10s %8s %8s\n", "CPU seconds:", "", "", "", "");
  std::printf("%-46s %10.2f %10s %8.3f %8s\n", "  bare occlusion, robust", m.occlusion.cpu_seconds, "", m.occlusion.cpu_seconds / fast_cpu, "");
  std::printf("%-46s %10.2f %10s %8.3f %8s\n", "  bare occlusion, not robust (mean)", fast_cpu, "", 1.0, "");
  std::printf("%-46s %10.2f %10s %8.3f %8s\n", "  shadowed bake (call less one BVH build)", bake_cpu, "", bake_cpu / fast_cpu, "<=1.15");
  std::printf("%-46s %10s %10s %8.3f %8s\n", "  shadowed bake / robust bare occlusion", "", "", bake_cpu / m.occlusion.cpu_seconds, "");
  if (bounce) {
    row("bare closest hit (rtcIntersect1M), robust", m.closest.seconds, 1.0, "");
    row("bare closest hit, not robust", m.closest_fast.seconds, m.closest_fast.seconds / m.closest.seconds, "");
    row("interreflection pass (bounce 1)", bounce_seconds, bounce_seconds / m.closest.seconds, "<=1.5");
    std::printf("%-46s %10s %10s %8.3f %8s\n", "  bounce pass / non-robust bare closest hit", "", "",
                bounce_seconds / m.closest_fast.seconds, "");
  }
  std::printf("BVH build inside the bake: %.2f s\n", m.shadowed.seconds_build);
  // What robust mode changes on this mesh: per vertex, the unoccluded-ray counts of the two bare passes.
  std::uint64_t changed = 0;
  for (std::size_t v = 0; v < m.occlusion.counts.size() && v < m.occlusion_fast_before.counts.size(); ++v)
    changed += static_cast<std::uint64_t>(std::abs(int(m.occlusion.counts[v]) - int(m.occlusion_fast_before.counts[v])));
  std::printf("occlusion answers robust mode changes: at least %llu of %.0f rays (%.2g)\n",
              static_cast<unsigned long long>(changed), rays, static_cast<double>(changed) / rays);
  std::printf("vertices the bake traces with robust mode (their lifted origin touches a surface): %zu of %zu\n",
              m.contact_vertices, vertices);
  if (m.contact_vertices > 0)
    std::printf("  their rays, CPU us per ray: %.3f as the bake traces them (ray by ray), %.3f by rtcOccluded1M (robust scene)\n",
                1e6 * m.contact_ray_seconds, 1e6 * m.contact_ray_seconds_stream);
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  mesh::Mesh mesh;
  if (a.cornell > 0) {
    std::printf("bench_bake: Cornell box, %d cells per wall, %d samples/vertex, %d bands, %d threads\n", a.cornell,
                a.samples, a.bands, a.threads);
    mesh = bench::cornell_box(a.cornell);
  } else {
    std::printf("bench_bake: level %d blob, %d samples/vertex, %d bands, %d threads\n", a.level, a.samples, a.bands,
                a.threads);
    mesh = a.level == 8 ? bench::detailed_blob() : bench::bumpy_icosphere(a.level, 0.35f);
  }
  mesh.positions.reserve(mesh.positions.size() + 1);
  std::printf("mesh: %zu vertices, %zu triangles\n", mesh.positions.size(), mesh.indices.size() / 3);
  if (a.paired > 0) {
    paired_blocks(mesh, a);
    return 0;
  }
  const trace::Scene scene(mesh, trace::SceneOptions{a.threads, true});
  const Measured m = measure(mesh, scene, a);
  print_table(m, mesh.positions.size(), a.bounce);
  const std::size_t output_bytes = m.output_bytes;

  if (a.memory) {
    const std::string dir = std::filesystem::temp_directory_path() / "prt_bench_bake";
    std::filesystem::create_directories(dir);
    const std::string mesh_path = dir + "/blob.ply";
    mesh::write_ply(mesh_path, mesh.positions, {}, mesh.indices);
    const std::string prt = std::string(PRT_BINARY_DIR) + "/src/cli/prt";
    const double peak = peak_rss_of_bake(prt, mesh_path, dir + "/blob.prt", a);
    // What the bake cannot do without: the loaded mesh (positions, normals, indices), Embree's BVH and
    // buffers (measured by its memory monitor), and the output transfer.
    const double mesh_bytes = mesh.positions.size() * 24.0 + mesh.indices.size() * 4.0;
    const double embree_bytes = static_cast<double>(scene.stats().embree_bytes + scene.stats().geometry_bytes);
    const double floor = mesh_bytes + embree_bytes + static_cast<double>(output_bytes);
    std::printf("\npeak memory of `prt bake --transfer shadowed`: %.1f MiB; mesh %.1f + BVH %.1f + output %.1f = %.1f MiB; ratio %.3f (target <=1.3)\n",
                mib(peak), mib(mesh_bytes), mib(embree_bytes), mib(output_bytes), mib(floor), peak / floor);
    std::filesystem::remove_all(dir);
  }
  return 0;
}
