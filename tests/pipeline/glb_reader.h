#pragma once
// The tests' own reading of a GLB file (not prt's), by the glTF 2.0 specification's layout: the JSON
// chunk, the BIN chunk and float accessors.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace prt::test {

struct Glb {
  nlohmann::json doc;
  std::string bin;  ///< the BIN chunk's bytes (empty without one)
};

/// Reads `path`: checks the magic and the total length (Catch REQUIRE), splits the chunks.
Glb parse_glb(const std::string& path);

/// Float accessor `index` (tightly packed or with byteStride), its components element by element.
std::vector<float> floats(const Glb& glb, int index);

/// The bytes of buffer view `index`.
std::string view_bytes(const Glb& glb, int index);

}  // namespace prt::test
