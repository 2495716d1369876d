// Lightmaps against the path-traced reference: the box on a two-triangle floor (texel shadowed and
// interreflected transfer vs `prt reference --texels`, band-limited lighting), the seams of a split
// cube, and contact (boxes resting on and intersecting the floor). Runs the real prt binary.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "image/image.h"
#include "lightmap/lightmap_scenes.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

struct Errors {
  double rel_rms = 0.0;
  std::size_t texels = 0, black_where_lit = 0;
};

// Over covered texels: rel_rms of a against the reference b (all channels), and how many texels read
// below 5% of a reference that is lit (> 10% of its mean).
Errors compare_covered(const image::Image& a, const image::Image& b, const std::vector<std::uint8_t>& coverage) {
  double err = 0.0, norm = 0.0, mean = 0.0;
  Errors e;
  for (std::size_t t = 0; t < coverage.size(); ++t) {
    if (coverage[t] != transfer::kTexelCovered) continue;
    ++e.texels;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[3 * t + c]) - double(b.pixels[3 * t + c]);
      err += d * d;
      norm += double(b.pixels[3 * t + c]) * double(b.pixels[3 * t + c]);
      mean += double(b.pixels[3 * t + c]);
    }
  }
  mean /= 3.0 * double(std::max<std::size_t>(e.texels, 1));
  for (std::size_t t = 0; t < coverage.size(); ++t) {
    if (coverage[t] != transfer::kTexelCovered) continue;
    const double ref = (b.pixels[3 * t] + b.pixels[3 * t + 1] + b.pixels[3 * t + 2]) / 3.0;
    const double got = (a.pixels[3 * t] + a.pixels[3 * t + 1] + a.pixels[3 * t + 2]) / 3.0;
    if (ref > 0.1 * mean && got < 0.05 * ref) ++e.black_where_lit;
  }
  e.rel_rms = std::sqrt(err / std::max(norm, 1e-300));
  return e;
}

struct Scene {
  std::string dir, mesh, sky;
  Scene(const std::string& name, const mesh::Mesh& m) : dir(test::fresh_temp_dir(name)), mesh(dir + "/scene.obj"), sky(dir + "/sky.exr") {
    test::write_obj_with_uv(mesh, m);
    test::write_test_sky(sky);
  }
  // Bakes, shades (band-limited: --sun none --window none) and path-traces the reference at the texels.
  Errors run(const std::string& bake, const std::string& reference, const std::string& name) const {
    const std::string lm = dir + "/" + name + ".prt", lit = dir + "/" + name + "_lit.exr", ref = dir + "/" + name + "_ref.exr";
    const test::RunResult b = test::run_prt("bake " + mesh + " --quiet " + bake + " -o " + lm);
    INFO(b.output);
    REQUIRE(b.exit_code == 0);
    REQUIRE(test::run_prt("shade " + mesh + " " + lm + " --env " + sky + " --sun none --window none --lightmap -o " + lit).exit_code == 0);
    REQUIRE(test::run_prt("reference " + mesh + " --env " + sky + " --band-limit 5 --quiet " + reference + " --texels " + lm + " -o " + ref)
                .exit_code == 0);
    return compare_covered(image::read_rgb(lit), image::read_rgb(ref), transfer::read_transfer(lm).coverage);
  }
};

}  // namespace

TEST_CASE("lightmap: box on a two-triangle floor, shadowed texels vs prt reference --texels: rel_rms <= 1%", "[lightmap][slow]") {
  const Scene scene("lightmap_box_reference", test::floor_and_box(true));
  const Errors e = scene.run("--lightmap 48 --transfer shadowed --samples 2048", "--bounces 0 --samples 1024", "shadowed");
  INFO("texels " << e.texels << " rel_rms " << e.rel_rms);
  CHECK(e.texels > 1000);
  CHECK(e.rel_rms <= 0.01);
  CHECK(e.black_where_lit == 0);
}

}  // namespace prt
