#pragma once
// The engine-ready glTF binary (docs/formats.md, "The engine glTF: PRT_transfer"): the source mesh file
// as authored (glTF: scenes, nodes and their transforms, meshes, materials, textures, samplers, images
// and every UV set; OBJ/PLY: one node, one mesh, one primitive per material) with per-vertex data and a
// vendor extension added, written as one .glb (images embedded in the BIN chunk). The writer knows
// nothing of transfer: prt_pipeline (engine_export.h) says what to add. GltfExtras reads such data back.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mesh/mesh.h"
#include "mesh/writers.h"

namespace prt::mesh {

/// WebGL2's (and most GPUs') limit on vertex attributes: every primitive write_engine_glb writes has at most this many.
inline constexpr int kMaxVertexAttributes = 16;

/// A float vertex attribute to add: `components` (1..4: SCALAR, VEC2, VEC3, VEC4) floats per vertex of
/// the loaded mesh, in its vertex order (mesh.h, VERTEX ORDER).
struct EngineAttribute {
  std::string name;  ///< application-specific: '_' then A-Z, 0-9, '_'
  int components = 4;
  std::vector<float> values;  ///< components x mesh.vertex_count()
  int group = -1;  ///< -1: every baked primitive carries it; g >= 0: only the baked primitives of group g (EngineExtras::triangle_group)
};

/// Index of what write_engine_glb added, for the extension objects: the accessor of each of
/// EngineExtras::arrays and the glTF image of each of EngineExtras::images.
struct EngineIndices {
  std::vector<int> arrays, images;
};

/// What write_engine_glb adds to the source's data.
struct EngineExtras {
  std::vector<EngineAttribute> attributes;
  std::vector<std::vector<float>> arrays;  ///< each a SCALAR float accessor (no buffer view target)
  std::vector<GlbImage> images;            ///< appended after the source's images
  std::string extension;                   ///< vendor extension name: in extensionsUsed, not extensionsRequired; empty: none (root and primitive unused)
  std::function<nlohmann::json(const EngineIndices&)> root;       ///< the document's extension object
  /// Each baked primitive's extension object, given the primitive's group (0 without triangle_group).
  std::function<nlohmann::json(const EngineIndices&, int group)> primitive;
  /// A mixed export (e.g. some primitives per texel, the others per vertex): per triangle of the mesh,
  /// the group (0..255) of the primitive it is drawn in. A glTF source's baked primitive takes the group
  /// of its triangles, which must all have the same; the OBJ/PLY layout writes one primitive per
  /// (material, group), material-major. Empty: every triangle of group 0.
  std::vector<std::uint8_t> triangle_group;
  /// Per texel: the baked primitives' lightmap UVs are written as TEXCOORD_<lightmap_set> (an OBJ/PLY
  /// source's corner UVs split its vertices); -1: per vertex.
  int lightmap_set = -1;
  /// The mesh's lightmap UVs (Mesh::lightmap_uv, per corner) are not the source's (generated: `prt
  /// unwrap`, `prt bake --uv`): a glTF source's baked primitives are written as their loaded triangles
  /// (a triangle list; triangles the loader dropped are gone), one vertex per distinct (source vertex,
  /// UV) with the source's attributes gathered, and the UVs as TEXCOORD_<lightmap_set>, which must be
  /// >= 0. An OBJ/PLY source writes its corner UVs as below in any case.
  bool corner_uvs = false;
  /// Write the mesh as loaded (the OBJ/PLY layout below) even for a glTF source (e.g. a mesh made in
  /// memory).
  bool as_loaded = false;
};

/// Writes `path` (atomically): `source_path` (the file `mesh` was loaded from, with the same
/// LoadOptions) re-written as a glTF binary with `extras`.
/// glTF source: the document as authored (asset, scenes, nodes, cameras, meshes, materials, textures,
/// samplers, images, root and material extensions), except that: every accessor a primitive uses is
/// rewritten tightly packed in its own component type (Draco and meshopt data decoded; their extensions
/// dropped); images are embedded; animations, skins, morph targets, JOINTS/WEIGHTS attributes and
/// EXT_mesh_gpu_instancing are dropped (a static bake); each node instance the bake saw
/// (mesh.source_primitives) gets its own copy of its mesh when that mesh is used by another node too;
/// its triangle primitives get the attributes' slices and extras.primitive.
/// OBJ/PLY source (or extras.as_loaded): one scene, one node, one mesh, one primitive per material (and group)
/// (triangles in mesh order; a vertex per distinct (mesh vertex, UVs) in order of first use), POSITION,
/// NORMAL, TEXCOORD_0 (the base colour UVs, else the lightmap UVs unless they are of set 1), TEXCOORD_1 (the
/// lightmap UVs when they are of set 1, as generated ones are, or other than the base colour UVs; the primitive
/// extension's "texCoord" is then set to 1), COLOR_0 (vertex colours), materials as
/// pbrMetallicRoughness factors and base colour textures (PNG or JPEG files embedded; others dropped
/// with a note on stderr).
/// Throws prt::Error naming `path` when a primitive would have more than kMaxVertexAttributes attributes,
/// triangle_group has a length other than the triangle count or a glTF primitive's triangles in two groups,
/// an attribute's length or name is wrong, a node is baked twice (a node in two scenes loaded together),
/// an image's bytes are missing, or writing fails.
void write_engine_glb(const std::string& path, const std::string& source_path, const Mesh& mesh, const EngineExtras& extras);

/// Reading back a glTF file's own data that load_mesh leaves out: its JSON and float accessors, and
/// application vertex attributes in the loaded mesh's vertex order.
class GltfExtras {
 public:
  /// Parses `path` (.gltf or .glb) as load_mesh does. Throws prt::Error("<path>: <problem>").
  explicit GltfExtras(const std::string& path);
  ~GltfExtras();
  GltfExtras(const GltfExtras&) = delete;
  GltfExtras& operator=(const GltfExtras&) = delete;

  /// The file's JSON document as written.
  const nlohmann::json& document() const;
  /// Accessor `index` as floats (components x count, normalised integers mapped to [0,1] / [-1,1]);
  /// throws naming `what` if it does not exist or is malformed, or its element is not `components` wide.
  std::vector<float> floats(int index, int components, const std::string& what) const;
  /// Attribute `name` of each primitive in mesh.source_primitives (`mesh` loaded from this file),
  /// concatenated in vertex order: components x mesh.vertex_count() floats. Throws naming the
  /// primitive if one lacks it or it has the wrong width or count.
  std::vector<float> vertex_attribute(const Mesh& mesh, const std::string& name, int components) const;
  /// The file bytes of image `index`; throws naming `what` if it does not exist or has none.
  std::string image(int index, const std::string& what) const;

 private:
  struct Model;
  std::string path_;
  std::unique_ptr<Model> model_;
};

}  // namespace prt::mesh
