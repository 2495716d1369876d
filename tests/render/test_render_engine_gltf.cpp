// `prt render` of the engine glTF (docs/formats.md, "The engine glTF: PRT_transfer"): the .glb given as
// both MESH and TRANSFER draws the same pixels as the source mesh with the .cprt the same bake wrote
// (a textured third-party glTF, BoxTextured, CC-BY 4.0, under an HDRI with its sun as a disc and a
// rotated environment; an OBJ with two materials, whose export splits vertices between primitives and
// shades with _PRT_ALBEDO).
#include <catch2/catch.hpp>

#include <string>

#include "core/atomic_file.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

const std::string kEnv = std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr";

void bake(const std::string& source, const std::string& out) {
  const test::RunResult r = test::run_prt("bake " + source + " --transfer interreflected --bands 3 --samples 32 --bounces 1 "
                                          "--compress 3,2 -q -o " + out + ".cprt --gltf " + out + ".glb");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
}

std::string render(const std::string& mesh, const std::string& transfer, const std::string& out, const std::string& extra) {
  const test::RunResult r = test::run_prt("render " + mesh + " " + transfer + " --env " + kEnv + " --size 160x120 " +
                                          extra + " -o " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return read_file(out);
}

}  // namespace

TEST_CASE("prt render of an engine glTF equals the source with its .cprt", "[render][gl][gltf]") {
  const std::string dir = test::fresh_temp_dir("render_engine_gltf");
  const std::string box = std::string(PRT_SOURCE_DIR) + "/tests/data/BoxTextured/BoxTextured.glb";
  bake(box, dir + "/box");
  for (const std::string extra : {"", "--rotate 70,20,0 --sun none"}) {
    INFO(extra);
    CHECK(render(dir + "/box.glb", dir + "/box.glb", dir + "/a.exr", extra) == render(box, dir + "/box.cprt", dir + "/b.exr", extra));
  }
  write_file_atomically(dir + "/two.mtl", "newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.2 0.7\n");
  write_file_atomically(dir + "/two.obj",
                        "mtllib two.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 1 -1\nv 1 1 -1\n"
                        "usemtl red\nf 1 3 2\nf 1 4 3\nusemtl blue\nf 1 2 6\nf 1 6 5\n");
  bake(dir + "/two.obj", dir + "/two");
  render(dir + "/two.glb", dir + "/two.glb", dir + "/c.exr", "");
  render(dir + "/two.obj", dir + "/two.cprt", dir + "/d.exr", "");
  CHECK(test::compare_rel_rms(dir + "/c.exr", dir + "/d.exr") < 1e-5);
}
