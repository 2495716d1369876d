// The K x N table of issue 13 on the bundled lion (guardian_lion_10k.ply, 10,000 vertices), as the CPCA
// paper gives it: for glossy shadowed 25x25 transfer (phong exponent 16, ks 0.5, kd 0.4, 1024
// directions) and diffuse interreflected transfer (1 channel, 256 directions, 2 bounces, with its
// bounce-only part), each K x N: the shaded error of `prt shade` (the CPU reference; sunrise split as it
// splits it: the sun an exact disc, the sky windowed SH, the sun's bounce through the bounce-only part)
// of the decompressed model against the uncompressed transfer, rel_rms over vertices and channels
// (glossy: worst of three eye points), the transfer-space error, the .cprt payload (float32) and its
// share of the .prt values, the CPCA rounds and the compression's wall time. CPCA in the shaded metric
// of that lighting, as `prt compress --env sunrise.exr` does. Frame times: bench_compress.cpp's rows
// (the frame cost depends on K, N and the vertex count, not on the mesh).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>

#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "brdf/projection.h"
#include "compress/cprt_file.h"
#include "image/compare.h"
#include "light/disc.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "shade/glossy.h"
#include "shade/scene_shading.h"

using namespace prt;

namespace {

const std::string kEnvironment = PRT_SOURCE_DIR "/assets/env/sunrise.exr";

light::SceneLighting sunrise(bool glossy) {
  light::WindowRequest window;
  window.radiance = glossy;
  return light::load_scene_lighting(kEnvironment, 5, glm::dvec3(0.0), light::SunRequest{}, window);
}

// Shaded outputs of one transfer: per eye point for glossy, one set for diffuse.
using Shaded = std::vector<std::vector<glm::vec3>>;

struct Case {
  const mesh::Mesh* mesh = nullptr;
  const transfer::TransferData* transfer = nullptr;
  light::SceneLighting lighting;
  std::vector<glm::vec3> eyes;  // empty for diffuse
  Shaded reference;

  Shaded shade(const transfer::TransferData& t) const {
    Shaded out;
    if (eyes.empty()) return {shade::shade_diffuse_split(*mesh, t, lighting, "bench")};
    const brdf::VertexBrdfs brdfs = shade::baked_brdfs(t.header, "bench");
    for (const glm::vec3& eye : eyes) out.push_back(shade::shade_glossy_vertex_brdfs(*mesh, t, brdfs, lighting, eye, "bench"));
    return out;
  }
};

void print_row(const Case& c, int clusters, int pca) {
  const sh::RgbCoefficients discs = light::discs_coefficients(5, c.lighting.discs);
  const auto start = std::chrono::steady_clock::now();
  const compress::Metric metric = compress::transfer_metric(*c.transfer, {&c.lighting.sky, &discs}, "bench");
  const compress::CompressedTransfer model = compress::compress_transfer(*c.transfer, {clusters, pca}, transfer::Scalar::float32, "bench", &metric);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Shaded test = c.shade(compress::decompress(model));
  double worst = 0.0;
  for (std::size_t i = 0; i < test.size(); ++i)
    worst = std::max(worst, image::compare_values(&test[i][0].x, &c.reference[i][0].x, 3 * test[i].size()).rel_rms);
  const std::uint64_t bytes = compress::payload_bytes(model);
  const double prt_bytes = static_cast<double>(compress::uncompressed_bytes(model.source, transfer::Scalar::float32)) * (model.bounce ? 2 : 1);
  std::printf("%-8s %5d %3d %10.3f%% %10.2f%% %12llu %8.1f%% %7d %8.1f\n", c.eyes.empty() ? "diffuse" : "glossy", clusters, pca, 100 * worst,
              100 * model.total.transfer_relative(), static_cast<unsigned long long>(bytes), 100.0 * static_cast<double>(bytes) / prt_bytes,
              model.iterations, seconds);
  std::fflush(stdout);
}

void BM_LionTable(benchmark::State& state) {
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const mesh::Mesh lion = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/guardian_lion_10k.ply", nullptr, true);
    bake::BakeOptions g;
    g.kind = transfer::Kind::glossy_shadowed;
    g.bands = 5;
    g.samples = 1024;
    g.brdf = brdf::parse_brdf("phong:exponent=16,ks=0.5,kd=0.4");
    const transfer::TransferData glossy = bake::bake(lion, g);
    bake::BakeOptions d;
    d.kind = transfer::Kind::interreflected;
    d.bands = 5;
    d.samples = 256;
    d.bounces = 2;
    const transfer::TransferData diffuse = bake::bake(lion, d);
    const mesh::Bounds box = mesh::bounds(lion);
    Case gc{&lion, &glossy, sunrise(true), {}, {}};
    for (const glm::vec3& direction : {glm::vec3(0.1f, 1.0f, 0.6f), glm::vec3(1.0f, 0.5f, -0.7f), glm::vec3(-0.9f, 0.3f, 0.3f)})
      gc.eyes.push_back(0.5f * (box.lo + box.hi) + box.diagonal() * glm::normalize(direction));
    gc.reference = gc.shade(glossy);
    Case dc{&lion, &diffuse, sunrise(false), {}, {}};
    dc.reference = dc.shade(diffuse);
    std::printf("\nCPCA K x N on the lion (10,000 vertices), sunrise split as prt shade splits it, float32\n");
    std::printf("%-8s %5s %3s %11s %11s %12s %9s %7s %8s\n", "transfer", "K", "N", "shaded err", "transfer err", "bytes", "/ .prt", "rounds",
                "time s");
    for (int k : {64, 128, 256})
      for (int n : {4, 8}) print_row(gc, k, n);
    for (int k : {64, 128, 256, 512, 768, 1024})
      for (int n : {4, 8}) print_row(dc, k, n);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}

}  // namespace

BENCHMARK(BM_LionTable)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
