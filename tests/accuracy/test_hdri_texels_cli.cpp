// Issue 36's "bake high, ship light" per texel: the compressed texel default (`prt bake MESH --lightmap
// SIZE -o T.cprt`: 16 bands, CPCA sized to the 5-band texel .prt; compress::ship_texel_compression)
// against the path tracer at the texels' own sample points (`prt reference --texels`, which shares no
// transfer or SH-shading code with the bake; docs/architecture.md), diffuse shadowed, default shading
// options, on four maps of tests/data/hdri (forest: a bright sky without a compact sun; city: a high sun;
// interior: lamps; courtyard: overcast): rel_rms over the covered texels <= 3.5% per map and no worse
// than the old 5-band texel default (`-o T.prt`) beyond the references' noise; the .cprt no larger than
// the 5-band .prt. The texels are shaded by `prt shade --lightmap` (the decompressed model; the GPU's
// compressed pass equals it up to float rounding: tests/render/test_render_lightmap_cpca.cpp).
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "image/compare.h"
#include "image/image.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

namespace {

using prt::test::run_prt;

const std::string kData = std::string(PRT_SOURCE_DIR) + "/tests/data/";

void require_run(const std::string& arguments) {
  const auto run = run_prt(arguments);
  INFO(arguments << "\n" << run.output);
  REQUIRE(run.exit_code == 0);
}

// rel_rms of lit lightmap `path` against the reference lightmap `reference` over the covered texels.
double covered_rel_rms(const std::string& path, const std::string& reference, const std::vector<std::uint8_t>& coverage) {
  const prt::image::Image a = prt::image::read_rgb(path), b = prt::image::read_rgb(reference);
  REQUIRE(a.pixels.size() == b.pixels.size());
  REQUIRE(a.pixels.size() == 3 * coverage.size());
  std::vector<float> x, y;
  for (std::size_t t = 0; t < coverage.size(); ++t)
    if (coverage[t] == prt::transfer::kTexelCovered)
      for (std::size_t c = 0; c < 3; ++c) x.push_back(a.pixels[3 * t + c]), y.push_back(b.pixels[3 * t + c]);
  REQUIRE(x.size() > 3 * 1000);
  return prt::image::compare_values(x.data(), y.data(), x.size()).rel_rms;
}

}  // namespace

TEST_CASE("texel default bake (--lightmap, -o T.cprt): each map within 3.5% of the path tracer and no worse than 5 bands, "
          "file no larger than 5 bands'",
          "[accuracy][hdri][lightmap][slow]") {
  const std::string dir = prt::test::fresh_temp_dir("hdri_texels");
  const std::string mesh = dir + "/s.glb";
  require_run("unwrap " + kData + "sphere_on_floor.ply --size 64 -q -o " + mesh);
  require_run("bake " + mesh + " --lightmap 64 -q -o " + dir + "/old.prt");
  require_run("bake " + mesh + " --lightmap 64 -q -o " + dir + "/new.cprt");
  CHECK(std::filesystem::file_size(dir + "/new.cprt") <= std::filesystem::file_size(dir + "/old.prt"));
  const std::vector<std::uint8_t> coverage = prt::transfer::read_transfer(dir + "/old.prt").coverage;
  for (const char* map : {"forest", "city", "interior", "courtyard"}) {
    CAPTURE(map);
    const std::string env = " --env " + kData + "hdri/" + map + ".exr";
    require_run("reference " + mesh + env + " --bounces 0 --texels " + dir + "/old.prt --samples 1024 -q -o " + dir + "/ref.exr");
    require_run("shade " + mesh + " " + dir + "/new.cprt" + env + " --lightmap -q -o " + dir + "/new.exr");
    require_run("shade " + mesh + " " + dir + "/old.prt" + env + " --lightmap -q -o " + dir + "/old.exr");
    const double now = covered_rel_rms(dir + "/new.exr", dir + "/ref.exr", coverage);
    const double before = covered_rel_rms(dir + "/old.exr", dir + "/ref.exr", coverage);
    std::printf("texel default vs path tracer, %-9s: 5 bands %.4f, now %.4f\n", map, before, now);
    CHECK(now <= 0.035);
    CHECK(now <= before + 0.002);  // the 1024-path references' own noise is in both
  }
}
