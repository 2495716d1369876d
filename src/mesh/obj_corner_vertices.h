#pragma once
// Internal to prt_mesh: how the OBJ loader turns face corners into vertices, splitting a "v" at hard
// edges (mesh.h VERTEX ORDER, docs/formats.md "Vertex order").
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "mesh/loaders.h"

namespace prt::mesh::detail {

/// OBJ face corners to prt vertices: a corner stands for its "v" and the value of its normal ("none"
/// when it has no "vn" or its "vn" is zero or not finite; -0 and +0 are one value). The first such
/// pair met for each "v" keeps the v's index; each further distinct pair (a hard edge) becomes a new
/// vertex at the v's position, numbered after all "v"s in the order the pairs are first met.
class CornerVertices {
 public:
  /// `file_normals`: the "vn" lines, 3 floats each; `raw` holds the "v" positions. Both must outlive this.
  CornerVertices(const std::string& path, const std::vector<float>& file_normals, RawMesh* raw);
  /// The vertex of a corner whose indices (0-based; normal_index -1: none) are in range; appends the
  /// vertex to raw (position, normal) when its pair is new. prt::Error past 2^32 - 1 vertices.
  std::uint32_t vertex_of(int vertex_index, int normal_index);
  /// Sets raw's normals (none at all when the file has no "vn") and the reason some vertices have none.
  void finish();

 private:
  using Key = std::tuple<bool, float, float, float>;  // (has a usable normal, its x, y, z)
  Key key_of(int normal_index);
  void set_normal(std::uint32_t vertex, const Key& key);

  const std::string& path_;
  const std::vector<float>& file_normals_;
  RawMesh* raw_;
  std::vector<std::uint8_t> assigned_;  // per "v": its own index stands for a pair yet
  std::vector<Key> own_key_;            // per "v": the pair its own index stands for
  std::map<std::pair<std::uint32_t, Key>, std::uint32_t> extra_;  // (v, pair) -> appended vertex
  std::vector<std::uint8_t> bad_normal_;  // per "vn": referenced, and zero or not finite
  std::size_t corners_without_normal_ = 0;
};

}  // namespace prt::mesh::detail
