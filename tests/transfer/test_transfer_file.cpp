// Transfer files: exact round trips and a precise error for every kind of damage.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "transfer/half.h"
#include "transfer/transfer_file.h"

namespace fs = std::filesystem;
using namespace prt::transfer;

namespace {

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / "prt_test_transfer";
  fs::create_directories(dir);
  return dir;
}

TransferData sample_data(Kind kind, std::uint32_t bands, std::uint32_t channels, Scalar scalar) {
  TransferData d;
  d.header.kind = kind;
  d.header.bands = bands;
  d.header.bands_out = is_glossy(kind) ? 2 : 0;
  d.header.channels = channels;
  d.header.scalar = scalar;
  d.header.vertex_count = 7;
  d.header.triangle_count = 3;
  d.header.mesh_fingerprint = 0x0123456789abcdefull;
  d.header.parameters_json = R"({"samples":1024,"seed":5})";
  d.values.resize(d.header.vertex_count * d.header.values_per_vertex());
  for (std::size_t i = 0; i < d.values.size(); ++i) d.values[i] = static_cast<float>(i) * 0.37f - 3.0f;
  return d;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const prt::Error& e) {
    return e.what();
  }
  return "";
}

void corrupt_byte(const fs::path& p, std::uint64_t offset) {
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(offset));
  char c;
  f.get(c);
  f.seekp(static_cast<std::streamoff>(offset));
  f.put(static_cast<char>(c ^ 0x5a));
}

}  // namespace

TEST_CASE("transfer files round-trip bit-exactly in float32", "[transfer]") {
  for (Kind kind : {Kind::unshadowed, Kind::shadowed, Kind::interreflected, Kind::glossy_shadowed}) {
    for (std::uint32_t channels : {1u, 3u}) {
      TransferData d = sample_data(kind, 3, channels, Scalar::float32);
      fs::path p = temp_dir() / "roundtrip.prt";
      write_transfer(p.string(), d);
      TransferData r = read_transfer(p.string());
      CHECK(r.header.kind == kind);
      CHECK(r.header.bands == 3);
      CHECK(r.header.bands_out == d.header.bands_out);
      CHECK(r.header.channels == channels);
      CHECK(r.header.vertex_count == 7);
      CHECK(r.header.triangle_count == 3);
      CHECK(r.header.mesh_fingerprint == 0x0123456789abcdefull);
      CHECK(r.header.parameters_json == d.header.parameters_json);
      REQUIRE(r.values == d.values);
    }
  }
}

TEST_CASE("float16 transfer files store the nearest half of every value", "[transfer]") {
  TransferData d = sample_data(Kind::shadowed, 5, 3, Scalar::float16);
  fs::path p = temp_dir() / "half.prt";
  write_transfer(p.string(), d);
  TransferData r = read_transfer(p.string());
  REQUIRE(r.values.size() == d.values.size());
  for (std::size_t i = 0; i < d.values.size(); ++i) REQUIRE(r.values[i] == half_to_float(float_to_half(d.values[i])));
  // The payload is half the float32 size.
  CHECK(fs::file_size(p) < 7 * 75 * 4);
}

TEST_CASE("transfer readers say exactly what is wrong", "[transfer]") {
  TransferData d = sample_data(Kind::shadowed, 3, 1, Scalar::float32);
  fs::path p = temp_dir() / "damaged.prt";
  auto fresh = [&] { write_transfer(p.string(), d); };

  fresh();
  std::uint64_t size = fs::file_size(p);
  fs::resize_file(p, size - 5);
  CHECK(error_of([&] { read_transfer(p.string()); }).find("truncated: payload") != std::string::npos);

  fresh();
  fs::resize_file(p, 20);
  CHECK(error_of([&] { read_transfer(p.string()); }).find("truncated") != std::string::npos);

  fresh();
  corrupt_byte(p, 0);
  CHECK(error_of([&] { read_transfer(p.string()); }).find("wrong magic") != std::string::npos);

  fresh();
  corrupt_byte(p, 8);
  CHECK(error_of([&] { read_transfer(p.string()); }).find("unsupported transfer file version") != std::string::npos);

  fresh();
  corrupt_byte(p, 48);  // fingerprint
  CHECK(error_of([&] { read_transfer(p.string()); }).find("header checksum mismatch") != std::string::npos);

  fresh();
  corrupt_byte(p, size - 3);  // inside the payload
  CHECK(error_of([&] { read_transfer(p.string()); }).find("payload checksum mismatch") != std::string::npos);
  // The header alone is still fine.
  CHECK(read_transfer_header(p.string()).bands == 3);

  fresh();
  {
    std::ofstream f(p, std::ios::app | std::ios::binary);
    f << "x";
  }
  CHECK(error_of([&] { read_transfer(p.string()); }).find("unexpected bytes after the payload") != std::string::npos);

  CHECK(error_of([&] { read_transfer((temp_dir() / "missing.prt").string()); }).find("missing.prt: cannot open") !=
        std::string::npos);

  std::string msg = error_of([&] { check_mesh_match("t.prt", d.header, 8, 3, d.header.mesh_fingerprint); });
  CHECK(msg.rfind("t.prt: transfer was baked for a different mesh", 0) == 0);
  CHECK(error_of([&] { check_mesh_match("t.prt", d.header, 7, 3, d.header.mesh_fingerprint); }).empty());
  CHECK_FALSE(error_of([&] { check_mesh_match("t.prt", d.header, 7, 3, 1); }).empty());
}

TEST_CASE("an inconsistent header is refused before anything is written", "[transfer]") {
  TransferData d = sample_data(Kind::shadowed, 3, 1, Scalar::float32);
  d.values.pop_back();
  fs::path p = temp_dir() / "never.prt";
  fs::remove(p);
  CHECK_THROWS_AS(write_transfer(p.string(), d), prt::Error);
  CHECK_FALSE(fs::exists(p));
  d = sample_data(Kind::shadowed, 33, 1, Scalar::float32);
  CHECK(error_of([&] { write_transfer(p.string(), d); }).find("bands 33 out of range") != std::string::npos);
  CHECK(error_of([] { parse_kind("glossy"); }).find("unknown transfer kind 'glossy'") != std::string::npos);
}
