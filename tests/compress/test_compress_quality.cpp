// The acceptance settings of CPCA on real transfer: glossy shadowed transfer of a bowl and of the
// bundled lion, K in 64..256 and N = 8, and diffuse interreflected transfer of the lion with N = 4.
// The measure is the shaded radiance (prt::shade, the CPU reference) of the decompressed transfer
// against the uncompressed one under the bundled sunrise environment: glossy toward three eye points,
// relative rms over all vertices and channels.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "brdf/projection.h"
#include "compress/compressed.h"
#include "image/compare.h"
#include "light/environment.h"
#include "light/projection.h"
#include "mesh/mesh.h"
#include "shade/glossy.h"
#include "shade/shade.h"
#include "support/shapes.h"

using namespace prt;

namespace {

const sh::RgbCoefficients& sunrise() {
  static const sh::RgbCoefficients l = light::project(light::load_environment(PRT_SOURCE_DIR "/assets/env/sunrise.exr"), 5);
  return l;
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

// Worst rel_rms over three eye points of the decompressed transfer against the original.
double glossy_error(const mesh::Mesh& m, const transfer::TransferData& original, const compress::CompressedTransfer& c) {
  const transfer::TransferData approximate = compress::decompress(c);
  const brdf::BrdfMatrix b = brdf::project(shade::baked_brdf(original.header, "original"), 5);
  const mesh::Bounds bounds = mesh::bounds(m);
  const glm::vec3 centre = 0.5f * (bounds.lo + bounds.hi);
  const float radius = bounds.diagonal();
  double worst = 0;
  for (const glm::vec3 direction : {glm::vec3(0.1f, 1.0f, 0.6f), glm::vec3(1.0f, 0.5f, -0.7f), glm::vec3(-0.9f, 0.3f, 0.3f)}) {
    const glm::vec3 eye = centre + radius * glm::normalize(direction);
    const auto test = shade::shade_glossy_eye(approximate, b, sunrise(), m.positions, m.normals, eye);
    const auto reference = shade::shade_glossy_eye(original, b, sunrise(), m.positions, m.normals, eye);
    worst = std::max(worst, rel_rms(test, reference));
  }
  return worst;
}

}  // namespace

TEST_CASE("CPCA of glossy shadowed transfer, N = 8: shaded radiance within 2% (bowl K = 64, lion K = 128)", "[compress][slow]") {
  const mesh::Mesh surface = test::bowl(40, 80);
  const transfer::TransferData t = bake_glossy(surface, 256);
  const compress::CompressedTransfer c = compress::compress_transfer(t, {64, 8}, transfer::Scalar::float32, "bowl");
  const double bowl_error = glossy_error(surface, t, c);
  INFO("bowl: transfer " << c.total.transfer_relative() << ", radiance " << bowl_error);
  CHECK(bowl_error <= 0.02);

  const mesh::Mesh lion = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/chinese_dragon_10k.ply", nullptr, true);
  const transfer::TransferData lt = bake_glossy(lion, 128);
  const compress::CompressedTransfer lc = compress::compress_transfer(lt, {128, 8}, transfer::Scalar::float32, "lion");
  const double lion_error = glossy_error(lion, lt, lc);
  INFO("lion: transfer " << lc.total.transfer_relative() << ", radiance " << lion_error);
  CHECK(lion_error <= 0.02);
}

TEST_CASE("CPCA of diffuse interreflected transfer of the lion, K = 64, N = 4: shaded radiance within 1%", "[compress][slow]") {
  const mesh::Mesh lion = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/chinese_dragon_10k.ply", nullptr, true);
  bake::BakeOptions o;
  o.kind = transfer::Kind::interreflected;
  o.bands = 5;
  o.samples = 256;
  o.bounces = 2;
  const transfer::TransferData t = bake::bake(lion, o);
  compress::CompressedTransfer c = compress::compress_transfer(t, {64, 4}, transfer::Scalar::float32, "lion");
  const double error = rel_rms(shade::shade_diffuse(compress::decompress(c), sunrise()), shade::shade_diffuse(t, sunrise()));
  INFO("transfer " << c.total.transfer_relative() << ", radiance " << error);
  CHECK(error <= 0.01);
  // The error the compressor records under the same lighting is this one.
  compress::add_radiance_error(c, t, sunrise(), "lion");
  CHECK(c.total.radiance_relative() == Approx(error).epsilon(1e-3));
}
