#pragma once
// Loading what the renderer draws: a mesh with its baked transfers, and lighting (environment images or
// SH lighting files). No GL here; shared by `prt render` and `prt view`.
#include <string>
#include <vector>

#include <memory>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "brdf/vertex_brdfs.h"
#include "compress/compressed.h"
#include "image/image.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::render {

/// A mesh and the transfers baked for it (diffuse or glossy).
struct SceneInputs {
  mesh::Mesh mesh;
  std::vector<transfer::TransferData> transfers;
  std::vector<std::string> transfer_paths;
  /// Per transfer: the model of a compressed (.cprt) file, whose entry in `transfers` then has the
  /// header only (no values); null for a .prt file.
  std::vector<std::shared_ptr<const compress::CompressedTransfer>> compressed;
};

/// Loads the mesh (its scene `scene`, mesh::LoadOptions::scene; quietly: no notes on stderr, as `prt shade`) and each transfer (compress::open_transfer:
/// .prt, or .cprt: compressed, per vertex or per texel, kept compressed except glossy transfer with one BRDF
/// per material, which is decompressed: the CPCA pass holds one BRDF), checks every transfer against the mesh
/// (transfer::check_mesh_match with mesh::fingerprint). Throws prt::Error("<file>: <problem>") for the
/// first file that fails.
SceneInputs load_scene(const std::string& mesh_path, const std::vector<std::string>& transfer_paths,
                       int scene = mesh::kDefaultScene);

/// Distant lighting for the renderer.
struct Lighting {
  std::string source;               ///< the path (or cube-face spec) it came from
  sh::RgbCoefficients coefficients; ///< SH radiance of the sky (all but the discs), environment frame, windowed
  std::vector<light::Disc> discs;   ///< exact discs (a sun), environment frame (light::load_scene_lighting)
  std::string description;          ///< light::describe_lighting: the discs and the window
  std::string window;               ///< the window applied to the sky, e.g. "laplacian(0.0012)"
  bool has_image = false;           ///< an environment image was given (not an SH lighting file)
  /// When has_image: the sky as an equirect image, what the "env" background shows. Discs found in the
  /// map (sun auto) are not in it: their texels are refilled from the surrounding sky, as for the SH,
  /// and the renderer draws each disc it shades instead (Renderer::set_discs).
  image::Image equirect;
};

/// Loads `spec` split into discs and sky as light::load_scene_lighting does (unrotated: the renderer
/// rotates per frame; `sun` and `window` as --sun and --window): a .json SH lighting file, or an
/// environment (light::load_environment: equirect, cross or six faces) projected to `bands` bands. The
/// environment image, less the discs found in it, is kept for the background; cube environments are
/// resampled to an equirect image of 4 x 2 face widths (bilinear, Environment::radiance at each pixel
/// centre; with discs found, the residual is already equirect: light/sun_extraction.h). With
/// sun none and window none the coefficients are exactly light::project's (or the file's).
/// Throws prt::Error("<file>: <problem>").
Lighting load_render_lighting(const std::string& spec, int bands, const light::SunRequest& sun = {},
                       const light::WindowRequest& window = {});

/// Largest band count among the transfers (the bands lighting is projected to).
int max_bands(const SceneInputs& scene);

/// The BRDFs a glossy transfer is shaded with: `spec`'s for every vertex if not empty, else those recorded
/// at bake time, one per vertex for a `--brdf mesh` bake (shade::baked_brdfs). Throws prt::Error naming
/// `origin` if the transfer records none, or `spec` does not parse.
brdf::VertexBrdfs glossy_brdfs(const transfer::TransferData& transfer, const std::string& origin, const std::string& spec);

}  // namespace prt::render
