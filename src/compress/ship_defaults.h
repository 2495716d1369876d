#pragma once
// "Bake high, ship light" (issue 36; docs/conventions.md, "Bake high, ship light"): the defaults of a
// diffuse bake written compressed (`prt bake MESH -o T.cprt`; per texel with `--lightmap SIZE`:
// ship_texel_compression). The bake's cost hardly grows
// with the band count (rays dominate), so it bakes kHighBands bands, where the truncation floor under
// real skies is a third of 5 bands'; clustered PCA (cpca.h) then ships that transfer at the run-time
// cost and file size of an uncompressed 5-band file: the renderer shades a compressed vertex with
// N + 1 <= 25 blend weights instead of 25 products, and the file holds a per-vertex cluster id and N
// float16 weights plus K (N + 1) float16 vectors of bands^2 values.
#include <cstddef>
#include <cstdint>

#include "sh/coefficients.h"

namespace prt::compress {

inline constexpr int kHighBands = 16;      ///< bands of the compressed default bake
inline constexpr int kShipBands = 5;       ///< bands of the uncompressed default bake (.prt)
inline constexpr int kMaxShipPca = 24;     ///< N + 1 = 25 blend weights: the products of 5 bands shaded directly
inline constexpr int kVerticesPerCluster = 256;
inline constexpr int kMaxShipClusters = 64;
/// The compressed default's CPCA rounds run on at most this many points (cpca.h, "fitting on a
/// subset"), and at most kShipRounds of them: on a 256 x 256 lightmap (about 50k texels) this cuts the
/// compression's time by about 3x for about 4% more transfer error (docs/conventions.md, "Bake high,
/// ship light").
inline constexpr std::size_t kShipFitPoints = 8192;
inline constexpr int kShipRounds = 8;

/// The CPCA setting of the compressed default.
struct ShipCompression {
  int clusters = 1;  ///< K
  int pca = 1;       ///< N
  std::size_t fit_points = kShipFitPoints;  ///< S (cpca.h)
  int rounds = kShipRounds;                 ///< most CPCA rounds
};

/// The compressed default for a per-vertex transfer of `vertices` (>= 1) vertices, `channels` (1 or 3)
/// channels, `sections` (1, or 2 with the bounce-only part) and `bands` bands (kHighBands unless
/// --bands), stored as float16:
///   K = vertices / 256 rounded down, clamped to 1..64 (Sloan et al. 2003 use clusters of a few hundred
///       vertices: each cluster then spans a patch of similar normals and occluders);
///   N = the largest in 1..24 whose payload, estimated as
///       vertices (4 + 2N) + K ((N + 1) channels sections bands^2 2 + 64)  bytes
///       (a u32 cluster id and N weights per vertex; per cluster a mean, N directions and its error sums),
///       is at most that of the uncompressed 5-band float32 file, vertices channels sections 25 4 bytes.
/// N <= 24 keeps the renderer's per-vertex work (N + 1 weights per channel) within the 25 products of
/// 5 bands. A mesh too small for N = 1 to fit still gets N = 1.
ShipCompression ship_compression(std::uint64_t vertices, int channels, int sections, int bands);

/// The compressed default for a texel (lightmap) transfer (`prt bake MESH --lightmap SIZE -o T.cprt`): the
/// rule of ship_compression with the model's points, the `points` non-empty texels (>= 1), in place of
/// the vertices, and the budget of the uncompressed 5-band float32 texel .prt, which stores every one of
/// the `texels` (W x H >= points) texels: K = points / 256 clamped to 1..64; N the largest in 1..24 with
///   points (4 + 2N) + K ((N + 1) channels sections bands^2 2 + 64)  <=  texels channels sections 25 4
/// (both files also hold the W x H coverage mask, left out of both sides). The renderer shades each
/// non-empty texel with N + 1 <= 25 products per channel, once per lighting change
/// (render/pass_lightmap_cpca.cpp), where the 5-band lightmap takes 25 per pixel every frame.
ShipCompression ship_texel_compression(std::uint64_t points, std::uint64_t texels, int channels, int sections, int bands);

/// The lighting prior the compressed default is fitted to (CompressionRequest::metric_sky): zonal
/// coefficients c_(l,0) = sqrt((2l+1) / (l+1)^2), the same in every colour, so that its rotation-averaged
/// spectrum (metric.h) is s_l = (l+1)^-2. Real skies fall off with the band: the eight maps of
/// tests/data/hdri, their discs split off, fit s_l ~ (l+1)^-p with p from 1.5 to 3.9 (median 2.3);
/// fitting CPCA to that prior instead of a flat spectrum spends its directions on the low bands that
/// carry the shading (measured: docs/conventions.md, "Bake high, ship light").
/// Precondition: 1 <= bands <= sh::kMaxBands.
sh::RgbCoefficients ship_metric_sky(int bands);

}  // namespace prt::compress
