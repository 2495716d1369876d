#pragma once
// Internal to prt_mesh: a strict PLY 1.0 reader shared by load_mesh (.ply) and read_ply_colours.
// Reads ASCII, binary_little_endian and binary_big_endian files; the element "vertex" (x, y, z
// required; nx, ny, nz and red, green, blue (or diffuse_red, ...) optional) and the element "face"
// (list property vertex_indices or vertex_index). Other elements and properties are read and skipped.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace prt::mesh::detail {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

/// The parts of a PLY file prt uses.
struct PlyContents {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< empty unless the vertex has nx, ny and nz
  std::vector<double> colours;     ///< 3 stored values per vertex, unconverted; empty unless red, green, blue
  std::vector<glm::vec2> uv;       ///< u, v (s, t) per vertex as stored; empty unless both exist
  PlyType colour_types[3] = {PlyType::UInt8, PlyType::UInt8, PlyType::UInt8};
  bool partial_colours = false;        ///< some but not all of red/green/blue exist (they are ignored)
  std::vector<std::uint32_t> indices;  ///< faces fan-triangulated; every index < positions.size()
  std::size_t skipped_polygons = 0;    ///< faces with fewer than 3 vertices
};

/// Parses `bytes` (the whole file named `path`, used in messages). Throws prt::Error("<path>: ...")
/// for a malformed header, unsupported property types, bad ASCII values, truncated data, face indices
/// out of range, or a missing vertex element / x, y, z property.
PlyContents parse_ply(const std::string& path, const std::string& bytes);

bool is_integer(PlyType type);
/// Largest value of an unsigned integer type (255 for UInt8, 65535 for UInt16, ...); 1 for floats.
double unsigned_max(PlyType type);

}  // namespace prt::mesh::detail
