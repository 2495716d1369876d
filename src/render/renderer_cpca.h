#pragma once
// CPCA-compressed transfer on the GPU (renderer.h, PASSES: prt_cpca). Per frame, on the CPU, the
// K x (N+1) products of every cluster's mean and PCA directions with the object-frame lighting
// (glossy: then through the BRDF matrix B, as O = B (M L) of the uncompressed glossy pass; B is linear,
// so B applied to each product equals B applied to the blend); then a compute pass, prt_cpca.comp,
// blends each vertex's N + 1 products with its weights (and, glossy, evaluates the outgoing radiance
// coefficients toward the eye at the vertex, as prt::shade::shade_glossy does) into a per-vertex
// radiance buffer, and prt_cpca.vert + surface.frag draw it, interpolated like the diffuse pass (glossy
// shading is per vertex here, not per fragment as in the uncompressed glossy pass).
// At vertices this is `prt shade` of the .cprt (prt::shade of compress::decompress).
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "brdf/projection.h"
#include "compress/compressed.h"
#include "render/gl.h"
#include "render/scene_inputs.h"

namespace prt::render {

/// The products on the CPU, float: out[((k * (N + 1) + j) * C + o)] for cluster k, vector j (0 = the
/// mean, 1..N the directions) and output o < C, C = 1 (diffuse: radiance, sum_i A[c'][i] L_i.c over the
/// first bands^2 coefficients, c' as shade_diffuse) or bands_out^2 (glossy: sum_q B_c[o][q] sum_i
/// A[c'][q][i] L_i.c). `lighting` holds at least bands^2 object-frame coefficients; `brdf` is required
/// for glossy transfer (bands == its bands_out), ignored otherwise. With `discs` (the discs' SH, object
/// frame, bands^2; null: none) and a model holding the bounce-only part, each product also adds that
/// part's product with `discs` (the discs' bounce light, as prt::shade::shade_*_split).
void cpca_products(const compress::CompressedTransfer& compressed, const glm::vec3* lighting, const glm::vec3* discs, int bands,
                   const brdf::BrdfMatrix* brdf, std::vector<glm::vec4>& out);

/// The part of `compressed` the per-frame products need (cpca_products): its header, K, N, bounce flag,
/// means and directions; the per-point arrays (clusters, weights, coverage) left empty.
compress::CompressedTransfer cluster_vectors(const compress::CompressedTransfer& compressed);

/// One compressed transfer on the GPU: cluster ids and weights uploaded once (storage buffers), the
/// products re-uploaded every frame. Keeps the means and directions on the CPU for the products.
class CpcaTransfer {
 public:
  /// Throws prt::Error("<origin>: ...") if the model's arrays do not match its header.
  CpcaTransfer(const compress::CompressedTransfer& compressed, const std::string& origin);
  ~CpcaTransfer();
  CpcaTransfer(const CpcaTransfer&) = delete;
  CpcaTransfer& operator=(const CpcaTransfer&) = delete;

  /// The uncompressed transfer's header (float32), as Renderer::transfer_header reports it.
  const transfer::Header& header() const { return header_; }
  int pca() const { return model_.pca; }
  void set_brdf(const brdf::BrdfMatrix& matrix) { brdf_ = matrix, has_brdf_ = true; }
  bool has_brdf() const { return has_brdf_; }
  /// This frame's products (first `bands` bands of the object-frame lighting; `discs`, null or the
  /// discs' object-frame SH for the bounce-only part), uploaded; then binds them (texture unit 0), the
  /// cluster ids, weights and the per-vertex radiance buffer of prt_cpca.comp.
  void prepare(const glm::vec3* lighting, const glm::vec3* discs, int bands);
  /// The model holds the bounce-only part (compress::CompressedTransfer::bounce).
  bool has_bounce() const { return model_.bounce; }
  /// Bytes on the GPU: ids, weights and one frame's products.
  std::size_t gpu_bytes() const;

 private:
  compress::CompressedTransfer model_;  // means and directions (per-vertex arrays dropped after upload)
  transfer::Header header_;
  brdf::BrdfMatrix brdf_;
  bool has_brdf_ = false;
  GLuint products_ = 0, products_view_ = 0, clusters_ = 0, weights_ = 0, radiance_ = 0;
  std::size_t products_bytes_ = 0, vertex_bytes_ = 0;
  std::vector<glm::vec4> scratch_;
};

class Renderer;

/// Adds scene transfer i to the renderer (Renderer::add, with its model for a per-vertex .cprt file),
/// textured (Renderer::set_textured) when the mesh is and the transfer was baked with its albedo.
int add_scene_transfer(Renderer& renderer, const SceneInputs& scene, std::size_t i);

/// For the viewer's transfer list: ", 25.0 MB" for a .prt transfer (float32 on the GPU), or
/// ", CPCA K 128 N 8, 2.9 MB, error 1.23%" for a compressed one (its payload; the recorded relative
/// transfer-space error, and the shaded-radiance error if recorded), per vertex or per texel.
std::string transfer_memory_label(const SceneInputs& scene, std::size_t i);

}  // namespace prt::render
