// Hostile probe, transfer, lighting, points, BRDF and image files (issue 10's list): each gives one
// prt::Error naming the file, decided from the header before anything large is allocated.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "brdf/brdf_file.h"
#include "core/error.h"
#include "hardening/bad_input_files.h"
#include "image/image.h"
#include "light/light_file.h"
#include "probes/probe_file.h"
#include "probes/probe_set.h"
#include "transfer/transfer_file.h"

namespace prt::test {
namespace {

using Catch::Matchers::Contains;

std::string put(const std::string& name, const std::string& bytes) {
  return write_in("hardening_files", name, bytes);
}

std::string hex(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

// A 1-band probe file assembled from probes/prt/README.md: `count` probes (positions, coefficients,
// valid, backface_fraction), a grid layout with counts_json, the header's "count" = header_count and
// `parameters` as the parameters' JSON text. backface is every probe's back-face fraction, bounds_json
// the grid's bounds.
std::string probe_file(std::size_t count, const std::string& counts_json, std::uint64_t header_count,
                       const std::string& parameters = "{}", float backface = 0.25f,
                       const std::string& bounds_json = "[[0,0,0],[1,1,1]]") {
  std::string payload, arrays;
  auto add = [&](const std::string& name, const std::string& type, const std::string& shape, const std::string& bytes) {
    while (payload.size() % 8) payload.push_back('\0');
    arrays += std::string(arrays.empty() ? "" : ",") + R"({"name":")" + name + R"(","type":")" + type +
              R"(","shape":)" + shape + R"(,"offset":)" + std::to_string(payload.size()) + R"(,"bytes":)" +
              std::to_string(bytes.size()) + "}";
    payload += bytes;
  };
  const std::string n = std::to_string(count);
  std::vector<float> positions(3 * count, 0.5f), coefficients(3 * count, 1.0f), fractions(count, backface);
  auto raw = [](const std::vector<float>& v) { return std::string(reinterpret_cast<const char*>(v.data()), 4 * v.size()); };
  add("positions", "float32", "[" + n + ",3]", raw(positions));
  add("coefficients", "float32", "[" + n + ",1,3]", raw(coefficients));
  add("valid", "uint8", "[" + n + "]", std::string(count, '\1'));
  add("backface_fraction", "float32", "[" + n + "]", raw(fractions));
  while (payload.size() % 8) payload.push_back('\0');
  std::string header = R"({"format":"prt-probes","version":1,"bands":1,"basis":"real-orthonormal-condon-shortley",)"
                       R"("index":"l*(l+1)+m","frame":"right-handed, +Y up","quantity":"incident radiance","count":)" +
                       std::to_string(header_count) + R"(,"layout":{"type":"grid","counts":)" + counts_json +
                       R"(,"bounds":)" + bounds_json + R"(},"sky":[[1,1,1]],"parameters":)" + parameters +
                       R"(,"arrays":[)" + arrays + R"(],"payload_bytes":)" + std::to_string(payload.size()) +
                       R"(,"payload_fnv1a64":")" + hex(fnv1a(payload)) + "\"}\n";
  while (header.size() % 8) header.push_back(' ');
  std::string out = "PRTPROBE";
  put32(out, 1);
  put32(out, static_cast<std::uint32_t>(header.size()));
  return out + header + payload;
}

TEST_CASE("the hand-made probe file of these tests is valid", "[hardening][probes]") {
  const probes::ProbeSet p = probes::parse_probe_file(probe_file(8, "[2,2,2]", 8), "ok.prtprobes");
  REQUIRE(p.count() == 8);
  REQUIRE(p.grid.counts[2] == 2);
  REQUIRE(p.backface_fraction[7] == 0.25f);
}

TEST_CASE("probe header parameters nested 100000 deep are refused before parsing", "[hardening][probes]") {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  REQUIRE_THROWS_WITH(probes::parse_probe_file(probe_file(8, "[2,2,2]", 8, deep), "deep.prtprobes"),
                      Contains("deep.prtprobes") && Contains("nested deeper than 64"));
}

TEST_CASE("probe grid counts [-1,-1,8] and counts above 2^31 are refused", "[hardening][probes]") {
  REQUIRE_THROWS_WITH(probes::parse_probe_file(probe_file(8, "[-1,-1,8]", 8), "neg.prtprobes"),
                      Contains("grid count -1"));
  // 2^32 + 1 truncated to int is 1: 1 x 1 x 8 would have matched the count.
  REQUIRE_THROWS_WITH(probes::parse_probe_file(probe_file(8, "[4294967297,1,8]", 8), "big.prtprobes"),
                      Contains("grid count 4294967297"));
}

TEST_CASE("a NaN back-face fraction in a probe file is refused", "[hardening][probes]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  REQUIRE_THROWS_WITH(probes::parse_probe_file(probe_file(8, "[2,2,2]", 8, "{}", nan), "nan.prtprobes"),
                      Contains("backface_fraction"));
  REQUIRE_THROWS_WITH(probes::parse_probe_file(probe_file(8, "[2,2,2]", 8, "{}", 1.5f), "big.prtprobes"),
                      Contains("backface_fraction"));
}

TEST_CASE("a 5 KB probe file claiming 67108864 probes fails at once, without allocating", "[hardening][probes]") {
  const std::string bytes = probe_file(8, "[8192,8192,1]", 67108864);
  const auto start = std::chrono::steady_clock::now();
  REQUIRE_THROWS_WITH(probes::parse_probe_file(bytes, "many.prtprobes"), Contains("need more than the payload"));
  REQUIRE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 0.5);
}

TEST_CASE("wrong JSON types in a probe header are prt::Errors", "[hardening][probes]") {
  const std::string bytes = probe_file(8, "[2,2,2]", 8, "{}", 0.25f, R"([["a",0,0],[1,1,1]])");
  REQUIRE_THROWS_AS(probes::parse_probe_file(bytes, "types.prtprobes"), prt::Error);
  REQUIRE_THROWS_WITH(probes::parse_probe_file(bytes, "types.prtprobes"), Contains("must be a number"));
}

TEST_CASE("1e999 in an SH light or a points JSON is a prt::Error", "[hardening][json]") {
  const std::string light = put("light_e999.json", R"({"bands":1,"basis":"real-orthonormal-condon-shortley",)"
                                                   R"("index":"l*(l+1)+m","frame":"right-handed, +Y up",)"
                                                   R"("coefficients":[[1e999,0,0]]})");
  REQUIRE_THROWS_AS(light::read_light_file(light), prt::Error);
  const std::string points = put("points_e999.json", "[[0,0,1e999]]");
  REQUIRE_THROWS_AS(probes::read_points_file(points), prt::Error);
  REQUIRE_THROWS_WITH(probes::read_points_file(points), Contains(points));
}

TEST_CASE("an SH coefficient of 1.7e308 is refused (it made every pixel NaN)", "[hardening][light]") {
  const std::string head = R"({"bands":1,"basis":"real-orthonormal-condon-shortley","index":"l*(l+1)+m",)"
                           R"("frame":"right-handed, +Y up","coefficients":[[)";
  const std::string path = put("light_huge.json", head + "1.7e308,0,0]]}");
  REQUIRE_THROWS_WITH(light::read_light_file(path), Contains(path) && Contains("out of range"));
  REQUIRE(light::read_light_file(put("light_ok.json", head + "1e17,0,0]]}")).values[0].x == 1e17);
}

// A 1-band, 1-channel float32 transfer file (docs/formats.md) with the given vertex count, every
// payload value `value`, and valid checksums.
std::string transfer_file(std::uint64_t vertex_count, float value) {
  std::string h = "PRTXFER";
  h.push_back('\0');
  put32(h, 1);  // version
  put32(h, 0);  // unshadowed
  put32(h, 1);  // bands
  put32(h, 0);  // output bands
  put32(h, 1);  // channels
  put32(h, 0);  // float32
  put64(h, vertex_count);
  put64(h, 1);  // triangles
  put64(h, 0);  // fingerprint
  // The payload size a forger writes: 4 x count, wrapped to 64 bits (16 bytes for 2^62 + 4), and a
  // payload of exactly that size, so that only the overflow could make the sizes agree.
  const std::uint64_t payload_size = 4 * vertex_count;
  std::string payload;
  for (std::uint64_t i = 0; i < payload_size / 4; ++i) payload.append(reinterpret_cast<const char*>(&value), 4);
  put64(h, payload_size);
  put64(h, fnv1a(payload));
  put32(h, 2);
  h += "{}";
  while (h.size() % 8) h.push_back('\0');
  put64(h, fnv1a(h));
  return h + payload;
}

TEST_CASE("a .prt vertex count of 2^62+4 does not pass the size check by overflow", "[hardening][prt]") {
  REQUIRE(transfer::read_transfer(put("ok.prt", transfer_file(1, 0.5f))).values[0] == 0.5f);
  const std::string path = put("wrap.prt", transfer_file((std::uint64_t{1} << 62) + 4, 0.5f));
  REQUIRE_THROWS_WITH(transfer::read_transfer(path), Contains(path) && Contains("do not fit"));
}

TEST_CASE("NaN or Inf in a .prt payload with valid checksums is refused", "[hardening][prt]") {
  const std::string nan = put("nan.prt", transfer_file(1, std::numeric_limits<float>::quiet_NaN()));
  REQUIRE_THROWS_WITH(transfer::read_transfer(nan), Contains(nan) && Contains("not finite"));
  const std::string inf = put("inf.prt", transfer_file(1, std::numeric_limits<float>::infinity()));
  REQUIRE_THROWS_WITH(transfer::read_transfer(inf), Contains("not finite"));
}

TEST_CASE("a BRDF of 300 lobes is refused at once - 16 are accepted", "[hardening][brdf]") {
  std::string spec = "phong:exponent=8,ks=0.001";
  for (int i = 1; i < 300; ++i) spec += "+phong:exponent=8,ks=0.001";
  REQUIRE_THROWS_WITH(brdf::parse_brdf(spec), Contains("300 lobes, more than 16"));
  std::string sixteen = "phong:exponent=8,ks=0.01";
  for (int i = 1; i < 16; ++i) sixteen += "+phong:exponent=8,ks=0.01";
  REQUIRE(brdf::parse_brdf(sixteen).lobes.size() == 16);
}

TEST_CASE("a BRDF matrix JSON whose version or format has another type is a prt::Error", "[hardening][brdf]") {
  // Found by fuzz_brdf: json::value() threw type_error past the reader.
  const std::string version = put("version_string.json", R"({"format":"prt-brdf-matrix","version":"1"})");
  REQUIRE_THROWS_AS(brdf::read_brdf_matrix(version), prt::Error);
  REQUIRE_THROWS_WITH(brdf::read_brdf_matrix(version), Contains(version) && Contains("unsupported version"));
  const std::string format = put("format_number.json", R"({"format":7,"version":1})");
  REQUIRE_THROWS_WITH(brdf::read_brdf_matrix(format), Contains("not a prt BRDF matrix"));
}

TEST_CASE("a BRDF matrix with a NaN value is refused", "[hardening][brdf]") {
  std::string bin = "PRTBRDF1";
  put32(bin, 1);  // bands
  put32(bin, 1);  // channels
  put32(bin, 0);  // spec length
  put32(bin, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bin.append(reinterpret_cast<const char*>(&nan), 8);
  const std::string path = put("nan_brdf.bin", bin);
  REQUIRE_THROWS_WITH(brdf::read_brdf_matrix(path), Contains(path) && Contains("not finite"));
}

// A PNG (ISO/IEC 15948) with the given IHDR size and one tiny IDAT.
std::string png_declaring(std::uint32_t width, std::uint32_t height) {
  std::string ihdr;
  for (std::uint32_t v : {width, height})
    for (int k = 3; k >= 0; --k) ihdr.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, deflate, no filter, no interlace
  const std::string idat("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);  // an empty zlib stream
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat) + png_chunk("IEND", "");
}

TEST_CASE("a tiny PNG declaring 60000x30000 pixels is refused from its header", "[hardening][image]") {
  const std::string path = put("huge.png", png_declaring(60000, 30000));
  REQUIRE_THROWS_WITH(image::read_rgb(path), Contains(path) && Contains("exceeds prt's limits"));
  // Timed after the first read has loaded the image backend: no 2.4 GB allocation happens.
  const auto start = std::chrono::steady_clock::now();
  REQUIRE_THROWS_WITH(image::read_rgb(put("wide.png", png_declaring(20000, 10000))), Contains("exceeds"));
  REQUIRE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 1.0);
}

}  // namespace
}  // namespace prt::test
