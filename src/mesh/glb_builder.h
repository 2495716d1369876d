#pragma once
// Internal to src/mesh (glb_writer.cpp and the engine glTF writers): the BIN chunk of a glTF binary with
// the buffer views and accessors that describe it, and the GLB container (layout in writers.h).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "mesh/mesh.h"

namespace prt::mesh::glb {

inline constexpr int kFloat = 5126;        // glTF componentType FLOAT
inline constexpr int kUnsignedInt = 5125;  // glTF componentType UNSIGNED_INT
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;

/// Accumulates the BIN chunk and the buffer views / accessors that describe it.
struct Builder {
  std::string bin;
  nlohmann::json buffer_views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();

  /// Appends tightly packed data as a new buffer view (4-byte aligned) and an accessor on it;
  /// returns the accessor index.
  int add(const std::string& bytes, std::size_t count, const char* type, int component_type, int target);
  /// `count` elements of `components` floats (vec2, vec3, vec4: `type`) as an ARRAY_BUFFER accessor.
  int add_floats(const float* values, std::size_t count, int components, const char* type);
  /// POSITION: vec3 floats with the accessor's min/max the exact extremes. Precondition: not empty.
  int add_positions(const std::vector<glm::vec3>& positions);
  /// Triangle indices: scalar unsigned int, ELEMENT_ARRAY_BUFFER.
  int add_indices(const std::vector<std::uint32_t>& indices);
  /// Raw bytes (an image) as a buffer view without target or accessor; returns the buffer view index.
  int add_view(const std::string& bytes);
};

/// Whether `name` is an application-specific attribute semantic: '_' then A-Z, 0-9, '_'.
bool valid_semantic(const std::string& name);

/// The glTF accessor type of 1..4 components: "SCALAR", "VEC2", "VEC3", "VEC4".
const char* accessor_type(int components);

/// Throws prt::Error("<path>: cannot write glTF: ...") unless the mesh has vertices and triangles,
/// its indices are in range, its positions finite and its normals absent or one per vertex.
void check_mesh(const std::string& path, const Mesh& mesh);

/// The GLB file: 12-byte header, JSON chunk (`document` with "buffers" set to the BIN chunk's length,
/// padded with spaces), BIN chunk (padded with zeros). Throws prt::Error naming `path` beyond 4 GiB.
std::string container(const std::string& path, nlohmann::json document, std::string bin);

}  // namespace prt::mesh::glb
