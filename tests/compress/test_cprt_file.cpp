// The .cprt format (docs/formats.md, "Compressed transfer files"): round trip, float16, sizes against
// the documented layout, and one named one-line error for each kind of damage.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>

#include "compress/cprt_file.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

// A small glossy transfer (2 bands in and out, 1 channel: 4 x 4 = 16 values per vertex), smooth in v.
transfer::TransferData small_transfer(std::size_t vertices) {
  transfer::TransferData t;
  t.header.kind = transfer::Kind::glossy_shadowed;
  t.header.bands = 2;
  t.header.bands_out = 2;
  t.header.channels = 1;
  t.header.vertex_count = vertices;
  t.header.triangle_count = 7;
  t.header.mesh_fingerprint = 0x1234567890abcdefull;
  t.header.parameters_json = R"({"brdf":"phong:exponent=8,ks=0.5,kd=0.3"})";
  for (std::size_t v = 0; v < vertices; ++v)
    for (int i = 0; i < 16; ++i) t.values.push_back(static_cast<float>(std::sin(0.01 * v * (i + 1)) + 0.01 * i));
  return t;
}

// FNV-1a 64, written out here (docs/formats.md), to re-seal patched headers.
std::uint64_t fnv(const std::string& s, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
  return h;
}
void put64(std::string& s, std::size_t at, std::uint64_t v) {
  for (int b = 0; b < 8; ++b) s[at + b] = static_cast<char>((v >> (8 * b)) & 0xff);
}
void put32(std::string& s, std::size_t at, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) s[at + b] = static_cast<char>((v >> (8 * b)) & 0xff);
}
std::uint32_t get32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int b = 0; b < 4; ++b) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + b])) << (8 * b);
  return v;
}
// Header length H (the header checksum sits at H - 8).
std::size_t header_length(const std::string& s) { return (124 + get32(s, 120) + 7) / 8 * 8 + 8; }
void reseal_header(std::string& s) {
  const std::size_t h = header_length(s);
  put64(s, h - 8, fnv(s, h - 8));
}
void reseal_payload(std::string& s) {
  const std::size_t h = header_length(s);
  const std::string payload = s.substr(h);
  put64(s, 112, fnv(payload, payload.size()));
}

std::string error_of(const std::string& path) {
  try {
    compress::read_cprt(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE(".cprt round trip: every field and array, sizes as documented, float16 halves the values", "[compress]") {
  const std::string dir = test::fresh_temp_dir("cprt_file");
  const transfer::TransferData t = small_transfer(60);
  const compress::CpcaOptions o{3, 2};
  compress::CompressedTransfer c = compress::compress_transfer(t, o, transfer::Scalar::float32, "small");
  sh::RgbCoefficients light(2);
  light.values[0] = glm::dvec3(1.0, 0.8, 0.6);
  light.values[2] = glm::dvec3(0.3, 0.2, 0.1);
  compress::add_radiance_error(c, t, light, "small");
  compress::write_cprt(dir + "/a.cprt", c);
  const compress::CompressedTransfer r = compress::read_cprt(dir + "/a.cprt");
  CHECK(r.source.kind == t.header.kind);
  CHECK(r.source.mesh_fingerprint == t.header.mesh_fingerprint);
  CHECK(r.source.parameters_json == t.header.parameters_json);
  CHECK(r.clusters == 3);
  CHECK(r.pca == 2);
  CHECK(r.iterations == c.iterations);
  CHECK(r.means == c.means);
  CHECK(r.bases == c.bases);
  CHECK(r.weights == c.weights);
  CHECK(r.cluster == c.cluster);
  CHECK(r.has_radiance_error);
  CHECK(r.total.radiance_error2 == c.total.radiance_error2);
  CHECK(r.per_cluster[1].transfer_error2 == c.per_cluster[1].transfer_error2);
  // Layout: header 124 + JSON, padded to 8, + 8; payload (K D + K N D + P N) * 4 + 4 P + 32 K.
  const std::string bytes = read_file(dir + "/a.cprt");
  const std::size_t json = t.header.parameters_json.size();
  CHECK(bytes.size() == (124 + json + 7) / 8 * 8 + 8 + (3 * 16 + 3 * 2 * 16 + 60 * 2) * 4 + 4 * 60 + 32 * 3);
  // float16: the values take half the bytes, and the stored values are what the errors describe.
  compress::CompressedTransfer h = compress::compress_transfer(t, o, transfer::Scalar::float16, "small");
  compress::write_cprt(dir + "/h.cprt", h);
  CHECK(read_file(dir + "/h.cprt").size() == (124 + json + 7) / 8 * 8 + 8 + (3 * 16 + 3 * 2 * 16 + 60 * 2) * 2 + 4 * 60 + 32 * 3);
  const compress::CompressedTransfer hr = compress::read_cprt(dir + "/h.cprt");
  CHECK(hr.means == h.means);
  // The decompressed transfer's error is the recorded one.
  const transfer::TransferData back = compress::decompress(r);
  double e = 0, n = 0;
  for (std::size_t i = 0; i < back.values.size(); ++i) {
    e += (double(back.values[i]) - t.values[i]) * (double(back.values[i]) - t.values[i]);
    n += double(t.values[i]) * t.values[i];
  }
  CHECK(std::sqrt(e / n) == Approx(r.total.transfer_relative()).epsilon(1e-6));
  CHECK(r.total.transfer_relative() < 0.5);
}

TEST_CASE(".cprt with the bounce-only part: 2D values per mean and direction, both parts come back", "[compress]") {
  const std::string dir = test::fresh_temp_dir("cprt_bounce");
  transfer::TransferData t = small_transfer(50);
  t.header.kind = transfer::Kind::glossy_interreflected;
  for (std::size_t i = 0; i < t.values.size(); ++i) t.bounce_only.push_back(0.25f * t.values[i] + 0.01f * static_cast<float>(i % 16));
  const compress::CompressedTransfer c = compress::compress_transfer(t, {3, 2}, transfer::Scalar::float32, "small");
  REQUIRE(c.bounce);
  CHECK(c.point_dimension() == 32);
  compress::write_cprt(dir + "/b.cprt", c);
  const std::string bytes = read_file(dir + "/b.cprt");
  const std::size_t json = t.header.parameters_json.size();
  CHECK(bytes.size() == (124 + json + 7) / 8 * 8 + 8 + (3 * 32 + 3 * 2 * 32 + 50 * 2) * 4 + 4 * 50 + 32 * 3);
  CHECK(get32(bytes, 44) == 2);  // flags: bit 1, the bounce-only section
  const compress::CompressedTransfer r = compress::read_cprt(dir + "/b.cprt");
  CHECK(r.bounce);
  CHECK(r.means == c.means);
  CHECK(r.bases == c.bases);
  // Both parts reconstruct (mean + 2 directions of 32 values fitted to data that vary smoothly).
  const transfer::TransferData back = compress::decompress(r);
  REQUIRE(back.bounce_only.size() == t.bounce_only.size());
  double e = 0, n = 0;
  for (std::size_t i = 0; i < t.bounce_only.size(); ++i) {
    e += (double(back.bounce_only[i]) - t.bounce_only[i]) * (double(back.bounce_only[i]) - t.bounce_only[i]);
    n += double(t.bounce_only[i]) * t.bounce_only[i];
  }
  CHECK(std::sqrt(e / n) < 0.05);
  // The reconstruction of each part is the model's: mean + sum_n w_n b_n over that part's values.
  const std::size_t p = 17, k = r.cluster[p];
  for (std::size_t i = 0; i < 16; ++i) {
    double x = r.means[k * 32 + 16 + i];
    for (std::size_t j = 0; j < 2; ++j) x += double(r.weights[p * 2 + j]) * r.bases[(k * 2 + j) * 32 + 16 + i];
    CHECK(back.bounce_only[p * 16 + i] == Approx(x).margin(1e-6));
  }
}

TEST_CASE(".cprt readers name each kind of damage in one line", "[compress]") {
  const std::string dir = test::fresh_temp_dir("cprt_damage");
  const compress::CpcaOptions o{2, 2};
  compress::write_cprt(dir + "/good.cprt", compress::compress_transfer(small_transfer(40), o, transfer::Scalar::float32, "small"));
  const std::string good = read_file(dir + "/good.cprt");
  const auto check = [&](const std::string& bytes, const std::string& expected) {
    const std::string path = dir + "/bad.cprt";
    write_file_atomically(path, bytes);
    const std::string message = error_of(path);
    INFO(message);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.rfind(path + ": ", 0) == 0);
    CHECK(message.find(expected) != std::string::npos);
  };
  CHECK(error_of(dir + "/good.cprt") == "no error");
  check(good.substr(0, 50), "truncated: 50 bytes is shorter than a compressed transfer header");
  std::string s = good;
  s[0] = 'X';
  check(s, "wrong magic");
  s = good;
  put32(s, 8, 3);  // 1 = per vertex, 2 = texel
  check(s, "unsupported compressed transfer file version 3");
  s = good;
  put32(s, 32, 3);  // K changed without resealing
  check(s, "header checksum mismatch");
  const std::pair<std::size_t, std::uint32_t> fields[] = {{12, 9}, {16, 0}, {20, 0}, {24, 2}, {28, 5}, {32, 0}, {32, 41},
                                                          {36, 0}, {36, 17}, {40, 0}, {44, 4}, {44, 2}};
  const char* names[] = {"unknown transfer kind 9", "bands 0", "output bands 0", "channels 2", "unknown scalar type 5",
                         "cluster count 0", "cluster count 41", "PCA count 0", "PCA count 17", "iteration count 0", "unknown flags 4",
                         "flags: a bounce-only section in a glossy-shadowed transfer"};
  for (std::size_t i = 0; i < std::size(fields); ++i) {
    s = good;
    put32(s, fields[i].first, fields[i].second);
    reseal_header(s);
    check(s, names[i]);
  }
  s = good;
  put64(s, 72, 0xfff0000000000000ull);  // -inf transfer error
  reseal_header(s);
  check(s, "error statistics are negative or not finite");
  s = good;
  put64(s, 104, 12);
  reseal_header(s);
  check(s, "payload size does not match");
  check(good.substr(0, good.size() - 3), "truncated: payload has");
  check(good + "x", "unexpected bytes after the payload");
  s = good;
  s[header_length(s) + 5] ^= 1;
  check(s, "payload checksum mismatch");
  // A cluster id >= K, and a NaN mean, with a valid checksum.
  const std::size_t ids = header_length(good) + (2 * 16 + 2 * 2 * 16 + 40 * 2) * 4;
  s = good;
  put32(s, ids + 4 * 7, 2);
  reseal_payload(s);
  reseal_header(s);
  check(s, "cluster id 2 out of range (2 clusters)");
  s = good;
  put32(s, header_length(good), 0x7fc00000u);
  reseal_payload(s);
  reseal_header(s);
  check(s, "non-finite value in the cluster means");
}
