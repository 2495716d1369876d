#pragma once
// Texture-space transfer: diffuse PRT baked at the texel sample points of a mesh's lightmap UVs
// (`prt bake MESH --lightmap WxH`). The passes are the vertex baker's (bake/passes.h), run over the
// texel samples instead of the vertices (bake.h describes the estimators):
//   - unshadowed: closed form at each sample's normal;
//   - shadowed: the same S cosine-distributed Owen-scrambled Sobol directions per sample, in the
//     frame sh::vertex_frame(n, seed, texel index) (with --denoise: unturned frames and one of up to 256
//     sample sets per texel, interleaved_sampling, denoise.h; a texel at a chart's border also traces the
//     sets of its empty neighbours, and after the direct pass a texel on a steep falloff three more sets,
//     add_contact_sets; a texel's transfer is the mean of its points), with the unshadowed control
//     variate;
//   - interreflected: each bounce pass gathers, at a front-face hit, the previous pass's texel
//     transfer at the hit's lightmap UV, filtered bilinearly in the texel grid (bake/passes.h,
//     TexelGrid; the grid's gutters are filled before each pass); the bounce-only part is kept in
//     the file's second section, as for vertices.
// Samples are traced in Morton order of their positions, 64 per parallel chunk, with ray batches of
// 256 (trace/vertex_rays.h). Channels: 1 if every vertex albedo is grey, else 3 (RGB). Glossy
// kinds are refused (per-texel matrices wait for transfer compression).
// Pipeline: UV checks (uv_validation.h) -> rasterize (rasterize.h) -> sample repair
// (sample_repair.h) -> passes -> optional denoising (denoise.h) -> gutters (gutter.h) -> optional seam
// stitching (seams.h). Byte-identical for any thread count.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bake/bake.h"
#include "lightmap/denoise.h"
#include "lightmap/seams.h"
#include "lightmap/rasterize.h"
#include "mesh/mesh.h"
#include "trace/scene.h"
#include "transfer/transfer_file.h"

namespace prt::lightmap {

struct LightmapOptions {
  int width = 0, height = 0;  ///< 1..transfer::kMaxTexelSide
  int gutter = 2;             ///< dilation rounds, 0..64
  bool repair = true;         ///< move buried samples out (sample_repair.h)
  std::string mesh_path;      ///< names the mesh in errors about its UVs
  std::string missing_uv_reason;  ///< mesh::LoadReport::missing_uv_reason, for the error when there are no UVs
  bool denoise = false;       ///< filter the baked transfer (denoise.h) before the gutters are filled
  DenoiseOptions denoise_options;  ///< its settings (threads: the bake's)
  bool stitch = false;        ///< stitch the seams (seams.h) after denoising and gutters
  StitchOptions stitch_options;
  /// Mixed scenes (part_choice.h): per triangle, 1 when it is baked per vertex (no texels of its own,
  /// its UVs not checked); empty: every triangle per texel.
  std::vector<std::uint8_t> vertex_triangles;

  /// A mixed scene: some triangle is baked per vertex.
  bool mixed() const { return std::find(vertex_triangles.begin(), vertex_triangles.end(), 1) != vertex_triangles.end(); }
  /// The bake gives its texels interleaved sample sets (denoise.h): denoised, interleave on, not mixed (a
  /// mixed scene's points go on with its vertices, whose sets and frames stay a vertex bake's).
  bool interleaves() const { return denoise && denoise_options.interleave && !mixed(); }
};

struct LightmapReport {
  std::size_t covered = 0, gutter = 0;     ///< texels of each kind
  std::size_t moved = 0, unrecoverable = 0;  ///< sample repair
  std::vector<std::string> uv_summary;       ///< UV defects tolerated (UvProblems::summary), one line each
  bake::BakeReport bake;
  StitchReport stitch;
  double seconds_raster = 0.0, seconds_repair = 0.0, seconds_denoise = 0.0, seconds_stitch = 0.0;
};

/// Parses "WxH" or "SIZE" (square); throws prt::Error("--lightmap: ...") for anything else and for
/// sides outside 1..16384.
void parse_lightmap_size(const std::string& text, int& width, int& height);

/// Bytes a bake of this size needs at most (texel grids, samples, pass buffers), for the memory check.
std::uint64_t estimated_bytes(const LightmapOptions& lightmap, const bake::BakeOptions& options, int channels);

/// Throws prt::Error naming the lightmap size unless estimated_bytes plus `extra_bytes` (what the mesh
/// adds: bake::hit_colour_bytes) fits in 80% of `available_bytes` (physical memory by default, sysconf).
void check_memory(const LightmapOptions& lightmap, const bake::BakeOptions& options, int channels, std::uint64_t extra_bytes = 0,
                  std::uint64_t available_bytes = 0);

/// The texel sample points of `mesh` for `lightmap`: UVs checked (prt::Error "lightmap UVs: ..."
/// listing every problem when uv_validation.h refuses them, else their summary in report->uv_summary;
/// or "has no lightmap UVs (<reason>)"), rasterized with `albedo` (one per
/// vertex) and, if lightmap.repair, repaired against `scene` (built from `mesh`) with `seed`.
/// `report` (optional) gets covered/moved/unrecoverable counts. The same points for the same mesh,
/// size, repair flag and seed: `prt shade --lightmap` and `prt reference --texels` recompute them.
TexelSamples texel_samples(const mesh::Mesh& mesh, const trace::Scene& scene, const std::vector<glm::vec3>& albedo,
                           const LightmapOptions& lightmap, std::uint32_t seed, int threads, LightmapReport* report = nullptr);

/// What recomputing a texel file's sample points needs, from its header and bake parameters: size,
/// gutter, repair flag, a mixed scene's per-vertex triangles (LightmapOptions) and the seed. Throws prt::Error("<path>: ...") for a
/// per-vertex file or parameters without them.
struct BakedLightmap {
  LightmapOptions options;
  std::uint32_t seed = 1;
};
BakedLightmap baked_lightmap(const transfer::Header& header, const std::string& path);

/// Throws prt::Error for invalid options (bake::validate_options, gutter 0..64, sides), glossy
/// kinds, a mesh without lightmap UVs, and a lightmap too large for memory: what bake_lightmap
/// checks before any work.
void check_lightmap(const mesh::Mesh& mesh, const bake::BakeOptions& options, const LightmapOptions& lightmap);

/// Bakes the texel transfer (after check_lightmap). Also throws prt::Error for UV problems.
/// MIXED SCENES (lightmap.vertex_triangles marks some triangle): one bake over the texel samples of the
/// texel triangles and every mesh vertex, in one scene of the whole mesh; the bounce passes read a hit
/// on a per-vertex triangle from its vertices (barycentric), any other from the texel grid
/// (bake/passes.h, TexelGrid). The rays of a vertex leave from its footprint (options.footprint, as in
/// a vertex bake), with the vertex's albedo. `vertex_data` (required then) gets the per-vertex transfer of every mesh
/// vertex (a per-vertex file's data; the texel triangles' vertices are baked as receivers too).
transfer::TransferData bake_lightmap(const mesh::Mesh& mesh, const bake::BakeOptions& options, const LightmapOptions& lightmap,
                                     LightmapReport* report = nullptr, transfer::TransferData* vertex_data = nullptr);

}  // namespace prt::lightmap
