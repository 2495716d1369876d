// CPCA on real transfer at the acceptance settings: glossy shadowed transfer of a bowl and of
// the bundled lion, K in 64..256 and N = 8, and diffuse interreflected transfer with N = 4.
// The measure is the shaded radiance of `prt shade` (the CPU reference: the sun as an exact disc, the
// sky as SH through the transfer, the sun's bounce light through the bounce-only part) of the
// decompressed transfer against the uncompressed one under the bundled sunrise environment: glossy
// toward three eye points, relative rms over all vertices and channels. CPCA runs in the shaded
// metric of that lighting (compress/metric.h), as `prt compress --env` does.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "brdf/projection.h"
#include "compress/compressed.h"
#include "image/compare.h"
#include "light/disc.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "shade/glossy.h"
#include "shade/scene_shading.h"
#include "shade/shade.h"
#include "support/shapes.h"

using namespace prt;

namespace {

const std::string kSunrise = PRT_SOURCE_DIR "/assets/env/sunrise.exr";

// The lighting as `prt shade` splits it by default: the sun as an exact disc, the rest as windowed SH.
light::SceneLighting split_sunrise(bool glossy, const glm::dvec3& yaw_pitch_roll = glm::dvec3(0.0)) {
  light::WindowRequest window;
  window.radiance = glossy;
  return light::load_scene_lighting(kSunrise, 5, yaw_pitch_roll, light::SunRequest{}, window);
}

// The whole lighting as SH (`--sun none --window none`): the sun rings through every band.
sh::RgbCoefficients unsplit_sunrise() {
  light::SunRequest none;
  none.mode = light::SunRequest::Mode::none;
  return light::load_scene_lighting(kSunrise, 5, glm::dvec3(0.0), none, light::parse_window_request("none")).sky;
}

double rel_rms(const std::vector<glm::vec3>& test, const std::vector<glm::vec3>& reference) {
  return image::compare_values(&test[0].x, &reference[0].x, 3 * test.size()).rel_rms;
}

transfer::TransferData bake_glossy(const mesh::Mesh& m, int samples) {
  bake::BakeOptions o;
  o.kind = transfer::Kind::glossy_shadowed;
  o.bands = 5;
  o.samples = samples;
  o.brdf = brdf::parse_brdf("phong:exponent=16,ks=0.5,kd=0.4");
  return bake::bake(m, o);
}

transfer::TransferData bake_interreflected(const mesh::Mesh& m, int samples) {
  bake::BakeOptions o;
  o.kind = transfer::Kind::interreflected;
  o.bands = 5;
  o.samples = samples;
  o.bounces = 2;
  return bake::bake(m, o);
}

// CPCA in the shaded metric of `lighting` (sky SH for the transfer, the discs' SH for its bounce part),
// as `prt compress --env` does.
compress::CompressedTransfer compress_for(const transfer::TransferData& t, int clusters, int pca, const light::SceneLighting& lighting) {
  const sh::RgbCoefficients discs = light::discs_coefficients(5, lighting.discs);
  const compress::Metric metric = compress::transfer_metric(t, {&lighting.sky, &discs}, "test");
  return compress::compress_transfer(t, {clusters, pca}, transfer::Scalar::float32, "test", &metric);
}

const std::vector<glm::vec3> kEyeDirections = {glm::vec3(0.1f, 1.0f, 0.6f), glm::vec3(1.0f, 0.5f, -0.7f), glm::vec3(-0.9f, 0.3f, 0.3f)};

glm::vec3 eye_point(const mesh::Mesh& m, const glm::vec3& direction) {
  const mesh::Bounds bounds = mesh::bounds(m);
  return 0.5f * (bounds.lo + bounds.hi) + bounds.diagonal() * glm::normalize(direction);
}

// Worst rel_rms over three eye points of `prt shade` (split lighting: SH sky through the transfer, the
// sun's direct light exact) of the decompressed transfer against the original.
double glossy_error(const mesh::Mesh& m, const transfer::TransferData& original, const compress::CompressedTransfer& c,
                    const light::SceneLighting& lighting) {
  const transfer::TransferData approximate = compress::decompress(c);
  const brdf::Brdf surface = shade::baked_brdfs(original.header, "original").table.at(0);
  const brdf::BrdfMatrix b = brdf::project(surface, 5);
  double worst = 0;
  for (const glm::vec3& direction : kEyeDirections) {
    const glm::vec3 eye = eye_point(m, direction);
    worst = std::max(worst, rel_rms(shade::shade_glossy_split(m, approximate, surface, b, lighting, eye, "compressed"),
                                    shade::shade_glossy_split(m, original, surface, b, lighting, eye, "original")));
  }
  return worst;
}

// The same with the whole lighting as SH (no disc), for the record.
double glossy_error_unsplit(const mesh::Mesh& m, const transfer::TransferData& original, const compress::CompressedTransfer& c) {
  const transfer::TransferData approximate = compress::decompress(c);
  const brdf::BrdfMatrix b = brdf::project(shade::baked_brdfs(original.header, "original").table.at(0), 5);
  double worst = 0;
  for (const glm::vec3& direction : kEyeDirections) {
    const glm::vec3 eye = eye_point(m, direction);
    worst = std::max(worst, rel_rms(shade::shade_glossy_eye(approximate, b, unsplit_sunrise(), m.positions, m.normals, eye),
                                    shade::shade_glossy_eye(original, b, unsplit_sunrise(), m.positions, m.normals, eye)));
  }
  return worst;
}

double diffuse_error(const mesh::Mesh& m, const transfer::TransferData& original, const compress::CompressedTransfer& c,
                     const light::SceneLighting& lighting) {
  return rel_rms(shade::shade_diffuse_split(m, compress::decompress(c), lighting, "compressed"),
                 shade::shade_diffuse_split(m, original, lighting, "original"));
}

}  // namespace

TEST_CASE("CPCA of converged transfer of a bowl: glossy K 64 N 8 within 2%, diffuse K 64 N 4 within 1%", "[compress][slow]") {
  // 2048 directions per vertex: with fewer, the Monte Carlo noise of the uncompressed matrices (which
  // no low-rank model keeps) weighs more in the difference.
  const mesh::Mesh surface = test::bowl(40, 80);
  const light::SceneLighting glossy_light = split_sunrise(true);
  REQUIRE(glossy_light.discs.size() == 1);  // the sun
  const transfer::TransferData t = bake_glossy(surface, 2048);
  const compress::CompressedTransfer c = compress_for(t, 64, 8, glossy_light);
  const double error = glossy_error(surface, t, c, glossy_light);
  INFO("bowl glossy: transfer " << c.total.transfer_relative() << ", radiance " << error << ", whole lighting as SH "
                                << glossy_error_unsplit(surface, t, c));
  CHECK(error <= 0.02);

  // Diffuse interreflected transfer of the same bowl, N = 4; its bounce-only part is compressed with it.
  const transfer::TransferData d = bake_interreflected(surface, 1024);
  const light::SceneLighting light = split_sunrise(false);
  const compress::CompressedTransfer dc = compress_for(d, 64, 4, light);
  REQUIRE(dc.bounce);
  const double diffuse = diffuse_error(surface, d, dc, light);
  INFO("bowl diffuse: transfer " << dc.total.transfer_relative() << ", radiance " << diffuse);
  CHECK(diffuse <= 0.01);
}

TEST_CASE("CPCA of the lion: glossy K 64 N 8 within 3%, diffuse interreflected K 1024 N 4 within 1%", "[compress][slow]") {
  const mesh::Mesh lion = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/guardian_lion_10k.ply", nullptr, true);
  const light::SceneLighting glossy_light = split_sunrise(true);
  const transfer::TransferData glossy = bake_glossy(lion, 1024);
  const compress::CompressedTransfer gc = compress_for(glossy, 64, 8, glossy_light);
  const double glossy_radiance = glossy_error(lion, glossy, gc, glossy_light);
  INFO("lion glossy: transfer " << gc.total.transfer_relative() << ", radiance " << glossy_radiance);
  // 3%, not the 2% of the windowed sky: the default --window auto no longer windows the sky (it clamps the
  // shaded values, docs/conventions.md), so the glossy radiance keeps band 4's ringing, which a rank-8 model
  // keeps less of (2.72% measured, 2.87% turned).
  CHECK(glossy_radiance <= 0.03);
  // The metric averages over rotations of the lighting: another orientation of the same sky is as good.
  const glm::dvec3 turn(120.0, 35.0, 0.0);
  const double turned = glossy_error(lion, glossy, gc, split_sunrise(true, turn));
  INFO("lion glossy, environment turned (yaw 120, pitch 35): " << turned);
  CHECK(turned <= 0.03);

  // Diffuse interreflected, N = 4, with the bounce-only part in the same model (50 values per point).
  // The lion needs many clusters at N = 4: K 256 gives 1.40%, K 512 1.08%, K 768 0.83% (note of issue
  // 13: the error is the model's capacity -- neither bake noise, nor the seed, nor the shared cluster
  // assignment of the two parts); the issue fixes N = 4 here, not K. Checked in the sky's orientation
  // and turned, as for glossy.
  const transfer::TransferData t = bake_interreflected(lion, 256);
  const light::SceneLighting light = split_sunrise(false);
  const compress::CompressedTransfer c = compress_for(t, 1024, 4, light);
  const double error = diffuse_error(lion, t, c, light);
  const double diffuse_turned = diffuse_error(lion, t, c, split_sunrise(false, turn));
  INFO("lion diffuse: transfer " << c.total.transfer_relative() << ", radiance " << error << ", turned " << diffuse_turned);
  CHECK(error <= 0.01);
  CHECK(diffuse_turned <= 0.01);
}
