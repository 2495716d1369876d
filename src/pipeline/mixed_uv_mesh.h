#pragma once
// A mixed bake with generated lightmap UVs (`prt bake --lightmap SIZE --texel-parts ... --uv
// generate|auto`; docs/conventions.md "Mixed scenes"): the mesh that carries the UVs, written beside
// the pair as "<stem>.mesh.glb" in `prt unwrap`'s form (the mesh as loaded with its materials, the UVs
// as TEXCOORD_1), and baked as a renderer loads it back from that file. Generated UVs are per corner,
// so the file splits a vertex where its corners' UVs differ: the per-vertex file must be baked for the
// file's vertices, not the source's, and the texel file for its triangle order.
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "mesh/mesh.h"

namespace prt::pipeline {

/// The mesh file a mixed bake with generated UVs writes for texel file `texel_path`: "<stem>.mesh.glb"
/// in the same folder ("room.prt" -> "room.mesh.glb").
std::string mixed_mesh_path(const std::string& texel_path);

class MixedUvMesh {
 public:
  /// Writes `mesh` (its generated lightmap UVs of set 1) into a temporary of `path` (AtomicFile)
  /// and loads it back (quietly), carrying `vertex_triangle` (one per triangle of `mesh`, 1: per
  /// vertex) to the loaded triangles, which the file groups by material and kind (one primitive per
  /// material and kind, each in mesh order, so that every primitive is of one kind). Throws prt::Error naming `path` if it cannot be written or the loaded
  /// triangles are not `mesh`'s in that order (corner positions compared bit for bit).
  MixedUvMesh(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
              const std::vector<std::uint8_t>& vertex_triangle);

  /// The mesh as loaded from the file (what the bake runs on and a renderer draws).
  mesh::Mesh& loaded() { return loaded_; }
  /// vertex_triangle in the loaded mesh's triangle order.
  const std::vector<std::uint8_t>& vertex_triangle() const { return vertex_triangle_; }
  const std::string& path() const { return file_->path(); }
  /// Renames the file into place (AtomicFile::commit); without it the temporary is removed.
  void commit() { file_->commit(); }

 private:
  std::unique_ptr<AtomicFile> file_;
  mesh::Mesh loaded_;
  std::vector<std::uint8_t> vertex_triangle_;
};

}  // namespace prt::pipeline
