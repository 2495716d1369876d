// The compressed default's CPCA setting (compress/ship_defaults.h) against the .cprt format's own
// payload size (cprt_file.h payload_bytes, which the writer uses): for meshes from 100 to 10^6
// vertices, 1 and 3 channels, with and without the bounce-only section, the file payload stays within
// the uncompressed 5-band float32 payload, and N is the largest that does (or the cap of 24): one
// vector more, what a rule that undercounts the bytes would choose, fails the first check.
#include <catch2/catch.hpp>

#include <algorithm>

#include "compress/cprt_file.h"
#include "compress/ship_defaults.h"

using namespace prt;

namespace {

transfer::Header header(std::uint64_t vertices, int channels, int bands, transfer::Scalar scalar, bool bounce) {
  transfer::Header h;
  h.kind = bounce ? transfer::Kind::interreflected : transfer::Kind::shadowed;
  h.bands = static_cast<std::uint32_t>(bands);
  h.channels = static_cast<std::uint32_t>(channels);
  h.vertex_count = vertices;
  h.scalar = scalar;
  h.bounce_only_section = bounce;
  return h;
}

std::uint64_t cprt_payload(std::uint64_t vertices, int channels, bool bounce, int clusters, int pca) {
  compress::CompressedTransfer c;
  c.source = header(vertices, channels, compress::kHighBands, transfer::Scalar::float16, bounce);
  c.clusters = clusters;
  c.pca = pca;
  c.bounce = bounce;
  return compress::payload_bytes(c);
}

}  // namespace

TEST_CASE("ship default: the .cprt payload fits the 5-band .prt payload, with the largest N that fits", "[accuracy][ship]") {
  for (std::uint64_t vertices : {100ull, 227ull, 1000ull, 10000ull, 23000ull, 100000ull, 1000000ull})
    for (int channels : {1, 3})
      for (bool bounce : {false, true}) {
        CAPTURE(vertices, channels, bounce);
        const compress::ShipCompression ship = compress::ship_compression(vertices, channels, bounce ? 2 : 1, compress::kHighBands);
        CHECK(ship.clusters == std::clamp<std::uint64_t>(vertices / 256, 1, 64));
        REQUIRE(ship.pca >= 1);
        REQUIRE(ship.pca <= 24);
        // The 5-band float32 .prt's values: V x channels x 25 floats per section.
        const std::uint64_t budget = vertices * channels * 25 * 4 * (bounce ? 2 : 1);
        CHECK(cprt_payload(vertices, channels, bounce, ship.clusters, ship.pca) <= budget);
        // Largest: one more vector does not fit (the rule's estimate counts 32 bytes per cluster more than
        // the format's per-cluster error sums take).
        if (ship.pca < 24) CHECK(cprt_payload(vertices, channels, bounce, ship.clusters, ship.pca + 1) + 32 * ship.clusters > budget);
      }
}

TEST_CASE("ship default: the metric prior's rotation-averaged spectrum is (l+1)^-2", "[accuracy][ship]") {
  const sh::RgbCoefficients sky = compress::ship_metric_sky(16);
  for (int l = 0; l < 16; ++l) {
    double power = 0.0;
    for (int m = -l; m <= l; ++m) power += sky.values[static_cast<std::size_t>(l * (l + 1) + m)].y * sky.values[static_cast<std::size_t>(l * (l + 1) + m)].y;
    CHECK(power / (2 * l + 1) == Approx(1.0 / ((l + 1.0) * (l + 1.0))).epsilon(1e-12));
  }
}

TEST_CASE("texel ship default: the texel .cprt payload fits the 5-band texel .prt payload, with the largest N that fits",
          "[accuracy][ship][lightmap]") {
  // Lightmaps from 16^2 to 2048^2 texels, a third to all of them non-empty (covered or gutter).
  for (std::uint64_t side : {16ull, 64ull, 512ull, 2048ull})
    for (std::uint64_t fill : {3ull, 2ull, 1ull})  // points = texels / fill
      for (bool bounce : {false, true}) {
        const std::uint64_t texels = side * side, points = texels / fill;
        CAPTURE(side, fill, bounce);
        const compress::ShipCompression ship = compress::ship_texel_compression(points, texels, 1, bounce ? 2 : 1, compress::kHighBands);
        CHECK(ship.clusters == static_cast<int>(std::clamp<std::uint64_t>(points / 256, 1, 64)));
        REQUIRE(ship.pca >= 1);
        REQUIRE(ship.pca <= 24);
        compress::CompressedTransfer c;
        c.source = header(0, 1, compress::kHighBands, transfer::Scalar::float16, bounce);
        c.source.texel_width = c.source.texel_height = static_cast<std::uint32_t>(side);
        c.clusters = ship.clusters;
        c.bounce = bounce;
        c.texel_points = points;
        // The 5-band float32 texel .prt: the same coverage mask, then W x H x 25 floats per section.
        const std::uint64_t mask = (texels + 7) / 8 * 8, budget = mask + texels * 25 * 4 * (bounce ? 2 : 1);
        c.pca = ship.pca;
        CHECK(compress::payload_bytes(c) <= budget);
        c.pca = ship.pca + 1;
        if (ship.pca < 24) CHECK(compress::payload_bytes(c) + 32 * ship.clusters > budget);
      }
}
