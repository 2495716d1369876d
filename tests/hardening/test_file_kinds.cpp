// Issue 38's round of hostile paths, through the real prt binary: outputs that are devices or FIFOs,
// outputs that are inputs under another name or a file a mesh refers to, FIFOs as transfer inputs,
// finite but huge .cprt models, and options that would size memory beyond the machine.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "hardening/bad_input_files.h"
#include "image/image.h"

namespace prt::test {
namespace {

using Catch::Matchers::Contains;
namespace fs = std::filesystem;

struct Files {
  std::string dir, obj, mtl, gltf, bin, env, prt, cprt, lightmap_obj, lightmap;
};

void require_ok(const RunResult& r) {
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
}

void require_one_line_error(const RunResult& r, const std::string& mentions) {
  INFO(r.output);
  REQUIRE(r.exit_code == 1);
  REQUIRE(is_one_error_line(r.output));
  REQUIRE_THAT(r.output, Contains(mentions));
}

// A folder with an OBJ + MTL quad (with UVs, for a lightmap), a glTF triangle with an external buffer,
// a constant EXR environment, the quad's .prt and .cprt, and a 4x4 lightmap of it.
const Files& files() {
  static const Files f = [] {
    Files out;
    out.dir = fresh_temp_dir("hardening_kinds");
    out.mtl = out.dir + "/quad.mtl";
    write_bytes(out.mtl, "newmtl grey\nKd 0.5 0.5 0.5\n");
    out.obj = out.dir + "/quad.obj";
    write_bytes(out.obj, "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0.1 0.1\nvt 0.9 0.1\nvt 0.9 0.9\n"
                         "vt 0.1 0.9\nusemtl grey\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    out.bin = out.dir + "/tri.bin";
    write_bytes(out.bin, triangle_positions());
    out.gltf = out.dir + "/tri.gltf";
    write_bytes(out.gltf, triangle_gltf_json(R"({"byteLength":36,"uri":"tri.bin"})"));
    out.env = out.dir + "/env.exr";
    image::Image env(8, 4, 3);
    env.pixels.assign(env.pixels.size(), 1.0f);
    image::write(out.env, env);
    out.prt = out.dir + "/quad.prt";
    require_ok(run_prt("bake " + out.obj + " --transfer shadowed --bands 2 --samples 16 -q -o " + out.prt));
    out.cprt = out.dir + "/quad.cprt";
    require_ok(run_prt("compress " + out.prt + " --clusters 1 --pca 1 -q -o " + out.cprt));
    out.lightmap = out.dir + "/lightmap.prt";
    require_ok(run_prt("bake " + out.obj + " --lightmap 4x4 --bands 2 --samples 16 -q -o " + out.lightmap));
    return out;
  }();
  return f;
}

bool is_kind(const std::string& path, mode_t kind) {
  struct stat info;
  return lstat(path.c_str(), &info) == 0 && (info.st_mode & S_IFMT) == kind;
}

TEST_CASE("an output (-o) that is a character device or a FIFO is refused and the node stays what it was", "[hardening][outputs]") {
  const std::string device = files().dir + "/null", fifo = files().dir + "/out.fifo";
  // The same device numbers as /dev/null (1, 3); mknod needs root (CAP_MKNOD), as the issue's report did.
  if (mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    WARN("mknod " << device << ": " << std::strerror(errno) << "; the device half of this test is skipped");
  } else {
    require_one_line_error(run_prt("bake " + files().obj + " --bands 2 --samples 16 -q -o " + device), "not a regular file");
    require_one_line_error(run_prt("compress " + files().prt + " --clusters 1 --pca 1 -q -o " + device), device);
    require_one_line_error(run_prt("light " + files().env + " -o " + device), device);
    REQUIRE(is_kind(device, S_IFCHR));
    // A symbolic link to the device is the device.
    const std::string link = files().dir + "/null_link.prt";
    fs::create_symlink(device, link);
    require_one_line_error(run_prt("bake " + files().obj + " --bands 2 --samples 16 -q -o " + link), "not a regular file");
    REQUIRE(is_kind(link, S_IFLNK));
    REQUIRE(is_kind(device, S_IFCHR));
  }
  REQUIRE(mkfifo(fifo.c_str(), 0644) == 0);
  require_one_line_error(run_prt("bake " + files().obj + " --bands 2 --samples 16 -q -o " + fifo), fifo);
  require_one_line_error(run_prt("shade " + files().obj + " " + files().prt + " --env " + files().env + " -o " + fifo), fifo);
  REQUIRE(is_kind(fifo, S_IFIFO));
  // The control: a regular file is replaced as before.
  write_bytes(files().dir + "/old.prt", "old");
  require_ok(run_prt("bake " + files().obj + " --bands 2 --samples 16 -q -o " + files().dir + "/old.prt"));
  REQUIRE(file_bytes(files().dir + "/old.prt").substr(0, 7) == "PRTXFER");
}

TEST_CASE("an output that is an input under another name, or a file a mesh refers to, is refused first",
          "[hardening][outputs]") {
  const std::string prt_before = file_bytes(files().prt), env_before = file_bytes(files().env);
  const std::string compress = "compress " + files().prt + " --clusters 1 --pca 1 -q -o ";
  require_one_line_error(run_prt(compress + files().prt), "is also the input");
  const std::string relative = "cd " + files().dir + " && " + prt_binary() + " compress quad.prt --clusters 1 --pca 1 -q";
  require_one_line_error(run_shell(relative + " -o ./quad.prt"), "is also the input");
  const std::string hard = files().dir + "/hard_link.prt", soft = files().dir + "/soft_link.prt";
  fs::create_hard_link(files().prt, hard);
  fs::create_symlink(files().prt, soft);
  require_one_line_error(run_prt(compress + hard), "is also the input");
  require_one_line_error(run_prt(compress + soft), "is also the input");
  require_one_line_error(run_prt(compress + files().env + " --env " + files().env), "is also the input");
  REQUIRE(file_bytes(files().prt) == prt_before);
  REQUIRE(file_bytes(files().env) == env_before);
  // Files a mesh refers to: the OBJ's MTL, the glTF's external buffer.
  const std::string mtl_before = file_bytes(files().mtl), bin_before = file_bytes(files().bin);
  require_one_line_error(run_prt("bake " + files().obj + " --bands 2 --samples 16 -q -o " + files().mtl), files().obj);
  require_one_line_error(run_prt("bake " + files().gltf + " --bands 2 --samples 16 -q -o " + files().bin), "is also the input");
  REQUIRE(file_bytes(files().mtl) == mtl_before);
  REQUIRE(file_bytes(files().bin) == bin_before);
  // Before any work: a bake of 2^20 rays per vertex is refused at once.
  const auto start = std::chrono::steady_clock::now();
  require_one_line_error(run_prt("bake " + files().gltf + " --transfer interreflected --samples 1048576 -q -o " + files().bin),
                         "is also the input");
  REQUIRE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5.0);
}

TEST_CASE("a FIFO as the transfer of info, shade, shade --lightmap and render is refused, not waited on",
          "[hardening][io]") {
  const std::string fifo = files().dir + "/transfer_fifo.prt";
  REQUIRE(mkfifo(fifo.c_str(), 0644) == 0);
  // `timeout` turns a hang (the bug) into exit status 124 instead of a test that never ends.
  const std::string prt = "timeout 20 " + prt_binary() + " ";
  require_one_line_error(run_shell(prt + "info " + fifo), "not a regular file");
  const std::string lit = " --env " + files().env + " -o " + files().dir;
  require_one_line_error(run_shell(prt + "shade " + files().obj + " " + fifo + lit + "/fifo.ply"), "not a regular file");
  require_one_line_error(run_shell(prt + "shade " + files().obj + " " + fifo + " --lightmap" + lit + "/fifo.exr"),
                         "not a regular file");
  const RunResult render = run_shell(prt + "render " + files().obj + " " + fifo + lit + "/fifo.png");
  INFO(render.output);
  REQUIRE(render.exit_code == 1);  // the transfer, or no OpenGL on this machine: either way no hang
  REQUIRE(is_one_error_line(render.output));
  REQUIRE(is_kind(fifo, S_IFIFO));
}

// The .cprt at `path` with the float32 payload value at `index` set to `value`, both checksums redone
// (docs/formats.md, "Compressed transfer files": the payload's FNV-1a at 112, the header's at H).
std::string cprt_with_value(const std::string& path, std::size_t index, float value) {
  std::string bytes = file_bytes(path);
  std::uint32_t params = 0;
  std::memcpy(&params, bytes.data() + 120, 4);
  std::size_t h = 124 + params;
  h = (h + 7) / 8 * 8;
  const std::size_t payload = h + 8;
  std::memcpy(&bytes[payload + 4 * index], &value, 4);
  std::string checksum;
  put64(checksum, fnv1a(bytes.substr(payload)));
  bytes.replace(112, 8, checksum);
  checksum.clear();
  put64(checksum, fnv1a(bytes.substr(0, h)));
  bytes.replace(h, 8, checksum);
  return bytes;
}

TEST_CASE("a .cprt whose means, directions or weights are finite but huge is refused, not shaded to Inf",
          "[hardening][cprt]") {
  // quad.cprt: K = 1, N = 1, E = D = 4 (2 bands, 1 channel), 4 vertices: means [0, 4), directions
  // [4, 8), weights [8, 12).
  const std::string shade = "shade " + files().obj + " ";
  const std::string lit = " --env " + files().env + " -o " + files().dir + "/huge.ply";
  for (const auto& [index, mentions] : {std::pair<std::size_t, const char*>{0, "cluster mean"}, {5, "cluster direction"},
                                        {9, "vertex 1"}}) {
    const std::string path = files().dir + "/huge" + std::to_string(index) + ".cprt";
    write_bytes(path, cprt_with_value(files().cprt, index, 3e38f));
    const RunResult r = run_prt(shade + path + lit);
    require_one_line_error(r, path);
    REQUIRE_THAT(r.output, Contains(mentions));
  }
  REQUIRE_FALSE(fs::exists(files().dir + "/huge.ply"));
  require_ok(run_prt(shade + files().cprt + lit));  // the control: the file as compress wrote it
}

TEST_CASE("a probe grid or a bake whose memory cannot fit is refused at once, naming the option",
          "[hardening][memory]") {
  auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // 2^26 probes of 16 bands: about 400 GiB by the estimate, more than any machine these tests run on.
  const RunResult probes = run_prt("probes " + files().obj + " --env " + files().env + " --grid 4096,4096,4 --bands 16 "
                                   "--format prt -q -o " + files().dir + "/big.prtprobes");
  require_one_line_error(probes, "--grid 4096,4096,4");
  REQUIRE_THAT(probes.output, Contains("GiB"));
  REQUIRE(seconds() < 15.0);  // ~0.5 s alone; the bound only tells a refusal from a run (a loaded CI machine has taken 5 s)
  REQUIRE_FALSE(fs::exists(files().dir + "/big.prtprobes"));
  // Glossy 32 x 32 bands: 12 MiB of transfer per vertex; 128 x 128 vertices need about 1 TiB.
  std::string grid;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) grid += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
  for (int y = 0; y + 1 < 128; ++y)
    for (int x = 0; x + 1 < 128; ++x) {
      const int a = y * 128 + x + 1;
      grid += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 129) + "\n";
    }
  write_bytes(files().dir + "/grid.obj", grid);
  start = std::chrono::steady_clock::now();
  const RunResult bake = run_prt("bake " + files().dir + "/grid.obj --transfer glossy-shadowed --brdf phong:exponent=8,ks=0.5 "
                                 "--bands 32 --bands-out 32 --samples 64 -q -o " + files().dir + "/big.prt");
  require_one_line_error(bake, "--bands 32");
  REQUIRE_THAT(bake.output, Contains("GiB"));
  REQUIRE(seconds() < 20.0);
  REQUIRE_FALSE(fs::exists(files().dir + "/big.prt"));
}

}  // namespace
}  // namespace prt::test
