#pragma once
// Triangle meshes as prt bakes and renders them.
//
// VERTEX ORDER: a loaded mesh's vertices map 1:1, in order, to the input file's vertices (engines load
// baked per-vertex data onto their own copy of the mesh). Nothing is welded, reordered or dropped:
// - OBJ: the "v" lines, in file order, then the hard-edge copies. A face corner stands for its "v" and
//   the value of its normal ("none" without "vn" or for a zero or non-finite one); a "v" whose corners
//   stand for different pairs is split: its first pair (in face order) keeps the v's index, each
//   further distinct pair is a new vertex at the same position, numbered after all "v"s in the order
//   the pairs first appear. A file without hard edges maps 1:1 to its "v" lines.
// - PLY: the "vertex" elements, in file order.
// - glTF: the nodes of the scene are visited depth-first, each node before its children, children in
//   the order of the node's "children" array; for each visited node with a mesh, that mesh's
//   primitives in order; for each triangle primitive (modes 4, 5, 6), all `count` elements of its
//   POSITION accessor in accessor order (a Draco-compressed primitive: Draco's point order; a meshopt-
//   compressed buffer view: its decoded order; both as gltf-transform decodes them to plain glTF). A
//   mesh instanced by two nodes appears twice. Primitives in point or line modes contribute no
//   vertices. The hierarchy must be a set of trees (as the glTF spec requires): a node reached twice
//   is an error. Which scene (LoadOptions::scene): by default the file's "scene", else scene 0, else
//   (no scenes) every root node in document order, with a note when the file has several scenes; or
//   the scene of a given index; or all: every scene in document order, each one's nodes as above (a
//   node in two scenes appears twice).
// Polygons with more than 3 vertices (OBJ, PLY) are fan-triangulated: (v0, v1, v2), (v0, v2, v3), ...
// glTF triangle strips and fans are converted to triangle lists as the glTF spec defines.
//
// NORMALS: the file's, made unit length (kept bit for bit when already unit to within 1e-6 in squared
// length, so meshes written by prt round-trip exactly), vertex by vertex: a vertex of a triangle whose
// file normal is missing (no normals in the file or glTF primitive, an OBJ corner without "vn"), zero
// or not finite gets an area-weighted normal (see area_weighted_normals) and every other vertex keeps
// its own; LoadReport counts the computed ones. OBJ hard edges (one position, corners with different
// normals) are separate vertices (VERTEX ORDER), each with its normal. glTF normals are transformed by
// the inverse transpose of the node's world matrix; where that matrix mirrors (negative determinant)
// the triangles' winding is reversed so that front faces stay counter-clockwise.
//
// MATERIALS AND BASE COLOUR (docs/conventions.md, "Albedo and textures"): each triangle has a material
// (Mesh::triangle_material), and the base colour at a point is texture(transform(uv)) x factor x vertex
// colour (mesh/texture.h evaluates it; textures are linear RGB, alpha ignored).
// - OBJ: one material per MTL material: factor Kd (taken as linear), texture map_Kd with its -s
//   (scale) and -o (offset) options and -clamp on (clamp to edge; default repeat); its UVs are the
//   corners' "vt" as for lightmap UVs. Faces without a material get a material of Kd 0.8 (grey). No
//   vertex colours.
// - glTF: pbrMetallicRoughness.baseColorFactor.rgb and baseColorTexture (its texCoord set,
//   KHR_texture_transform with its texCoord override, the sampler's wrapS / wrapT and magFilter);
//   vertex colour COLOR_0.rgb (float, or normalised unsigned byte/short). A primitive without a
//   material gets a material of factor 1.
// - PLY: no materials; vertex colours red/green/blue (or diffuse_red/...): integer types (uchar
//   0..255, ushort 0..65535) are sRGB-encoded and decoded to linear, float/double are linear.
// Images are decoded with OpenImageIO (embedded in the file or external); one it cannot decode
// (KTX2/Basis, an unknown format, a missing file) gives one note naming the file and the image, and
// its materials use the factor alone.
//
// ALBEDO (Mesh::albedo: linear diffuse reflectance per vertex, clamped to [0,1]; what per-vertex bakes
// and shading use): for a vertex whose footprint (mesh/vertex_footprint.h, the hat-weighted one-ring)
// touches a textured triangle, the base colour averaged over that footprint (texture_albedo, by
// quadrature on sub-triangles of at most half a texel); for any other vertex the base colour at the vertex, and where the
// vertex joins triangles of several materials the mean over those distinct materials. Albedo is empty
// when the file gives no materials and no vertex colours; the caller then chooses a default.
//
// EMISSION (linear radiance leaving the front face, per vertex, >= 0; NaN and negative values become 0):
// - OBJ: the MTL "Ke" of the faces' materials, averaged per vertex over its distinct materials as for
//   Kd; faces without a material count as 0.
// - glTF: the material's emissiveFactor times KHR_materials_emissive_strength's emissiveStrength (1 if
//   absent); primitives without a material emit 0. Emissive textures are ignored.
// - PLY: none.
// Emission is empty when nothing in the file emits (every value 0).
//
// LIGHTMAP UVs (Mesh::lightmap_uv), one per triangle CORNER (not per vertex: OBJ indexes "vt" apart
// from "v", so a position on a UV seam has several), in prt's texture convention (docs/conventions.md,
// "Lightmap texels"): u to the right, v DOWN, (0,0) the top-left corner of the image, as glTF defines.
// - glTF: TEXCOORD_1 when any triangle primitive in the file has it, else TEXCOORD_0 (float, or
//   normalised unsigned byte/short), used as stored; every triangle primitive must have the chosen set.
// - OBJ: the corners' "vt" (u, v) become (u, 1 - v) (OBJ's v points up); every face corner must have one.
// - PLY: vertex properties u, v (or s, t, or texture_u, texture_v) become (u, 1 - v) as for OBJ.
// Where some triangle lacks a UV, lightmap_uv is empty and LoadReport::missing_uv_reason says why. UVs are not validated here
// (range, overlaps and zero-area charts are the lightmap baker's checks, lightmap/uv_validation.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/material.h"

namespace prt::mesh {

/// Limits every loaded mesh satisfies (docs/formats.md, "Limits"): |coordinate| <= kMaxCoordinate
/// (squared lengths and ray extents stay far from float overflow), a bounding-box diagonal of at
/// least kMinExtent (squared edge lengths stay far from float underflow), and emission <= kMaxEmission.
/// load_mesh refuses a mesh outside them, naming the file.
inline constexpr double kMaxCoordinate = 1e12;
inline constexpr double kMinExtent = 1e-9;
inline constexpr float kMaxEmission = 1e18f;

/// Where a mesh's albedo comes from, the strongest source first: some material has a base colour
/// texture; materials (factors) only; vertex colours only; none (Mesh::albedo empty).
enum class AlbedoSource : std::uint8_t { texture, material, vertex_colours, none };

/// "texture", "material", "vertex colours" or "none".
const char* albedo_source_name(AlbedoSource source);

/// Material index of a triangle of a mesh without materials.
inline constexpr std::uint32_t kNoMaterial = 0xffffffffu;

/// A glTF triangle primitive as the loader visited it (VERTEX ORDER): the loaded vertices
/// [first_vertex, first_vertex + vertex_count) are, in order, the POSITION elements of primitive
/// `primitive` of glTF mesh `mesh`, instanced by node `node` (indices into the file's arrays).
struct SourcePrimitive {
  int node = 0, mesh = 0, primitive = 0;
  std::uint32_t first_vertex = 0, vertex_count = 0;
  std::string node_name;  ///< the node's name in the file; may be empty
};

/// A triangle's origin in a glTF file (Mesh::triangle_source).
struct TriangleSource {
  std::uint32_t primitive = 0;  ///< index into Mesh::source_primitives
  std::uint32_t triangle = 0;   ///< triangle index within that primitive
};

struct Mesh {
  std::vector<glm::vec3> positions;    ///< in the file's units and frame (glTF: node transforms applied)
  std::vector<glm::vec3> normals;      ///< unit length, one per vertex
  std::vector<glm::vec3> albedo;       ///< linear diffuse reflectance in [0,1] per vertex; empty if none given
  std::vector<glm::vec3> emission;     ///< linear emitted radiance (>= 0) per vertex; empty if nothing emits
  std::vector<std::uint32_t> indices;  ///< 3 per triangle, counter-clockwise front faces; degenerate removed
  /// Lightmap UVs per triangle corner: lightmap_uv[3t + k] is the UV of corner k of triangle t (the
  /// vertex indices[3t + k]); empty, or exactly indices.size() entries. See "LIGHTMAP UVs" above.
  std::vector<glm::vec2> lightmap_uv;
  /// Which UV set lightmap_uv came from: glTF TEXCOORD_<n>; 0 for OBJ vt and PLY u,v.
  std::uint32_t lightmap_uv_set = 0;
  /// glTF: the triangle primitives the vertices came from, in vertex order (one entry per visited
  /// node instance and primitive with vertices; a node in two scenes loaded together appears twice);
  /// empty for OBJ and PLY. What a writer needs to put per-vertex data back on the file's primitives.
  std::vector<SourcePrimitive> source_primitives;

  /// Materials (see "MATERIALS AND BASE COLOUR"); empty when the file has none.
  std::vector<Material> materials;
  /// One index into materials per triangle when materials is non-empty; else empty.
  std::vector<std::uint32_t> triangle_material;
  /// Base colour UVs per triangle corner (as lightmap_uv: 3t + k, v down, glTF's convention), each
  /// triangle's from its material's texcoord set; empty, or indices.size() entries when some material
  /// has a texture (corners of untextured triangles hold (0, 0)).
  std::vector<glm::vec2> base_color_uv;
  /// Decoded images, indexed by TextureRef::image.
  std::vector<Texture> textures;
  /// Linear RGB vertex colour per vertex (glTF COLOR_0, PLY colours); empty when the file has none (1).
  std::vector<glm::vec3> vertex_color;
  AlbedoSource albedo_source = AlbedoSource::none;
  /// Where each triangle came from (glTF only; empty for OBJ and PLY): triangle_source[t] = {primitive,
  /// triangle}, `primitive` indexing source_primitives, `triangle` the triangle's index among that
  /// primitive's triangles (after strip and fan conversion, before degenerate ones are dropped).
  /// describe_triangle names it for messages.
  std::vector<TriangleSource> triangle_source;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  bool has_lightmap_uv() const { return !lightmap_uv.empty(); }
  bool textured() const { return !base_color_uv.empty(); }
};

/// Names triangle t for messages: "node 3 \"Gear\" mesh 2 primitive 0 triangle 17" when the mesh
/// keeps triangle sources (glTF), else "triangle 17" (the mesh's own index, as for OBJ and PLY).
std::string describe_triangle(const Mesh& mesh, std::size_t t);

/// Names a glTF primitive for messages: "node 3 \"Gear\" mesh 2 primitive 0" (no name when the node has none).
std::string describe_primitive(const SourcePrimitive& primitive);

/// Drops the albedo the file gave: albedo, materials, triangle_material, base_color_uv, textures and
/// vertex_color become empty and albedo_source none (the caller's default applies, e.g. --albedo).
void drop_albedo(Mesh* mesh);

/// What loading found, for messages and tests.
struct LoadReport {
  std::size_t skipped_degenerate = 0;     ///< triangles dropped: repeated index, zero area, polygons of < 3 vertices
  bool normals_computed = false;          ///< some vertices had no (usable) file normal: area-weighted ones computed
  std::size_t computed_normal_count = 0;  ///< how many vertices (of triangles) got computed normals
  bool albedo_from_file = false;          ///< albedo came from materials or vertex colours
  bool emission_from_file = false;        ///< some material emits (OBJ Ke, glTF emissiveFactor)
  std::size_t skipped_primitives = 0;     ///< glTF primitives in point/line modes or without POSITION
  std::vector<std::string> notes;         ///< the one-line notes printed on stderr (also when quiet)
  /// Why Mesh::lightmap_uv is empty ("the file has no vt", "primitive 2 has no TEXCOORD_0", ...);
  /// empty when the mesh has lightmap UVs. Not printed: the lightmap baker names it in its error.
  std::string missing_uv_reason;
};

/// LoadOptions::scene: the file's default scene (see VERTEX ORDER).
inline constexpr int kDefaultScene = -1;
/// LoadOptions::scene: every scene, one after the other (see VERTEX ORDER).
inline constexpr int kAllScenes = -2;

/// How load_mesh reads a file.
struct LoadOptions {
  /// Which glTF scene: kDefaultScene, kAllScenes, or a scene index >= 0 (load_mesh throws
  /// "<path>: scene N does not exist (the file has M scenes)" when it is out of range). An OBJ or
  /// PLY file is one scene, index 0.
  int scene = kDefaultScene;
  bool quiet = false;  ///< no notes on stderr
};

/// Loads .obj (+ .mtl Kd), .ply (ASCII / binary little or big endian, optional red/green/blue),
/// .gltf / .glb (every triangle primitive of the scene, node transforms, baseColorFactor and COLOR_0
/// as albedo); the extension (case-insensitive) picks the format, and the content must match it.
/// Throws prt::Error("<path>: <problem>") for: unreadable file, unsupported format (by extension or
/// content), malformed or truncated data, NaN/Inf positions, indices out of range, no triangles left,
/// values outside the limits above.
/// Prints each note of the report (normals computed, triangles or primitives skipped) as one line
/// "<path>: <note>" on stderr, unless `quiet`.
Mesh load_mesh(const std::string& path, LoadReport* report = nullptr, bool quiet = false);
/// load_mesh as above, reading the scene(s) that `options` names.
Mesh load_mesh(const std::string& path, const LoadOptions& options, LoadReport* report = nullptr);

/// The files a mesh file refers to, which load_mesh may read and which are inputs as much as the
/// mesh itself: an OBJ's "mtllib" files and their map_Kd images, a glTF's (.gltf or .glb) buffer and
/// image URIs other than data: URIs; each resolved against the mesh's folder. Empty for .ply, other
/// extensions, and a file that cannot be read or parsed (load_mesh then names the problem). Names that
/// do not exist are listed too.
std::vector<std::string> referenced_files(const std::string& path);

/// Area-weighted vertex normals: for each vertex, the normalised sum of (p1-p0)x(p2-p0) over the
/// triangles using it (the cross product's length is twice the area, so large triangles weigh more),
/// accumulated in double in triangle order. Vertices of no triangle, or whose sum vanishes, get +Y.
/// Preconditions: indices.size() % 3 == 0, every index < positions.size().
std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices);

/// True if triangle (a, b, c) has zero area: two equal points, or its double-precision cross
/// product's length is at most 1e-12 times the square of its longest edge (collinear to within far
/// below float resolution). load_mesh drops such triangles.
bool is_degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

/// 64-bit fingerprint of positions and indices, stored in transfer files so a reader can tell that a
/// file belongs to a mesh. FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) over the
/// bytes: vertex count as uint64 little-endian; each position's x, y, z float bit patterns as uint32
/// little-endian; index count as uint64 little-endian; each index as uint32 little-endian.
/// Identical on every machine; any change of one position bit or one index changes it.
std::uint64_t fingerprint(const Mesh& mesh);

/// 64-bit fingerprint of the lightmap UVs, stored in texel transfer files next to fingerprint():
/// FNV-1a 64 as above over the corner count as uint64 little-endian, then each corner's u, v float
/// bit patterns as uint32 little-endian. 0xcbf29ce484222325 folded with a zero count for no UVs.
std::uint64_t uv_fingerprint(const Mesh& mesh);

/// Axis-aligned bounds.
struct Bounds {
  glm::vec3 lo{0.0f}, hi{0.0f};
  float diagonal() const;  ///< |hi - lo|
};
/// Bounds of all positions (zero box for an empty mesh).
Bounds bounds(const Mesh& mesh);

}  // namespace prt::mesh
