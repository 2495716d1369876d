// Mixed scenes (`prt bake --lightmap N --texel-parts ...`, lightmap/part_choice.h): which parts go per
// texel (names, and the auto rule against its closed form), the .prt pair a mixed bake writes
// (byte-identical for any thread count, each file naming the other), and bad input: one line, exit 1,
// no file. The rendered pair against `prt reference --image` is tests/render/test_render_lightmap_image.cpp,
// the pair drawn in one frame tests/render/test_render_mixed.cpp.
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/atomic_file.h"
#include "lightmap/lightmap_scenes.h"
#include "lightmap/mixed_scenes.h"
#include "lightmap/part_choice.h"
#include "mesh/mesh.h"
#include "support/run_prt.h"
#include "transfer/mixed_parts.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

// The room (floor, box, wall) as a .gltf of three named nodes in `dir`; returns its path.
std::string write_room(const std::string& dir, bool with_box = true) {
  std::vector<test::NamedPart> parts;
  const mesh::Mesh room = test::room_with_box(with_box, parts);
  const std::string path = dir + "/room.gltf";
  test::write_gltf_parts(path, room, parts);
  return path;
}

// Per triangle of the loaded room, the name of its node.
std::vector<std::string> triangle_nodes(const mesh::Mesh& m) {
  std::vector<std::string> out;
  for (const mesh::TriangleSource& s : m.triangle_source) out.push_back(m.source_primitives[s.primitive].node_name);
  return out;
}

}  // namespace

TEST_CASE("mixed scenes: --texel-parts names pick their nodes' triangles and auto gives texels where W x H x UV area exceeds the vertices",
          "[lightmap][mixed]") {
  const std::string dir = test::fresh_temp_dir("mixed_parts");
  const mesh::Mesh room = mesh::load_mesh(write_room(dir));
  REQUIRE(room.triangle_count() == 16);
  const std::vector<std::string> node = triangle_nodes(room);

  const lightmap::PartChoice named = lightmap::choose_parts(room, "Floor,Wall", 32, 32, "room.gltf");
  CHECK(named.mixed());
  for (std::size_t t = 0; t < node.size(); ++t) CHECK(int(named.vertex_triangle[t]) == int(node[t] == "Box"));
  CHECK(named.texel_parts.size() == 2);
  CHECK(named.vertex_parts.size() == 1);

  // The closed form of the auto rule: texels = UV area x W x H against distinct vertices.
  //   8 x 8:   floor 0.58^2 x 64 = 21.5 > 4; box 6 x 0.18^2 x 64 = 12.4 < 24; wall 0.58 x 0.18 x 64 = 6.7 > 4.
  //   32 x 32: the box gets 199 texels > 24 vertices: every part per texel, nothing mixed.
  const lightmap::PartChoice small = lightmap::choose_parts(room, "auto", 8, 8, "room.gltf");
  for (std::size_t t = 0; t < node.size(); ++t) CHECK(int(small.vertex_triangle[t]) == int(node[t] == "Box"));
  CHECK_FALSE(lightmap::choose_parts(room, "auto", 32, 32, "room.gltf").mixed());
  CHECK_FALSE(lightmap::choose_parts(room, "all", 8, 8, "room.gltf").mixed());
}

TEST_CASE("prt bake --texel-parts: a .prt pair, byte-identical for 1 and 2 threads, each file naming the other",
          "[lightmap][mixed][cli]") {
  const std::string dir = test::fresh_temp_dir("mixed_pair");
  const std::string room = write_room(dir);
  const std::string bake = "bake " + room + " --transfer interreflected --bounces 1 --bands 3 --samples 64 --lightmap 32 "
                                             "--texel-parts Floor,Wall -q";
  // The same file names in two folders: each file of the pair names the other.
  for (const char* threads : {"1", "2"}) {
    std::filesystem::create_directory(dir + "/" + threads);
    const test::RunResult r = test::run_prt(bake + " --threads " + threads + " -o " + dir + "/" + threads + "/t1.prt");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  CHECK(read_file(dir + "/1/t1.prt") == read_file(dir + "/2/t1.prt"));
  CHECK(read_file(dir + "/1/t1.vertices.prt") == read_file(dir + "/2/t1.vertices.prt"));

  const transfer::TransferData texels = transfer::read_transfer(dir + "/1/t1.prt");
  const transfer::TransferData vertices = transfer::read_transfer(dir + "/1/t1.vertices.prt");
  CHECK(texels.header.is_texel());
  CHECK_FALSE(vertices.header.is_texel());
  CHECK(vertices.header.vertex_count == 32);
  CHECK(vertices.header.mesh_fingerprint == texels.header.mesh_fingerprint);
  CHECK(vertices.bounce_only.size() == vertices.values.size());
  const auto t = transfer::read_mixed_entry(texels.header, "t1.prt");
  const auto v = transfer::read_mixed_entry(vertices.header, "t1.vertices.prt");
  REQUIRE(t);
  REQUIRE(v);
  CHECK(t->partner == "t1.vertices.prt");
  CHECK(v->partner == "t1.prt");
  // The box: triangles 2..13 of the file (Floor first, then Box, then Wall).
  CHECK(t->vertex_runs == std::vector<std::pair<std::uint64_t, std::uint64_t>>{{2, 12}});
  CHECK(v->vertex_runs == t->vertex_runs);
  // No texel of the lightmap belongs to the box: the box's slots stay empty.
  const int w = 32;
  const int slot_texel = int(0.70f * w) + int(0.10f * w) * w;  // inside the box's top-face slot (0.61..0.79, 0.01..0.19)
  CHECK(int(texels.coverage[std::size_t(slot_texel)]) == int(transfer::kTexelEmpty));
  // Every vertex got transfer: the DC term of an upward floor vertex is positive.
  CHECK(vertices.values[0] > 0.0f);
}

TEST_CASE("prt bake --texel-parts: bad input gives one line, exit 1 and no file", "[lightmap][mixed][cli]") {
  const std::string dir = test::fresh_temp_dir("mixed_bad");
  const std::string room = write_room(dir);
  // A texel part without usable UVs: the floor's UVs collapsed to a point; and the room as an OBJ (one part).
  std::vector<test::NamedPart> parts;
  mesh::Mesh broken = test::room_with_box(true, parts);
  test::write_obj_with_uv(dir + "/room.obj", broken);
  for (int k = 0; k < 6; ++k) broken.lightmap_uv[std::size_t(k)] = glm::vec2(0.3f);
  test::write_gltf_parts(dir + "/broken.gltf", broken, parts);
  const std::size_t inputs = test::entries_in(dir);
  auto bake = [&](const std::string& scene) {
    return "bake " + scene + " --transfer shadowed --bands 2 --samples 16 --lightmap 16 ";
  };
  auto refused = [&](const std::string& arguments, const std::string& expected) {
    const test::RunResult r = test::run_prt(arguments);
    INFO("prt " << arguments << "\n" << r.output);
    CHECK(test::fails_in_one_line(r, expected));
    CHECK(test::entries_in(dir) == inputs);
  };
  refused(bake(room) + "--texel-parts Floor,Chair -o " + dir + "/o.prt", "no part named \"Chair\"");
  refused(bake(room) + "--texel-parts Floor, -o " + dir + "/o.prt", "empty name");
  // (--gltf of a mixed scene is written: tests/pipeline/test_mixed_gltf.cpp; a bad --gltf path is refused before the bake.)
  refused(bake(room) + "--texel-parts Floor --gltf " + dir + "/none/o.glb -o " + dir + "/o.prt", dir + "/none/o.glb");
  refused(bake(room) + "--texel-parts Floor -o " + dir + "/o.cprt", "mixed scene");
  refused("bake " + room + " --texel-parts Floor -o " + dir + "/o.prt", "--texel-parts applies to texel bakes only");
  refused(bake(dir + "/broken.gltf") + "--texel-parts Floor,Wall -o " + dir + "/o.prt",
          "\"Floor\" mesh 0 primitive 0 has no usable lightmap UVs");
  refused(bake(dir + "/room.obj") + "--texel-parts Floor -o " + dir + "/o.prt", "names need a glTF scene");
  refused(bake(room) + "--texel-parts Floor --uv generate -o " + dir + "/o.cprt", "mixed scene");
}

TEST_CASE("prt bake --texel-parts --uv auto judges the texel parts' UVs alone: tiling UVs on the box keep the file's UVs, bad texel UVs generate",
          "[lightmap][mixed][cli]") {
  const std::string dir = test::fresh_temp_dir("mixed_uv_auto");
  std::vector<test::NamedPart> parts;
  mesh::Mesh room = test::room_with_box(true, parts);
  // The box (triangles 2..13) gets tiling texture UVs, as a prop's TEXCOORD_0 repeating a texture.
  for (std::size_t c = 3 * 2; c < 3 * 14; ++c) room.lightmap_uv[c] = room.lightmap_uv[c] * 4.0f - 1.5f;
  test::write_gltf_parts(dir + "/room.gltf", room, parts);
  const std::string bake = "bake " + dir + "/room.gltf --transfer shadowed --bands 2 --samples 16 --lightmap 32 -q ";
  auto run = [&](const std::string& arguments) {
    const test::RunResult r = test::run_prt(bake + arguments);
    INFO("prt " << bake << arguments << "\n" << r.output);
    return r;
  };
  // The whole file's UVs would be generated (tiling), which a mixed scene cannot take; the texel parts'
  // own UVs are fine, so auto keeps them: the same bytes as --uv file.
  // (The same file names in two folders: each file of the pair names the other.)
  for (const char* mode : {"file", "auto"}) {
    std::filesystem::create_directory(dir + "/" + mode);
    REQUIRE(run("--texel-parts Floor,Wall --uv " + std::string(mode) + " -o " + dir + "/" + mode + "/t.prt").exit_code == 0);
  }
  CHECK(read_file(dir + "/file/t.prt") == read_file(dir + "/auto/t.prt"));
  CHECK(read_file(dir + "/file/t.vertices.prt") == read_file(dir + "/auto/t.vertices.prt"));
  // With the box per texel too, its tiling UVs are judged: auto generates (a plain bake, no pair).
  const test::RunResult all = run("--uv auto -o " + dir + "/all.prt");
  CHECK(all.exit_code == 0);
  CHECK_FALSE(std::filesystem::exists(dir + "/all.vertices.prt"));
  CHECK(transfer::read_transfer(dir + "/all.prt").header.uv_fingerprint != transfer::read_transfer(dir + "/file/t.prt").header.uv_fingerprint);
  // A texel part's own UVs unusable (a corner of the wall that only its first triangle uses, outside
  // [0, 1]: 11% of the texel parts' area skipped, beyond the 1% rule): auto generates, and the mixed
  // bake writes the mesh that carries the UVs beside the pair (pipeline/mixed_uv_mesh.h), and with
  // --gltf the engine glTF of it (tests/pipeline/test_mixed_gltf.cpp checks its contents).
  room.lightmap_uv[3 * 14 + 1] = glm::vec2(1.7f, 0.3f);
  test::write_gltf_parts(dir + "/room.gltf", room, parts);
  const test::RunResult generated = run("--texel-parts Floor,Wall --uv auto -o " + dir + "/gen.prt --gltf " + dir + "/gen.glb");
  CHECK(generated.exit_code == 0);
  CHECK(std::filesystem::exists(dir + "/gen.vertices.prt"));
  CHECK(std::filesystem::exists(dir + "/gen.mesh.glb"));
  CHECK(std::filesystem::exists(dir + "/gen.glb"));
  CHECK_FALSE(std::filesystem::exists(dir + "/file/t.mesh.glb"));  // none with the file's UVs
}


// One bounce, both halves of the pair against the path tracer (which shares no transfer code): the
// per-vertex file shaded at the vertices against `prt reference` per vertex (footprint area, as the bake
// stores), the texel file shaded per texel against `prt reference --texels` (gutter 0: only covered
// texels hold values in both). The box's vertices gather the floor's texels (with the box's shadow in
// them); an all-vertex bake gathers four floor vertices that cannot hold that shadow, so the mixed
// vertices must be closer to the truth than the all-vertex bake's.
TEST_CASE("mixed bake, one bounce: the vertex file against prt reference per vertex, the texel file against prt reference --texels",
          "[lightmap][mixed][cli][slow]") {
  const std::string dir = test::fresh_temp_dir("mixed_reference");
  const std::string room = write_room(dir), sky = dir + "/sky.exr";
  auto run = [](const std::string& arguments) {
    const test::RunResult r = test::run_prt(arguments);
    INFO("prt " << arguments << "\n" << r.output);
    REQUIRE(r.exit_code == 0);
  };
  run("light 'cone:0.6,0.55,0.45:30:6,5.5,5+constant:0.25,0.3,0.4' --bands 5 -o " + dir + "/sky.json --preview " + sky);
  const std::string bake = "bake " + room + " --transfer interreflected --bounces 1 --bands 5 --samples 512 -q";
  const std::string shade = " --env " + sky + " --sun none --window none -q -o " + dir;
  const std::string reference = "reference " + room + " --env " + sky + " --band-limit 5 --bounces 1 -q";
  run(bake + " --lightmap 64 --gutter 0 --texel-parts Floor,Wall -o " + dir + "/mixed.prt");
  run(bake + " -o " + dir + "/vertex.prt");
  run("shade " + room + " " + dir + "/mixed.vertices.prt" + shade + "/mixed_vertices.ply");
  run("shade " + room + " " + dir + "/vertex.prt" + shade + "/vertex.ply");
  run("shade " + room + " " + dir + "/mixed.prt --lightmap" + shade + "/mixed_texels.exr");
  run(reference + " --spp 4096 -o " + dir + "/reference.ply");
  run(reference + " --spp 1024 --texels " + dir + "/mixed.prt -o " + dir + "/reference_texels.exr");
  const double mixed_vertices = test::compare_rel_rms(dir + "/mixed_vertices.ply", dir + "/reference.ply");
  const double all_vertices = test::compare_rel_rms(dir + "/vertex.ply", dir + "/reference.ply");
  const double mixed_texels = test::compare_rel_rms(dir + "/mixed_texels.exr", dir + "/reference_texels.exr");
  std::printf("mixed bake, 1 bounce, rel_rms against prt reference: vertices %.4f (all-vertex bake %.4f), texels %.4f\n",
              mixed_vertices, all_vertices, mixed_texels);
  INFO("vertices " << mixed_vertices << " (all-vertex " << all_vertices << "), texels " << mixed_texels);
  CHECK(mixed_vertices < 0.025);  // measured 0.012 (512 bake samples, 4096 reference paths)
  CHECK(mixed_vertices < 0.5 * all_vertices);  // measured 0.045
  CHECK(mixed_texels < 0.025);  // measured 0.016 (1024 reference paths per texel)
}

}  // namespace prt
