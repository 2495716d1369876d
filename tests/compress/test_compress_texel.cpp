// CPCA of per-texel (lightmap) transfer (docs/formats.md, "Compressed transfer files", version 2): the
// points are the non-empty texels; a synthetic texel transfer lying exactly in K affine subspaces is
// recovered exactly; the .cprt keeps the lightmap's size, UV set, UV fingerprint and coverage mask; and
// through the real binary, `prt shade --lightmap` and `prt render` of the compressed lightmap are within
// a stated tolerance of the uncompressed one and equal to those of its decompressed texels.
#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <iterator>
#include <random>

#include "compress/cprt_file.h"
#include "compress/open_transfer.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "image/compare.h"
#include "image/image.h"
#include "lightmap_scenes.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A 12 x 10 interreflected texel transfer, 3 bands, 1 channel (9 values and 9 bounce-only values per
// texel): empty texels (zeros) in a stripe, the rest covered or gutter; every non-empty texel's 18
// values lie exactly in one of 3 affine subspaces of dimension 2 (means ~10 apart, weights in [-1, 1]).
transfer::TransferData synthetic_texels() {
  transfer::TransferData t;
  transfer::Header& h = t.header;
  h.kind = transfer::Kind::interreflected;
  h.bands = 3;
  h.channels = 1;
  h.vertex_count = 8;
  h.triangle_count = 12;
  h.mesh_fingerprint = 0xfeedbeefcafe1234ull;
  h.parameters_json = R"({"albedo": [0.8, 0.8, 0.8]})";
  h.bounce_only_section = true;
  h.texel_width = 12;
  h.texel_height = 10;
  h.uv_set = 1;
  h.uv_fingerprint = 0x0123456789abcdefull;
  const std::size_t texels = 120, D = 9;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> mean(3 * 2 * D), basis(3 * 2 * 2 * D);
  for (double& m : mean) m = 10.0 * unit(rng);
  for (double& b : basis) b = unit(rng);  // linearly independent with probability 1 (not orthonormal)
  t.coverage.resize(texels);
  t.values.assign(texels * D, 0.0f);
  t.bounce_only.assign(texels * D, 0.0f);
  for (std::size_t i = 0; i < texels; ++i) {
    const std::size_t x = i % 12;
    t.coverage[i] = x == 5 || x == 6 ? transfer::kTexelEmpty : (x == 4 || x == 7 ? transfer::kTexelGutter : transfer::kTexelCovered);
    if (t.coverage[i] == transfer::kTexelEmpty) continue;
    const std::size_t k = (i * 7) % 3;
    const double w[2] = {unit(rng), unit(rng)};
    for (std::size_t j = 0; j < 2 * D; ++j) {
      double v = mean[k * 2 * D + j];
      for (int n = 0; n < 2; ++n) v += w[n] * basis[(k * 2 + n) * 2 * D + j];
      (j < D ? t.values[i * D + j] : t.bounce_only[i * D + j - D]) = static_cast<float>(v);
    }
  }
  return t;
}

double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = a.size() == b.size() ? 0.0 : 1e30;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::abs(double(a[i]) - double(b[i])));
  return worst;
}

}  // namespace

TEST_CASE("CPCA of texel transfer: the non-empty texels are the points, low-rank texels come back exactly, .cprt version 2 keeps the lightmap",
          "[compress][lightmap]") {
  const transfer::TransferData t = synthetic_texels();
  const compress::CompressedTransfer c = compress::compress_transfer(t, {3, 2}, transfer::Scalar::float32, "texels");
  CHECK(c.point_count() == 100);  // 120 texels less the 20 empty ones
  CHECK(c.cluster.size() == 100);
  CHECK(c.bounce);
  const transfer::TransferData back = compress::decompress(c);
  CHECK(back.coverage == t.coverage);
  CHECK(max_difference(back.values, t.values) <= 1e-6 * 10.0 * 3.0);  // values up to ~16 in magnitude
  CHECK(max_difference(back.bounce_only, t.bounce_only) <= 1e-6 * 10.0 * 3.0);
  for (std::size_t i = 0; i < t.coverage.size(); ++i)
    if (t.coverage[i] == transfer::kTexelEmpty)
      for (std::size_t j = 0; j < 9; ++j) REQUIRE(back.values[i * 9 + j] == 0.0f);

  const std::string dir = test::fresh_temp_dir("cprt_texel");
  compress::write_cprt(dir + "/t.cprt", c);
  const std::string bytes = read_bytes(dir + "/t.cprt");
  REQUIRE(bytes.size() > 12);
  CHECK(static_cast<unsigned char>(bytes[8]) == 2);  // version 2: texel
  const compress::CompressedTransfer r = compress::read_cprt(dir + "/t.cprt");
  CHECK(r.source.texel_width == 12);
  CHECK(r.source.texel_height == 10);
  CHECK(r.source.uv_set == 1);
  CHECK(r.source.uv_fingerprint == 0x0123456789abcdefull);
  CHECK(r.texel_points == 100);
  CHECK(r.coverage == t.coverage);
  CHECK(r.cluster == c.cluster);
  CHECK(r.weights == c.weights);
  CHECK(r.means == c.means);
  // Payload as documented: mask padded to 8, then (K E + K N E + M N) S + 4 M + 32 K.
  CHECK(compress::payload_bytes(r) == 120 + (3 * 18 + 3 * 2 * 18 + 100 * 2) * 4 + 4 * 100 + 32 * 3);
  const std::string info = compress::describe(compress::read_cprt_header(dir + "/t.cprt"));
  CHECK(contains(info, "lightmap: 12x10 texels (UV set 1"));
  CHECK(contains(info, "compressed texels: 100"));
  // The door for any transfer file: it holds the model; expanded, the decompressed lightmap.
  compress::TransferFile file = compress::open_transfer(dir + "/t.cprt");
  CHECK(file.compressed());
  CHECK(file.header().is_texel());
  const transfer::TransferData loaded = compress::expand(std::move(file));
  CHECK(loaded.header.is_texel());
  CHECK(max_difference(loaded.values, back.values) == 0.0);
  CHECK(max_difference(loaded.bounce_only, back.bounce_only) == 0.0);
  // A per-vertex .cprt is still version 1.
  transfer::TransferData per_vertex = t;
  per_vertex.header.texel_width = per_vertex.header.texel_height = 0;
  per_vertex.coverage.clear();
  per_vertex.header.vertex_count = 120;
  compress::write_cprt(dir + "/v.cprt", compress::compress_transfer(per_vertex, {3, 2}, transfer::Scalar::float32, "vertices"));
  CHECK(static_cast<unsigned char>(read_bytes(dir + "/v.cprt")[8]) == 1);

  // Damage: a mask value out of range, and a header that disagrees with the mask (both resealed).
  const auto fnv = [](const std::string& s, std::size_t begin, std::size_t end) {
    std::uint64_t h = 14695981039346656037ull;
    for (std::size_t i = begin; i < end; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
    return h;
  };
  const auto put64 = [](std::string& s, std::size_t at, std::uint64_t v) {
    for (int b = 0; b < 8; ++b) s[at + b] = static_cast<char>((v >> (8 * b)) & 0xff);
  };
  const std::size_t params = static_cast<unsigned char>(bytes[120]) | (static_cast<unsigned char>(bytes[121]) << 8);
  const std::size_t texel_block = (124 + params + 7) / 8 * 8, header = texel_block + 32 + 8;
  const auto reseal = [&](std::string& s) {
    put64(s, 112, fnv(s, header, s.size()));
    put64(s, header - 8, fnv(s, 0, header - 8));
  };
  const auto error_of = [&](const std::string& damaged) {
    write_file_atomically(dir + "/bad.cprt", damaged);
    try {
      compress::read_cprt(dir + "/bad.cprt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string s = bytes;
  reseal(s);
  CHECK(error_of(s) == "no error");  // the resealing itself is right
  s[header + 3] = 3;
  reseal(s);
  CHECK(contains(error_of(s), "bad.cprt: coverage of texel 3 is 3 (0, 1 or 2 expected)"));
  s = bytes;
  s[header + 5] = transfer::kTexelCovered;  // an empty texel (column 5) marked covered: 101 non-empty
  reseal(s);
  CHECK(contains(error_of(s), "bad.cprt: coverage mask has 101 non-empty texels, the header 100"));
  s = bytes;
  put64(s, texel_block + 24, 121);  // more points than texels
  put64(s, header - 8, fnv(s, 0, header - 8));
  CHECK(contains(error_of(s), "bad.cprt: compressed texel count 121 out of range 1..width x height"));
}

TEST_CASE("prt compress and bake --compress of a lightmap: prt info shows it, prt shade --lightmap and prt render of the .cprt within 1% of the .prt",
          "[compress][lightmap][cli]") {
  const std::string dir = test::fresh_temp_dir("compress_lightmap");
  test::write_obj_with_uv(dir + "/s.obj", test::floor_and_box(true));
  test::write_test_sky(dir + "/sky.exr");
  const std::string prt_path = dir + "/lm.prt", cprt_path = dir + "/lm.cprt";
  REQUIRE(test::run_prt("bake " + dir + "/s.obj --lightmap 48 --transfer interreflected --bounces 1 --samples 128 --quiet -o " + prt_path)
              .exit_code == 0);
  const test::RunResult c = test::run_prt("compress " + prt_path + " --clusters 32 --pca 4 --env " + dir + "/sky.exr -o " + cprt_path);
  INFO(c.output);
  REQUIRE(c.exit_code == 0);
  CHECK(contains(c.output, "texels x 25 values"));  // 5 bands by default
  // bake --lightmap --compress K,N: the same model as prt compress without lighting (same seed).
  REQUIRE(test::run_prt("bake " + dir + "/s.obj --lightmap 48 --transfer interreflected --bounces 1 --samples 128 --quiet --compress 32,4 -o " +
                        dir + "/baked.cprt").exit_code == 0);
  REQUIRE(test::run_prt("compress " + prt_path + " --clusters 32 --pca 4 -q -o " + dir + "/plain.cprt").exit_code == 0);
  CHECK(read_bytes(dir + "/baked.cprt") == read_bytes(dir + "/plain.cprt"));
  CHECK(read_bytes(dir + "/baked.cprt").size() > 1000);
  const test::RunResult info = test::run_prt("info " + cprt_path);
  CHECK(contains(info.output, "lightmap: 48x48 texels (UV set 0"));
  CHECK(contains(info.output, "compressed texels: "));
  CHECK(contains(info.output, "with the bounce-only part"));

  // The decompressed texels written as a .prt: the same shading must come out of the .cprt.
  transfer::write_transfer(dir + "/decompressed.prt", compress::decompress(compress::read_cprt(cprt_path)));
  const std::string shade = "shade " + dir + "/s.obj ";
  const std::string lit = " --env " + dir + "/sky.exr --lightmap -o ";
  for (const char* name : {"lm.prt", "lm.cprt", "decompressed.prt"}) {
    const test::RunResult s = test::run_prt(shade + dir + "/" + name + lit + dir + "/" + name + ".exr");
    INFO(name << ": " << s.output);
    REQUIRE(s.exit_code == 0);
  }
  const image::Image original = image::read_rgb(prt_path + ".exr"), compressed = image::read_rgb(cprt_path + ".exr");
  const image::Image decompressed = image::read_rgb(dir + "/decompressed.prt.exr");
  const image::Difference d = image::compare_values(compressed.pixels.data(), original.pixels.data(), original.pixels.size());
  INFO("compressed lightmap vs uncompressed: rel_rms " << d.rel_rms);
  CHECK(d.rel_rms <= 0.01);  // measured 0.27% (K 32, N 4, 1638 texels)
  CHECK(d.rel_rms > 0.0);  // it is compressed
  CHECK(image::compare_values(compressed.pixels.data(), decompressed.pixels.data(), original.pixels.size()).max_abs == 0.0);

  // prt render of the compressed lightmap (GPU): drawn compressed (texels shaded from the clusters'
  // products), so its frame is the frame of the .prt of its decompressed texels up to float rounding,
  // and near the uncompressed lightmap's.
  const std::string frame = " --env " + dir + "/sky.exr --size 96x72 --camera 30,35,auto --background black -q -o ";
  for (const char* name : {"lm.prt", "lm.cprt", "decompressed.prt"}) {
    const test::RunResult r = test::run_prt("render " + dir + "/s.obj " + dir + "/" + name + frame + dir + "/" + name + ".frame.exr");
    INFO(name << ": " << r.output);
    REQUIRE(r.exit_code == 0);
  }
  const image::Image f_original = image::read_rgb(prt_path + ".frame.exr"), f_compressed = image::read_rgb(cprt_path + ".frame.exr");
  const image::Image f_decompressed = image::read_rgb(dir + "/decompressed.prt.frame.exr");
  const image::Difference rounding = image::compare_values(f_compressed.pixels.data(), f_decompressed.pixels.data(), f_original.pixels.size());
  const double largest = *std::max_element(f_decompressed.pixels.begin(), f_decompressed.pixels.end());
  INFO("frame of the compressed lightmap vs its decompressed texels: max_abs " << rounding.max_abs << " of " << largest);
  CHECK(rounding.max_abs <= 1e-5 * largest);
  const image::Difference f = image::compare_values(f_compressed.pixels.data(), f_original.pixels.data(), f_original.pixels.size());
  INFO("frame of the compressed lightmap vs the uncompressed: rel_rms " << f.rel_rms);
  CHECK(f.rel_rms <= 0.01);
  CHECK(f.reference_rms > 0.0);  // the object is in the frame
}
