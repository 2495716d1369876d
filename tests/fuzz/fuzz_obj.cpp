// libFuzzer target: OBJ meshes with their MTL through load_mesh. The input is the OBJ text, then
// optionally a line "#MTL" followed by the text of input.mtl (the OBJ names it with "mtllib input.mtl").
#include <cstring>

#include "fuzz_support.h"
#include "mesh/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = text.find("\n#MTL\n");
  const std::string obj = text.substr(0, split);
  const std::string mtl = split == std::string::npos ? "" : text.substr(split + 6);
  prt::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(mtl.data()), mtl.size(), "input.mtl");
  const std::string path =
      prt::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(obj.data()), obj.size(), "input.obj");
  prt::fuzz::expect_result_or_error([&] { prt::mesh::load_mesh(path, nullptr, /*quiet=*/true); });
  return 0;
}
