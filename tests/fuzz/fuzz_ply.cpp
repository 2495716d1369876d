// libFuzzer target: PLY meshes through load_mesh (header, ASCII and binary bodies, finish_mesh).
#include "fuzz_support.h"
#include "mesh/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = prt::fuzz::write_input(data, size, "input.ply");
  prt::fuzz::expect_result_or_error([&] { prt::mesh::load_mesh(path, nullptr, /*quiet=*/true); });
  return 0;
}
