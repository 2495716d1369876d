// Compressed and multi-scene glTF through the real binary (issue 33): a Draco and a meshopt file bake
// the same bytes as the plain glTF that another tool (gltf-transform, scripts/make_compressed_gltf.sh)
// decoded them to; unsupported required extensions, corrupt compressed data and scene indices out of
// range are one line naming the file, with no output file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "core/atomic_file.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

const std::string kData = std::string(PRT_SOURCE_DIR) + "/tests/data/gltf/";

/// Bakes `mesh` (interreflected, so that the decoded albedo and every bounce count too) to dir/name.prt.
std::string bake(const std::string& mesh, const std::string& dir, const std::string& name, const std::string& extra = "") {
  const std::string out = dir + "/" + name + ".prt";
  const test::RunResult r = test::run_prt("bake " + mesh + " --transfer interreflected --bounces 2 --samples 256 --bands 4 "
                                          "--threads 2 -q -o " + out + " " + extra);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return read_file(out);
}

}  // namespace

TEST_CASE("Draco and meshopt glTF bake the same bytes as their decoding by gltf-transform", "[bake][cli][gltf]") {
  const std::string dir = test::fresh_temp_dir("compressed_gltf");
  for (const char* codec : {"draco", "meshopt"}) {
    INFO(codec);
    const std::string compressed = bake(kData + "box_textured_" + codec + ".glb", dir, std::string(codec));
    const std::string plain = bake(kData + "box_textured_" + codec + "_decoded.glb", dir, std::string(codec) + "_plain");
    CHECK(compressed.size() > 1000);
    CHECK(compressed == plain);
  }
}

TEST_CASE("Bad compressed or multi-scene glTF is one line naming the file, and no output", "[bake][cli][gltf]") {
  const std::string dir = test::fresh_temp_dir("compressed_gltf_bad");
  const std::string out = dir + "/out.prt";
  const std::string draco = read_file(kData + "box_textured_draco.glb");
  const std::string meshopt = read_file(kData + "box_textured_meshopt.glb");
  auto check_fails = [&](const std::string& name, const std::string& bytes, const std::string& expected,
                         const std::string& extra = "") {
    const std::string path = dir + "/" + name;
    write_file_atomically(path, bytes);
    const test::RunResult r = test::run_prt("bake " + path + " -q --samples 16 -o " + out + " " + extra);
    INFO(r.output);
    CHECK(test::fails_in_one_line(r, path + ": " + expected));
    CHECK(!std::filesystem::exists(out));
    std::filesystem::remove(out);  // so that one failure does not fail the checks after it
  };
  auto replaced = [](std::string bytes, const std::string& from, const std::string& to) {
    REQUIRE(from.size() == to.size());  // the GLB's chunk lengths stay right
    const std::size_t at = bytes.find(from);
    REQUIRE(at != std::string::npos);
    return bytes.replace(at, from.size(), to);
  };
  check_fails("instancing.glb",
              replaced(draco, "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]",
                       "\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"   ]"),
              "requires glTF extension EXT_mesh_gpu_instancing, which prt does not support");
  // The Draco mesh's bytes: "DRACO" magic first; a wrong magic and a truncated mesh.
  check_fails("bad_magic.glb", replaced(draco, "DRACO", "DRACX"),
              "mesh 0 primitive 0 (KHR_draco_mesh_compression): the Draco data is corrupt or truncated (Not a Draco file.)");
  check_fails("truncated_draco.glb", replaced(draco, "\"byteOffset\":2440,\"byteLength\":233", "\"byteOffset\":2440,\"byteLength\": 40"),
              "mesh 0 primitive 0 (KHR_draco_mesh_compression): the Draco data is corrupt or truncated (Failed to decode point attributes.)");
  check_fails("truncated_meshopt.glb", replaced(meshopt, "\"byteOffset\":2536,\"byteLength\":139", "\"byteOffset\":2536,\"byteLength\": 39"),
              "buffer view 3 (EXT_meshopt_compression): the compressed data is corrupt or truncated (meshoptimizer error -2)");
  check_fails("huge_meshopt.glb", replaced(meshopt, "\"byteOffset\":2536,\"byteLength\":139", "\"byteOffset\":2536,\"byteLength\":  1"),
              "buffer view 3 (EXT_meshopt_compression): count 24 is too large for 1 compressed bytes");
  // The meshopt vertex stream of that view starts with its header byte (0xa0); any other is corrupt.
  std::string bad_header = meshopt;
  const std::size_t bin = 20 + std::size_t(std::uint8_t(meshopt[12])) + 256 * std::size_t(std::uint8_t(meshopt[13])) + 8;
  REQUIRE(std::uint8_t(bad_header.at(bin + 2536)) == 0xa0);
  bad_header[bin + 2536] = 0;
  check_fails("bad_header_meshopt.glb", bad_header,
              "buffer view 3 (EXT_meshopt_compression): the compressed data is corrupt or truncated (meshoptimizer error -1)");
  check_fails("scene.glb", draco, "scene 3 does not exist (the file has 1 scene)", "--scene 3");
}
