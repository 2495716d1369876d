// Colour PLY output (write_ply) and its partner read_ply_colours.
#include <cstring>
#include <limits>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/little_endian.h"
#include "mesh/ply_format.h"
#include "mesh/writers.h"

namespace prt::mesh {

namespace {

using le::put_u32;
void put_float(std::string& out, float value) { le::put_f32(out, value); }

}  // namespace

void write_ply(const std::string& path, const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& colours,
               const std::vector<std::uint32_t>& indices) {
  if (!colours.empty() && colours.size() != positions.size())
    fail_file(path, "cannot write PLY: " + std::to_string(colours.size()) + " colours for " +
                        std::to_string(positions.size()) + " vertices");
  if (indices.size() % 3 != 0) fail_file(path, "cannot write PLY: index count is not a multiple of 3");
  if (positions.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    fail_file(path, "cannot write PLY: too many vertices for int indices");
  for (std::uint32_t index : indices)
    if (index >= positions.size())
      fail_file(path, "cannot write PLY: index " + std::to_string(index) + " out of range");

  const bool with_colours = !colours.empty();
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment written by prt\nelement vertex " +
                      std::to_string(positions.size()) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (with_colours) bytes += "property float red\nproperty float green\nproperty float blue\n";
  bytes +=
      "element face " + std::to_string(indices.size() / 3) + "\nproperty list uchar int vertex_indices\nend_header\n";
  bytes.reserve(bytes.size() + positions.size() * (with_colours ? 24 : 12) + indices.size() / 3 * 13);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) put_float(bytes, positions[i][c]);
    if (with_colours)
      for (int c = 0; c < 3; ++c) put_float(bytes, colours[i][c]);
  }
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    bytes.push_back(char(3));
    for (int c = 0; c < 3; ++c) put_u32(bytes, indices[t + c]);
  }
  write_file_atomically(path, bytes);
}

ColourPly read_ply_colours(const std::string& path) {
  detail::PlyContents ply = detail::parse_ply(path, read_file(path));
  if (ply.colours.empty()) fail_file(path, "the PLY vertices have no red, green, blue properties");
  for (int c = 0; c < 3; ++c)
    if (detail::is_integer(ply.colour_types[c]))
      fail_file(path, "the PLY colours are integers (8-bit display colours), not float radiance");
  ColourPly out;
  out.positions = std::move(ply.positions);
  out.indices = std::move(ply.indices);
  out.colours.resize(out.positions.size());
  for (std::size_t i = 0; i < out.colours.size(); ++i)
    out.colours[i] = glm::vec3(float(ply.colours[3 * i]), float(ply.colours[3 * i + 1]), float(ply.colours[3 * i + 2]));
  return out;
}

}  // namespace prt::mesh
