#pragma once
// A transfer file compressed by CPCA (cpca.h): per-cluster means and principal directions, per-vertex
// cluster and weights, and how well it reconstructs the original. Each vertex's whole block of
// values (TransferData: channels x bands^2 for diffuse, channels x bands_out^2 x bands^2 for glossy)
// is one point of dimension D = Header::values_per_vertex(), so
//   T_p ~ mu_k + sum_n w_pn b_kn   (k = cluster of p),
// and, transfer being linear in the lighting, shading with T_p is the same blend of the shadings with
// mu_k and b_kn (what the renderer computes per frame: K x (N+1) products, then a blend per vertex).
//
// Errors: sums of squares, relative error = sqrt(error2 / norm2).
//   transfer space: |T_p - T~_p|^2 and |T_p|^2 over the vertex's values;
//   shaded radiance (optional, under one lighting): diffuse, the outgoing RGB radiance
//   (shade::shade_diffuse); glossy, the outgoing radiance coefficients O_p = B (M_p L) with the BRDF the
//   transfer was baked with (shade::glossy_outgoing_coefficients) -- by the orthonormality of the SH
//   basis, |O_p|^2 is the integral over all view directions of the squared outgoing radiance.
#include <cstdint>
#include <vector>

#include "compress/cpca.h"
#include "compress/metric.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::compress {

struct ErrorSums {
  double transfer_error2 = 0.0, transfer_norm2 = 0.0;
  double radiance_error2 = 0.0, radiance_norm2 = 0.0;
  double transfer_relative() const;   ///< sqrt(error2 / norm2); 0 when norm2 is 0
  double radiance_relative() const;
};

struct CompressedTransfer {
  /// The uncompressed transfer's header (kind, bands, bands_out, channels, vertex and triangle count,
  /// mesh fingerprint, parameters JSON); `source.scalar` is the scalar type of the compressed values.
  transfer::Header source;
  int clusters = 0;                     ///< K
  int pca = 0;                          ///< N
  int iterations = 0;                   ///< CPCA rounds run
  /// The model also holds the transfer's bounce-only part (TransferData::bounce_only): each point is
  /// [T_p, T_b,p], 2D values, fitted together (one cluster and one set of weights per vertex).
  bool bounce = false;
  std::vector<float> means;             ///< K x point_dimension() (already rounded to source.scalar)
  std::vector<float> bases;             ///< K x N x point_dimension()
  std::vector<std::uint32_t> cluster;   ///< per point (vertex or non-empty texel), < K
  std::vector<float> weights;           ///< per point, N
  /// Texel (lightmap) transfer (source.is_texel()): the source's coverage mask, W x H. The model's points
  /// are the non-empty texels (covered and gutter) in row-major order (point_blocks); empty texels are 0.
  std::vector<std::uint8_t> coverage;
  std::uint64_t texel_points = 0;       ///< texel transfer: the number of non-empty texels
  bool has_radiance_error = false;
  ErrorSums total;
  std::vector<ErrorSums> per_cluster;   ///< K entries
  /// P: the model's points: the vertices, or the non-empty texels of a texel transfer.
  std::uint64_t point_count() const { return source.is_texel() ? texel_points : source.vertex_count; }
  /// D: the transfer's values per vertex.
  std::size_t dimension() const { return static_cast<std::size_t>(source.values_per_vertex()); }
  /// Values per mean or direction: D, or 2D with the bounce-only section.
  std::size_t point_dimension() const { return dimension() * (bounce ? 2 : 1); }
};

/// The block each point of a model stands for (block b = values at b * values per vertex): every vertex
/// of a per-vertex transfer; the texels of `coverage` that are not transfer::kTexelEmpty, in row-major
/// order, of a texel transfer (header.is_texel()).
std::vector<std::size_t> point_blocks(const transfer::Header& header, const std::vector<std::uint8_t>& coverage);

/// Compresses `transfer` (any kind, 1 or 3 channels, per vertex or per texel: the points are its
/// point_blocks; with its bounce-only part if it has one) with CPCA, stores the model as `scalar` (float16
/// rounds means, directions and weights to nearest even) and fills the transfer-space error sums of
/// the stored model. `what` names the input in errors (bad K, N, iterations).
/// With a `metric` (metric.h; null or identity: plain L2 of the values), CPCA runs on G T_p and the
/// fitted means and directions are mapped back by G^-1 (its dimension: the points', 1 or 2 sections): the stored model is still of T_p (directions
/// then orthonormal in the metric, not in plain L2) and minimises the metric's error.
CompressedTransfer compress_transfer(const transfer::TransferData& transfer, const CpcaOptions& options, transfer::Scalar scalar,
                                     const std::string& what, const Metric* metric = nullptr);

/// The shaded-radiance metric (metric.h) for `transfer` as compress_transfer sees it: one section, or
/// two with its bounce-only part; for glossy through the BRDF it was baked with. Throws prt::Error
/// naming `what` if a glossy transfer records no BRDF.
Metric transfer_metric(const transfer::TransferData& transfer, const MetricLighting& lighting, const std::string& what);

/// Reconstruction of compressed point p (0 <= p < compressed.cluster.size()) into
/// out[0, compressed.point_dimension()): the cluster's mean plus the weighted PCA directions, summed in
/// double in a fixed order (the same bytes for any thread count).
void reconstruct_point(const CompressedTransfer& compressed, std::size_t p, float* out);

/// The reconstruction mu_k + sum_n w_pn b_kn of every point, as a float32 TransferData with the
/// source header (and bounce_only from the model's second section, if it has one); a texel transfer
/// gets its coverage mask back and zeros in its empty texels.
transfer::TransferData decompress(const CompressedTransfer& compressed);

/// Adds the shaded-radiance error sums against the uncompressed `original` (see the header comment)
/// of what the transfer shades: T . sky (+ T_b . discs, the discs' SH, when the transfer has a
/// bounce-only part and `discs` is given; the discs' direct light is exact and not counted). World-frame
/// radiance coefficients. Throws prt::Error naming `what` if a glossy transfer records no BRDF.
void add_radiance_error(CompressedTransfer& compressed, const transfer::TransferData& original, const sh::RgbCoefficients& sky,
                        const std::string& what, const sh::RgbCoefficients* discs = nullptr);

/// Payload bytes of the uncompressed transfer's values (one section; a texel file's every texel) stored
/// as `scalar` (cprt_file.h gives the compressed).
std::uint64_t uncompressed_bytes(const transfer::Header& header, transfer::Scalar scalar);

}  // namespace prt::compress
