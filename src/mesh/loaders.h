#pragma once
// Internal to prt_mesh: what each format's loader hands to the common finishing step, and the
// loaders themselves. Not part of the public API.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/srgb.h"
#include "mesh/mesh.h"

namespace prt::mesh::detail {

/// A mesh as read from a file, before validation.
struct RawMesh {
  std::vector<glm::vec3> positions;
  /// Empty (no vertex has a file normal) or one per position; meaningful where has_normal is 1. Any
  /// length; finish_mesh replaces the zero and non-finite ones with computed normals.
  std::vector<glm::vec3> normals;
  /// One per position when normals is non-empty: 1 if the file gives this vertex a normal.
  std::vector<std::uint8_t> has_normal;
  /// Why some vertices have no file normal, for the stderr note (e.g. "the file has no normals");
  /// finish_mesh adds the count of zero or non-finite ones.
  std::string computed_normals_reason;
  std::vector<glm::vec3> albedo;       ///< empty or one per position (linear, not yet clamped)
  std::vector<glm::vec3> emission;     ///< empty or one per position (linear radiance, not yet clamped)
  std::vector<std::uint32_t> indices;  ///< 3 per triangle; each loader has range-checked them
  /// Lightmap UVs, one per entry of `indices` (per triangle corner), already in prt's v-down
  /// convention; empty when the file has none for some corner (missing_uv_reason then says why).
  std::vector<glm::vec2> corner_uv;
  std::uint32_t uv_set = 0;
  std::vector<SourcePrimitive> source_primitives;  ///< glTF: Mesh::source_primitives; else empty
  std::string missing_uv_reason;
  /// Materials (mesh.h): empty, or one material index per triangle of `indices`; base colour UVs per
  /// corner when some material is textured (prt's v-down convention); the decoded images; vertex
  /// colours per position (linear) or empty. `albedo` holds the per-vertex rule's values (mesh.h).
  std::vector<Material> materials;
  std::vector<std::uint32_t> triangle_material;
  std::vector<glm::vec2> base_color_uv;
  std::vector<Texture> textures;
  std::vector<glm::vec3> vertex_color;
  std::vector<TriangleSource> triangle_source; ///< empty, or one per triangle of `indices`
  std::size_t skipped_polygons = 0;    ///< faces of fewer than 3 vertices, counted as degenerate
  LoadReport notes_only;               ///< loader-specific notes and skipped_primitives
};

/// True if `normal` can be made unit length: every component finite and not all zero (checked in
/// double, where a float's square neither overflows nor underflows).
bool usable_normal(const glm::vec3& normal);

/// Validates `raw` (finite positions, indices in range), drops degenerate triangles, computes the
/// normals that are missing, zero or not finite (each vertex on its own), clamps albedo, fills `report` and prints its notes unless `quiet`.
/// Throws prt::Error("<path>: ...") for non-finite positions and when no triangle is left.
Mesh finish_mesh(const std::string& path, RawMesh raw, LoadReport* report, bool quiet);

/// Moves raw's materials, base colour UVs, textures and vertex colours into `mesh` (positions, indices
/// and normals already final), sets mesh->albedo_source, and for a textured mesh replaces raw->albedo
/// of the vertices whose footprint touches a textured triangle by the footprint average (texture_albedo).
void take_materials(RawMesh* raw, Mesh* mesh, LoadReport* result);

/// Decodes `bytes`, an image file's content, into `texture` (linear RGB, image::decode_rgb) and
/// adds its size to *held_bytes. The format comes from the content's signature, else from `hint` (a
/// mime type or a file name). Returns false, with the one-line *problem naming `name`, for KTX2/Basis,
/// anything prt_image cannot decode, or when the image's header says that the textures held would then
/// pass half of the machine's memory (refused before its pixels are decoded).
bool decode_texture(const std::string& bytes, const std::string& hint, const std::string& name, std::uint64_t* held_bytes,
                    Texture* texture, std::string* problem);

RawMesh load_obj(const std::string& path);
RawMesh load_ply(const std::string& path);
/// `scene`: LoadOptions::scene.
RawMesh load_gltf(const std::string& path, bool binary, int scene);

/// The other files a mesh file names (mesh::referenced_files): an OBJ's "mtllib" files (and their
/// map_Kd images), a glTF's
/// external buffers and images, resolved against the mesh's folder as the loaders resolve them.
std::vector<std::string> obj_referenced_files(const std::string& path);
std::vector<std::string> gltf_referenced_files(const std::string& path, bool binary);

using prt::srgb_to_linear;  // core/srgb.h

}  // namespace prt::mesh::detail
