// bench_bake_texture: what a base colour texture costs a bake (issue 33: "bake of a textured asset within
// 1.1x of the same asset untextured"), in one run.
//
// Asset: a real textured mesh, by default spider.obj of Debian's assimp-testmodels
// (/usr/share/assimp/models/OBJ: 762 vertices, five materials with map_Kd JPEGs; BSD-3-clause per
// Debian's copyright file for assimp), or --mesh PATH (OBJ, PLY, glTF). The untextured copy is the same
// loaded mesh with its textures dropped (base-colour UVs and images gone, factors and per-vertex albedo
// kept): both bake 3 channels with the same per-vertex albedo, so the difference is the texture alone
// (the bounce passes' base colour per hit, bake/interreflection.cpp).
// Timed: bake::bake, interreflected (the only kind that looks textures up), textured and untextured
// alternated ROUNDS times; wall and process CPU seconds, best and worst of each. An OBJ is read from a
// copy of its folder (spider.mtl's ".\" image paths as "./"), and the load (mesh::load_mesh) of that
// copy is timed against a copy without the map_Kd lines: decoding the images and the per-vertex
// footprint averages of the texture (mesh/texture.h).
// --box CELLS: instead of a file, a closed room (bench::box's [-1, 1]^3, CELLS x CELLS quads per face,
// turned inward: 12 CELLS^2 triangles) whose every face maps the whole of one SIZE x SIZE texture
// (--texture SIZE, default 1024) of 8-bit sRGB codes in a fixed pseudo-random pattern: the case where
// bounce hits land all over a texture far larger than the CPU caches (--box 37: 16,428 triangles).
// A timed program, not Google Benchmark: on a shared machine the ratio of bests is the figure to read.
// Usage: bench_bake_texture [--mesh PATH | --box CELLS [--texture SIZE]] [--rounds R] [--samples S] [--bands N]
//                           [--bounces B] [--threads T]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "bench_meshes.h"
#include "core/error.h"
#include "mesh/mesh.h"
#include "mesh/texture.h"

using namespace prt;
namespace fs = std::filesystem;

namespace {

struct Seconds {
  double wall = 0.0, cpu = 0.0;
};

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) + 1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

Seconds timed(const std::function<void()>& f) {
  const double cpu = cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), cpu_seconds() - cpu};
}

// The mesh without its textures: no base-colour UVs or images; factors, vertex colours and albedo kept.
mesh::Mesh untextured(mesh::Mesh m) {
  m.base_color_uv.clear();
  m.textures.clear();
  for (mesh::Material& material : m.materials) material.base_color.image = -1;
  return m;
}

// A copy in `dir` of an OBJ and its folder's MTL files and images, with map_Kd's Windows-style ".\"
// prefix (spider.mtl's) as "./"; without the map_Kd lines unless `textured`. Returns the OBJ.
std::string copy_obj(const fs::path& obj, const fs::path& dir, bool textured) {
  fs::create_directories(dir);
  for (const auto& entry : fs::directory_iterator(obj.parent_path())) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".jpg" || ext == ".png") {
      if (textured) fs::copy_file(entry.path(), dir / entry.path().filename(), fs::copy_options::overwrite_existing);
      continue;
    }
    if (ext != ".mtl" && entry.path() != obj) continue;
    std::ifstream in(entry.path());
    std::ofstream out(dir / entry.path().filename());
    for (std::string line; std::getline(in, line);) {
      const std::size_t map = line.find("map_Kd");
      if (map != std::string::npos && !textured) continue;
      const std::size_t windows = line.find(".\\");
      if (map != std::string::npos && windows != std::string::npos) line.replace(windows, 2, "./");
      out << line << "\n";
    }
  }
  return (dir / obj.filename()).string();
}

// The --box room: bench::box turned inward, each face's UVs the whole texture, a size^2 texture of codes.
mesh::Mesh textured_room(int cells, int size) {
  mesh::Mesh m = bench::box(glm::vec3(-1.0f), glm::vec3(1.0f), cells);
  for (std::size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
  for (glm::vec3& n : m.normals) n = -n;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const int axis = std::abs(m.normals[m.indices[t]].x) > 0.5f ? 0 : std::abs(m.normals[m.indices[t]].y) > 0.5f ? 1 : 2;
    for (std::size_t k = 0; k < 3; ++k) {
      const glm::vec3& p = m.positions[m.indices[t + k]];
      m.base_color_uv.emplace_back(0.5f * (p[(axis + 1) % 3] + 1.0f), 0.5f * (p[(axis + 2) % 3] + 1.0f));
    }
  }
  m.materials.emplace_back();
  m.materials[0].base_color.image = 0;
  m.triangle_material.assign(m.triangle_count(), 0u);
  mesh::Texture texture;
  texture.width = texture.height = size;
  texture.codes.resize(3 * std::size_t(size) * std::size_t(size));
  for (std::size_t i = 0; i < texture.codes.size(); ++i) texture.codes[i] = std::uint8_t(64 + (i * 2654435761u >> 7) % 160);
  m.textures.push_back(std::move(texture));
  m.albedo.assign(m.vertex_count(), glm::vec3(1.0f));
  mesh::texture_albedo(m, 0, &m.albedo);
  m.albedo_source = mesh::AlbedoSource::texture;
  return m;
}

struct Pair {
  std::vector<Seconds> a, b;  // textured, untextured
};

double best(const std::vector<Seconds>& v, double Seconds::*field) {
  double m = v.front().*field;
  for (const Seconds& s : v) m = std::min(m, s.*field);
  return m;
}
double worst(const std::vector<Seconds>& v, double Seconds::*field) {
  double m = v.front().*field;
  for (const Seconds& s : v) m = std::max(m, s.*field);
  return m;
}

void print(const char* what, const Pair& p) {
  for (auto [name, field] : {std::pair{"wall", &Seconds::wall}, std::pair{"CPU ", &Seconds::cpu}})
    std::printf("%-5s %s  textured best %.3f s (worst %.3f)  untextured best %.3f s (worst %.3f)  ratio of bests %.3f\n", what,
                name, best(p.a, field), worst(p.a, field), best(p.b, field), worst(p.b, field), best(p.a, field) / best(p.b, field));
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = "/usr/share/assimp/models/OBJ/spider.obj";
  int rounds = 5, box_cells = 0, texture_size = 1024;
  bake::BakeOptions options;
  options.kind = transfer::Kind::interreflected;
  options.bands = 3;
  options.samples = 256;
  options.bounces = 2;
  options.threads = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const int value = std::atoi(argv[i + 1]);
    if (flag == "--mesh") path = argv[i + 1];
    else if (flag == "--rounds") rounds = std::max(1, value);
    else if (flag == "--box") box_cells = std::max(1, value);
    else if (flag == "--texture") texture_size = std::max(1, value);
    else if (flag == "--samples") options.samples = value;
    else if (flag == "--bands") options.bands = value;
    else if (flag == "--bounces") options.bounces = value;
    else if (flag == "--threads") options.threads = value;
    else {
      std::fprintf(stderr, "bench_bake_texture: unknown option %s\n", flag.c_str());
      return 2;
    }
  }
  try {
    if (box_cells) path = "room of " + std::to_string(box_cells) + "^2 quads a face, " + std::to_string(texture_size) + "^2 texture";
    else if (!fs::is_regular_file(path)) fail(path + ": cannot open: no such file");
    const bool obj = !box_cells && fs::path(path).extension() == ".obj";
    const fs::path temp = fs::temp_directory_path() / "prt_bench_bake_texture";
    const std::string textured_file = obj ? copy_obj(path, temp / "textured", true) : path;
    const std::string plain_file = obj ? copy_obj(path, temp / "plain", false) : "";
    const mesh::Mesh textured = box_cells ? textured_room(box_cells, texture_size) : mesh::load_mesh(textured_file, nullptr, true);
    if (!textured.textured()) fail(path + ": the mesh has no base colour texture");
    const mesh::Mesh plain = untextured(textured);
    std::printf("bench_bake_texture: %s, %zu vertices, %zu triangles, %zu textures; interreflected, %d bands, %d samples, "
                "%d bounces, %d threads, %d rounds\n",
                path.c_str(), textured.vertex_count(), textured.triangle_count(), textured.textures.size(), options.bands,
                options.samples, options.bounces, options.threads, rounds);
    Pair load, bake;
    bake::bake(textured, options);  // warm-up: the thread pool starts on first use (core/parallel.h)
    bake::bake(plain, options);
    for (int r = 0; r < rounds; ++r) {
      bake.a.push_back(timed([&] { bake::bake(textured, options); }));
      bake.b.push_back(timed([&] { bake::bake(plain, options); }));
      if (!obj) continue;
      load.a.push_back(timed([&] { mesh::load_mesh(textured_file, nullptr, true); }));
      load.b.push_back(timed([&] { mesh::load_mesh(plain_file, nullptr, true); }));
    }
    print("bake", bake);
    if (obj) print("load", load);
    std::printf("target (issue 33): textured bake <= 1.1 x untextured\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_bake_texture: %s\n", e.what());
    return 1;
  }
  return 0;
}
