// `prt unwrap` on real third-party meshes, checked by an independent rasterizer (atlas_check.h): no
// texel shared by two charts, 2 x padding empty texels between charts, no texel centre inside two
// triangles, every triangle on some texel, UVs in [0, 1]; byte-identical files for any thread count.
// Meshes: 2CylinderEngine (glTF sample model, Debian assimp-testmodels, 110k triangles, 82 nodes; the
// package's copyright file: BSD-3-clause; Khronos glTF-Sample-Models: CC-BY 4.0, AGI), the armadillo
// scan and the guardian lion scan (assets/meshes, docs in assets/).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "mesh/mesh.h"
#include "support/run_prt.h"
#include "unwrap/atlas_check.h"

namespace {

using namespace prt;

const char* kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

std::string asset(const std::string& name) { return std::string(PRT_SOURCE_DIR) + "/assets/meshes/" + name; }

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

test::AtlasCheck unwrap_and_check(const std::string& input, int size, const std::string& out) {
  const test::RunResult run = test::run_prt("unwrap " + input + " -o " + out + " --size " + std::to_string(size) + " --padding 2");
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  const mesh::Mesh m = mesh::load_mesh(out, nullptr, true);
  REQUIRE(m.lightmap_uv_set == 1);
  const test::AtlasCheck c = test::check_atlas(m, size, size, 2);
  std::printf("unwrap %s at %d: %zu triangles, %zu charts, %zu texels touched, texel area p95/mean %.3f\n", input.c_str(), size,
              m.triangle_count(), c.charts, c.touched, c.p95_over_mean);
  return c;
}

void check_clean(const test::AtlasCheck& c) {
  CHECK(c.outside == 0);
  CHECK(c.shared_texels == 0);
  CHECK(c.padding_violations == 0);
  CHECK(c.double_centres == 0);
  CHECK(c.triangles_without_texel == 0);
}

}  // namespace

TEST_CASE("prt unwrap: 2CylinderEngine (110k triangles in 82 nodes) and the armadillo and lion scans pack cleanly", "[unwrap]") {
  const std::string dir = test::fresh_temp_dir("unwrap_real");
  struct Case {
    std::string input;
    int size;
  };
  for (const Case& k : {Case{kEngine, 1024}, Case{asset("armadillo.ply"), 1024}, Case{asset("guardian_lion_10k.ply"), 512}}) {
    SECTION(k.input) {
      const test::AtlasCheck c = unwrap_and_check(k.input, k.size, dir + "/out.glb");
      check_clean(c);
      CHECK(c.charts > 1);
      CHECK(c.p95_over_mean < 3.0);
      // Packing density: the scan's charts nest by their profiles (unwrap/pack.h). Touched texels were
      // 37% of the lightmap with padded rectangles alone, 46% with the profiles.
      if (k.input == asset("armadillo.ply")) CHECK(double(c.touched) > 0.43 * k.size * k.size);
    }
  }
}

TEST_CASE("atlas check: fails on UVs moved onto another chart and on a larger padding than packed", "[unwrap]") {
  const std::string dir = test::fresh_temp_dir("unwrap_broken");
  REQUIRE(test::run_prt("unwrap " + asset("guardian_lion_10k.ply") + " -o " + dir + "/lion.glb --size 512 -q").exit_code == 0);
  mesh::Mesh m = mesh::load_mesh(dir + "/lion.glb", nullptr, true);
  CHECK(test::check_atlas(m, 512, 512, 3).padding_violations > 0);  // packed with 2: 4 empty texels, not 6
  for (int k = 0; k < 3; ++k) m.lightmap_uv[std::size_t(k)] = m.lightmap_uv[3 * 5000 + std::size_t(k)];  // triangle 0 onto 5000
  const test::AtlasCheck broken = test::check_atlas(m, 512, 512, 2);
  CHECK(broken.shared_texels + broken.double_centres > 0);
}

TEST_CASE("prt unwrap: byte-identical output for any thread count (1 and 2 on the engine and 1 to 3 on the lion)", "[unwrap]") {
  const std::string dir = test::fresh_temp_dir("unwrap_threads");
  for (const std::string& input : {std::string(kEngine), asset("guardian_lion_10k.ply")}) {
    std::string first;
    for (int threads : input == kEngine ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 3}) {
      const std::string out = dir + "/t" + std::to_string(threads) + ".glb";
      REQUIRE(test::run_prt("unwrap " + input + " -o " + out + " -q --threads " + std::to_string(threads)).exit_code == 0);
      if (threads == 1) first = bytes_of(out);
      else CHECK(bytes_of(out) == first);
    }
    CHECK(first.size() > 1000);
  }
}

TEST_CASE("prt unwrap: bad input is one line with exit 1 and no output file", "[unwrap]") {
  const std::string dir = test::fresh_temp_dir("unwrap_bad");
  CHECK(test::fails_in_one_line(test::run_prt("unwrap " + dir + "/missing.obj -o " + dir + "/a.glb"), "missing.obj"));
  CHECK(test::fails_in_one_line(test::run_prt("unwrap " + std::string(kEngine) + " -o " + dir + "/a.glb --size 16 -q"),
                                std::string(kEngine) + ": 4178 charts do not fit a 16x16 lightmap"));
  CHECK(test::fails_in_one_line(test::run_prt("unwrap " + asset("guardian_lion_10k.ply") + " -o " + dir + "/a.glb --chart-angle 95"),
                                "--chart-angle 95"));
  CHECK(test::entries_in(dir) == 0);
}
