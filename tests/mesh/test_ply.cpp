// PLY: ASCII and binary (both endians) loading, colours (sRGB uchar, linear float), degenerate faces,
// errors on truncated or garbled files, and the colour PLY writer/reader round trip.
#include <random>

#include <catch2/catch.hpp>

#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "mesh_test_util.h"

using namespace prt::mesh;
using namespace prt::mesh::test;

namespace {

// Reference sRGB decodings (IEC 61966-2-1), from published tables: 128 -> 0.21586050,
// 188 -> 0.50288646, 10 -> 0.00303527 (linear segment: 10/255/12.92).
constexpr double kSrgb128 = 0.21586050011389926;
constexpr double kSrgb188 = 0.5028864580325687;
constexpr double kSrgb10 = 0.003035269835488375;

/// A binary PLY with mixed property types, an ignored ushort vertex property, float colours, an
/// extra element, and a quad. `big_endian` selects the encoding.
std::string binary_ply(bool big_endian) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment mixed types\nelement vertex 4\nproperty float x\nproperty double y\n"
                  "property float z\nproperty ushort flags\nproperty float nx\nproperty float ny\nproperty float nz\n"
                  "property float red\nproperty float green\nproperty float blue\n"
                  "element face 1\nproperty list uchar uint vertex_indices\nproperty int face_flags\n"
                  "element extra 2\nproperty list int short stuff\nend_header\n";
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  const float rgb[4][3] = {{0.25f, 0.5f, 1.0f}, {0, 0, 0}, {1, 1, 1}, {0.125f, 0.75f, 0.375f}};
  for (int i = 0; i < 4; ++i) {
    put(s, xyz[i][0], big_endian);
    put(s, double(xyz[i][1]), big_endian);
    put(s, xyz[i][2], big_endian);
    put(s, std::uint16_t(0xBEEF), big_endian);
    put(s, 0.0f, big_endian);
    put(s, 0.0f, big_endian);
    put(s, 2.0f, big_endian);  // not unit: normalised on load
    for (int c = 0; c < 3; ++c) put(s, rgb[i][c], big_endian);
  }
  s.push_back(4);
  for (std::uint32_t v : {0u, 1u, 2u, 3u}) put(s, v, big_endian);
  put(s, std::int32_t(-5), big_endian);
  put(s, std::int32_t(2), big_endian);
  put(s, std::int16_t(7), big_endian);
  put(s, std::int16_t(8), big_endian);
  put(s, std::int32_t(0), big_endian);
  return s;
}

const char* kAsciiPly =
    "ply\r\n"
    "format ascii 1.0\r\n"
    "comment uchar colours, CRLF header\r\n"
    "obj_info anything\r\n"
    "element vertex 5\r\n"
    "property float x\r\nproperty float y\r\nproperty float z\r\n"
    "property uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\nproperty uchar alpha\r\n"
    "element face 3\r\n"
    "property list uchar int vertex_index\r\n"
    "end_header\r\n"
    "0 0 0 0 128 255 9\n"
    "1 0 0 188 10 0 9\n"
    "1 1 0 255 255 255 9\n"
    "0 1 0 0 0 0 9\n"
    "0.1 0.2 -0.3 1 2 3 9\n"
    "4 0 1 2 3\n"
    "2 0 1\n"     // a segment: skipped
    "3 0 0 1\n";  // repeated vertex: skipped

}  // namespace

TEST_CASE("ASCII PLY with uchar sRGB colours: linearised albedo and fan triangles and skipped faces", "[mesh][ply]") {
  LoadReport report;
  const Mesh mesh = load_mesh(write_temp("colours.ply", kAsciiPly), &report, true);
  REQUIRE(mesh.vertex_count() == 5);
  CHECK(mesh.positions[0] == glm::vec3(0, 0, 0));
  CHECK(mesh.positions[2] == glm::vec3(1, 1, 0));
  CHECK(mesh.positions[4] == glm::vec3(0.1f, 0.2f, -0.3f));  // parsed as float: correctly rounded
  CHECK(mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  CHECK(report.skipped_degenerate == 2);
  CHECK(report.normals_computed);
  for (int i = 0; i < 4; ++i) CHECK(mesh.normals[i] == glm::vec3(0, 0, 1));
  CHECK(mesh.normals[4] == glm::vec3(0, 1, 0));  // in no triangle
  REQUIRE(report.albedo_from_file);
  CHECK(mesh.albedo[0].x == 0.0f);
  CHECK(mesh.albedo[0].y == Approx(kSrgb128).epsilon(1e-7));
  CHECK(mesh.albedo[0].z == 1.0f);
  CHECK(mesh.albedo[1].x == Approx(kSrgb188).epsilon(1e-7));
  CHECK(mesh.albedo[1].y == Approx(kSrgb10).epsilon(1e-7));
  CHECK(mesh.albedo[2] == glm::vec3(1.0f));
  REQUIRE(report.notes.size() == 2);
  CHECK(report.notes[0] == "skipped 2 degenerate triangles (repeated vertex, zero area, or fewer than 3 vertices)");
  // Vertex 4 is in no triangle: +Y, not counted.
  CHECK(report.notes[1] == "computed area-weighted normals for 4 of 5 vertices (the file has no normals)");
}

TEST_CASE("Binary PLY little and big endian give the same mesh and float colours are linear", "[mesh][ply]") {
  LoadReport report;
  const Mesh little = load_mesh(write_temp("little.ply", binary_ply(false)), &report, true);
  const Mesh big = load_mesh(write_temp("big.ply", binary_ply(true)), nullptr, true);
  REQUIRE(little.vertex_count() == 4);
  CHECK(little.positions[3] == glm::vec3(0, 1, 0.5f));
  CHECK(little.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  for (const glm::vec3& n : little.normals) CHECK(n == glm::vec3(0, 0, 1));
  CHECK_FALSE(report.normals_computed);
  CHECK(little.albedo[0] == glm::vec3(0.25f, 0.5f, 1.0f));
  CHECK(little.albedo[3] == glm::vec3(0.125f, 0.75f, 0.375f));
  CHECK(little.positions == big.positions);
  CHECK(little.normals == big.normals);
  CHECK(little.albedo == big.albedo);
  CHECK(little.indices == big.indices);
  CHECK(fingerprint(little) == fingerprint(big));
}

TEST_CASE("PLY errors: truncated or garbled or out of range or non-finite", "[mesh][ply]") {
  const std::string good = binary_ply(false);
  const std::size_t header_end = good.find("end_header\n") + 11;

  // Every truncation inside the data is an error that says so.
  for (std::size_t length = header_end; length < good.size() - 18; ++length) {
    const std::string path = write_temp("truncated.ply", good.substr(0, length));
    const std::string message = error_of([&] { load_mesh(path, nullptr, true); });
    INFO("length " << length << ": " << message);
    CHECK_THAT(message, Catch::StartsWith(path + ": truncated PLY data"));
  }
  const std::string cut = write_temp("cut.ply", good.substr(0, header_end + 60));
  CHECK(error_of([&] { load_mesh(cut, nullptr, true); }) ==
        cut + ": truncated PLY data: the header declares 4 vertex elements, more than the file can hold");
  const std::string cut_list = write_temp("cut_list.ply", good.substr(0, header_end + 183));
  CHECK(error_of([&] { load_mesh(cut_list, nullptr, true); }) ==
        cut_list + ": truncated PLY data: a list of 4 items in face 0 of 1");
  const std::string cut_face = write_temp("cut_face.ply", good.substr(0, header_end + 4 * 42 + 1 + 4 * 4 + 2));
  CHECK(error_of([&] { load_mesh(cut_face, nullptr, true); }) ==
        cut_face + ": truncated PLY data: it ends in face 0 of 1");

  auto ascii = [](const std::string& body) {
    return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           body;
  };
  const std::string bad_value = write_temp("bad_value.ply", ascii("0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"));
  CHECK(error_of([&] { load_mesh(bad_value, nullptr, true); }) ==
        bad_value + ": bad PLY value \"zero\" for property y in vertex 1 of 3");
  const std::string range = write_temp("range.ply", ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
  CHECK(error_of([&] { load_mesh(range, nullptr, true); }) ==
        range + ": face 0 refers to vertex 3, but the file has 3 vertices");
  const std::string nan = write_temp("nan.ply", ascii("0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"));
  CHECK(error_of([&] { load_mesh(nan, nullptr, true); }) == nan + ": vertex 1 has a non-finite position (1, nan, 0)");
  const std::string no_faces =
      write_temp("no_faces.ply",
                 "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                 "property float z\nend_header\n0 0 0\n");
  CHECK(error_of([&] { load_mesh(no_faces, nullptr, true); }) == no_faces + ": no triangles (the file has no faces)");
  const std::string no_end = write_temp("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  CHECK(error_of([&] { load_mesh(no_end, nullptr, true); }) == no_end + ": malformed PLY header: no end_header line");
  const std::string bad_type =
      write_temp("bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n");
  CHECK(error_of([&] { load_mesh(bad_type, nullptr, true); }) ==
        bad_type + ": malformed PLY header, line 4: unknown property type \"half\"");
  const std::string no_z = write_temp(
      "no_z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n");
  CHECK(error_of([&] { load_mesh(no_z, nullptr, true); }) == no_z + ": the PLY vertex element lacks x, y or z");
  const std::string huge = write_temp("huge.ply",
                                      "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n"
                                      "property float x\nproperty float y\nproperty float z\nend_header\n");
  CHECK(error_of([&] { load_mesh(huge, nullptr, true); }) ==
        huge +
            ": truncated PLY data: the header declares 18446744073709551615 vertex elements, more than the file can "
            "hold");
  const std::string not_ply = write_temp("obj_inside.ply", "v 0 0 0\n");
  CHECK(error_of([&] { load_mesh(not_ply, nullptr, true); }) ==
        not_ply + ": not a PLY file (its content looks like text)");
}

TEST_CASE("Garbled PLY files load or fail with prt::Error and never crash", "[mesh][ply]") {
  std::mt19937 rng(12345);
  for (const std::string& original : {binary_ply(false), binary_ply(true), std::string(kAsciiPly)}) {
    for (int trial = 0; trial < 200; ++trial) {
      std::string bytes = original;
      const int flips = 1 + int(rng() % 4);
      for (int k = 0; k < flips; ++k) bytes[rng() % bytes.size()] = char(rng() % 256);
      const std::string path = write_temp("garbled.ply", bytes);
      try {
        load_mesh(path, nullptr, true);
      } catch (const prt::Error&) {
      }
    }
  }
  SUCCEED("no crash and no exception other than prt::Error");
}

TEST_CASE("write_ply / read_ply_colours round-trip bit for bit", "[mesh][ply][writer]") {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1.5f, -2.25f, 1e-30f}, {0.1f, 0.2f, 0.3f}, {-7, 8, 9}};
  const std::vector<glm::vec3> colours = {{0, 0.5f, 1}, {3.75f, 1e-20f, 123456.7f}, {-0.0f, 0.3f, 2}, {1, 1, 1}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const std::string path = temp_path("radiance.ply");
  write_ply(path, positions, colours, indices);
  const std::string bytes = read_bytes(path);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by prt\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nproperty float red\nproperty float green\n"
      "property float blue\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK(bytes.substr(0, header.size()) == header);
  CHECK(bytes.size() == header.size() + 4 * 24 + 2 * 13);

  const ColourPly back = read_ply_colours(path);
  REQUIRE(back.positions.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(same_bits(back.positions[i], positions[i]));
    CHECK(same_bits(back.colours[i], colours[i]));
  }
  CHECK(back.indices == indices);

  // Without colours: load_mesh reads it; read_ply_colours refuses it.
  const std::string plain = temp_path("plain.ply");
  write_ply(plain, positions, {}, indices);
  const Mesh mesh = load_mesh(plain, nullptr, true);
  CHECK(mesh.positions == positions);
  CHECK(mesh.indices == indices);
  CHECK(mesh.albedo.empty());
  CHECK(error_of([&] { read_ply_colours(plain); }) == plain + ": the PLY vertices have no red, green, blue properties");
  const std::string uchar = write_temp("uchar.ply", kAsciiPly);
  CHECK(error_of([&] { read_ply_colours(uchar); }) ==
        uchar + ": the PLY colours are integers (8-bit display colours), not float radiance");

  CHECK(error_of([&] {
          write_ply(temp_path("bad.ply"), positions, {{0, 0, 0}}, indices);
        }) == temp_path("bad.ply") + ": cannot write PLY: 1 colours for 4 vertices");
  CHECK(error_of([&] { write_ply(temp_path("no_folder/x.ply"), positions, colours, indices); }) ==
        temp_path("no_folder/x.ply") + ": output folder does not exist");
}

TEST_CASE("PLY with a NaN and a zero normal: those two are computed, the others kept bit for bit", "[mesh][ply][normals]") {
  // Two triangles of the plane z = 0 sharing an edge; file normals lean (not +Z), vertex 1's is NaN,
  // vertex 3's zero: only those two get the area-weighted normal, +Z exactly.
  const std::string path = write_temp("nan_normal.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                                      "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                      "0 0 0 0.6 0 0.8\n1 0 0 nan 0 1\n1 1 0 0 0.6 0.8\n0 1 0 0 0 0\n3 0 1 2\n3 0 2 3\n");
  LoadReport report;
  const Mesh mesh = load_mesh(path, &report, true);
  CHECK(report.computed_normal_count == 2);
  CHECK(report.notes.back() ==
        "computed area-weighted normals for 2 of 4 vertices (2 of the file's normals are zero or not finite)");
  CHECK(mesh.normals[0] == glm::vec3(0.6f, 0.0f, 0.8f));
  CHECK(mesh.normals[2] == glm::vec3(0.0f, 0.6f, 0.8f));
  CHECK(mesh.normals[1] == glm::vec3(0, 0, 1));
  CHECK(mesh.normals[3] == glm::vec3(0, 0, 1));
}
