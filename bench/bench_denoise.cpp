// bench_denoise: the texel transfer denoiser (src/lightmap/denoise.h) on a 1024 x 1024 lightmap of 25
// coefficients x 3 channels (RGB), the size of issue 35's target (at most 5 s on 2 cores).
//
// Input: one plane (every texel covered, guides: positions on a grid, one normal), split into 16 x 16
// square charts; transfer = a smooth field plus pseudo-random noise (a fixed LCG), so that the range
// weights vary as on a real bake. Reported: the best and the worst of `--repeat` runs of denoise_texels.
// Usage: bench_denoise [--size N] [--threads T] [--repeat R] [--iterations I] [--twicing W] [--stride F] [--out FILE]
// --stride: floats per texel (75: 25 coefficients x RGB; 25: one channel). --out: the last run's
// output, raw little-endian floats, for byte comparisons of two builds.
// A timed program, not Google Benchmark: run it on a quiet machine.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "lightmap/denoise.h"

using namespace prt;

namespace {

struct Args {
  int size = 1024, threads = 2, repeat = 3, iterations = lightmap::DenoiseOptions{}.iterations;
  float twicing = lightmap::DenoiseOptions{}.twicing;
  std::size_t stride = 75;
  const char* out = nullptr;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--size")) a.size = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) a.threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeat")) a.repeat = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--iterations")) a.iterations = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--twicing")) a.twicing = float(std::atof(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--stride")) a.stride = std::size_t(std::max(1, std::atoi(argv[i + 1])));
    else if (!std::strcmp(argv[i], "--out")) a.out = argv[i + 1];
    else {
      std::fprintf(stderr, "bench_denoise: unknown option %s\n", argv[i]);
      std::exit(2);
    }
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  const std::size_t texels = std::size_t(a.size) * std::size_t(a.size), stride = a.stride;
  lightmap::DenoiseGuides g;
  g.width = g.height = a.size;
  g.covered.assign(texels, 1);
  g.normal.assign(texels, glm::vec3(0, 0, 1));
  g.size.assign(texels, 1.0f / float(a.size));
  g.chart.resize(texels);
  g.position.resize(texels);
  const int chart_side = std::max(1, a.size / 16);
  for (int j = 0; j < a.size; ++j)
    for (int i = 0; i < a.size; ++i) {
      const std::size_t t = std::size_t(i) + std::size_t(j) * std::size_t(a.size);
      g.position[t] = glm::vec3(float(i) / float(a.size), float(j) / float(a.size), 0.0f);
      g.chart[t] = std::uint32_t(i / chart_side + 16 * (j / chart_side));
    }
  std::vector<float> input(texels * stride);
  std::uint32_t state = 12345;
  for (std::size_t t = 0; t < texels; ++t)
    for (std::size_t c = 0; c < stride; ++c) {
      state = state * 1664525u + 1013904223u;
      const float noise = float(state >> 8) / 16777216.0f - 0.5f;
      input[t * stride + c] = std::sin(0.01f * float(t % std::size_t(a.size)) + float(c)) + 0.1f * noise;
    }
  lightmap::DenoiseOptions o;
  o.threads = a.threads;
  o.iterations = a.iterations;
  o.twicing = a.twicing;
  std::vector<double> seconds, cpu;
  std::vector<float> values;
  for (int r = 0; r < a.repeat; ++r) {
    std::vector<float> none;
    values = input;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    lightmap::denoise_texels(values, none, stride, g, o);
    cpu.push_back(double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  if (a.out) {
    std::FILE* f = std::fopen(a.out, "wb");
    if (!f || std::fwrite(values.data(), sizeof(float), values.size(), f) != values.size() || std::fclose(f) != 0) {
      std::fprintf(stderr, "bench_denoise: cannot write %s\n", a.out);
      return 1;
    }
  }
  std::sort(seconds.begin(), seconds.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("denoise %dx%d, %zu floats per texel, %d iterations, %d threads: best %.3f s, worst %.3f s over %d runs "
              "(target <= 5 s on 2 cores); process CPU time best %.3f s, worst %.3f s (/ threads: the wall time on idle cores)\n",
              a.size, a.size, stride, o.iterations, a.threads, seconds.front(), seconds.back(), a.repeat, cpu.front(), cpu.back());
  return 0;
}
