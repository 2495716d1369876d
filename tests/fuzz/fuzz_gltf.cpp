// libFuzzer target: glTF 2.0 through load_mesh; an input starting with "glTF" is read as .glb,
// anything else as .gltf (JSON). External buffers resolve against the scratch folder.
#include <cstring>

#include "fuzz_support.h"
#include "mesh/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = prt::fuzz::write_input(data, size, binary ? "input.glb" : "input.gltf");
  prt::fuzz::expect_result_or_error([&] { prt::mesh::load_mesh(path, nullptr, /*quiet=*/true); });
  return 0;
}
