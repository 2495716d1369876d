// OBJ face corners to vertices, split at hard edges (obj_corner_vertices.h).
#include "mesh/obj_corner_vertices.h"

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace prt::mesh::detail {

CornerVertices::CornerVertices(const std::string& path, const std::vector<float>& file_normals, RawMesh* raw)
    : path_(path),
      file_normals_(file_normals),
      raw_(raw),
      assigned_(raw->positions.size(), 0),
      own_key_(raw->positions.size()),
      bad_normal_(file_normals.size() / 3, 0) {
  raw->normals.assign(raw->positions.size(), glm::vec3(0.0f));
  raw->has_normal.assign(raw->positions.size(), 0);
}

CornerVertices::Key CornerVertices::key_of(int normal_index) {
  if (normal_index < 0) {
    ++corners_without_normal_;
    return Key(false, 0.0f, 0.0f, 0.0f);
  }
  const float* n = &file_normals_[3 * std::size_t(normal_index)];
  if (!usable_normal(glm::vec3(n[0], n[1], n[2]))) {
    bad_normal_[std::size_t(normal_index)] = 1;
    return Key(false, 0.0f, 0.0f, 0.0f);
  }
  return Key(true, n[0] + 0.0f, n[1] + 0.0f, n[2] + 0.0f);  // + 0: -0 and +0 are one value
}

std::uint32_t CornerVertices::vertex_of(int vertex_index, int normal_index) {
  const std::uint32_t v = std::uint32_t(vertex_index);
  const Key key = key_of(normal_index);
  if (!assigned_[v]) {
    assigned_[v] = 1;
    own_key_[v] = key;
    set_normal(v, key);
    return v;
  }
  if (own_key_[v] == key) return v;
  const auto [it, inserted] = extra_.emplace(std::make_pair(v, key), std::uint32_t(raw_->positions.size()));
  if (inserted) {
    if (it->second == std::numeric_limits<std::uint32_t>::max()) fail_file(path_, "too many vertices");
    const glm::vec3 position = raw_->positions[v];
    raw_->positions.push_back(position);
    raw_->normals.emplace_back(0.0f);
    raw_->has_normal.push_back(0);
    set_normal(it->second, key);
  }
  return it->second;
}

void CornerVertices::set_normal(std::uint32_t vertex, const Key& key) {
  raw_->has_normal[vertex] = std::get<0>(key) ? 1 : 0;
  raw_->normals[vertex] = glm::vec3(std::get<1>(key), std::get<2>(key), std::get<3>(key));
}

void CornerVertices::finish() {
  const std::size_t bad = std::size_t(std::count(bad_normal_.begin(), bad_normal_.end(), 1));
  if (file_normals_.empty()) {
    raw_->normals.clear();
    raw_->has_normal.clear();
    raw_->computed_normals_reason = "the file has no normals";
    return;
  }
  std::string& reason = raw_->computed_normals_reason;
  if (corners_without_normal_ > 0) reason = std::to_string(corners_without_normal_) + " face corners have no normal";
  if (bad > 0)
    reason += (reason.empty() ? "" : ", ") + std::to_string(bad) + " referenced normals are zero or not finite";
}

}  // namespace prt::mesh::detail
