#pragma once
// Denoising of texel transfer (`prt bake --lightmap ... --denoise`; docs/conventions.md, "Lightmap
// charts, denoising and seams"). Filters the transfer COEFFICIENTS, not a lit image: every weight depends only on guides
// that no lighting changes, and the same weight multiplies every coefficient of a texel (both
// sections), so the filtered lightmap is linear in the lighting like the bake and one denoised bake
// serves every environment.
//
// FILTER. An edge-avoiding a-trous wavelet filter (Dammertz et al., "Edge-Avoiding A-Trous Wavelet
// Transform for fast Global Illumination Filtering", HPG 2010) over the covered texels, with a
// noise-aware range weight in the spirit of SVGF (Schied et al., HPG 2017) and non-local means (Buades
// et al., CVPR 2005). Iteration i (step s = 2^i texels) sets each covered texel p to
// sum_q w(p,q) T_q / sum_q w(p,q) over the 3 x 3 taps q = p + s (dx, dy), dx, dy in {-1, 0, 1}, that
// are covered texels of p's chart (the centre q = p always with weight 1/4), with
//   w(p,q) = h(dx) h(dy)                                         h = (1/4, 1/2, 1/4): B-spline taps
//          * exp(-(n_p . (x_q - x_p))^2 / (plane_sigma * size_p)^2   off p's tangent plane
//                - D(p,q) / (value_sigma^2 (v_p + v_q) + f_i^2 |T_p|^2))    f_i = value_floor floor_decay^i
//          * max(0, n_p . n_q)^normal_power                           normals turning
// where x, n are the texel's sample position and unit normal, size_p the world size of a texel there
// (charts.h), T the texel's whole transfer vector (every coefficient of every channel; the bounce-only
// section follows the weights of `values`), and D(p,q) = max(0, |T_q - T_p|^2 - v_p - v_q) the squared
// distance of the two vectors less what their noise alone gives it. |T_q - T_p|^2 is the mean squared
// difference of the two texels' lit values over lightings with independent unit SH coefficients, so the
// range weight keeps apart texels that some lighting tells apart (a contact shadow, the shadow of a
// compact light), whichever lighting is used later. v_p is the noise variance (summed over the vector)
// of T_p: at the start the median, over the chart's texels in p's 5 x 5 window, of the squared norm of
// each texel's difference from the mean of its chart's 3 x 3 neighbours (x k/(k-1) for k texels);
// each iteration propagates it as v_p <- sum w^2 v_q / (sum w)^2. Gutter and empty texels are not
// read or written (refill the gutters afterwards, gutter.h). The weights of each texel then become
// those of a weighted local linear fit (`linear`), its slopes damped by a ridge (`slope_ridge`).
// TWICING (Tukey 1977). The levels S above, with their weights kept, filter the residual once more:
// T <- S T + twicing x S (T - S T). At equal settings this about halves S's bias (curvature, one-sided
// taps) and leaves more noise: on the test's box scene (a 4096-sample bake filtered and compared with
// itself, sunrise) 0.27% -> 0.15% at value_floor 0.01. The defaults spend the gain on a wider range
// weight (docs/conventions.md has the figures).
// Still one fixed linear map per texel: linear in the lighting.
// INTERLEAVED SAMPLES. A bake that will be denoised gives the texels of each tile complementary sample
// sets, border texels also their empty neighbours' sets (interleaved_sampling) and texels on a steep
// falloff of the direct light three more of their own (add_contact_sets), so that neighbouring texels'
// noise largely cancels in the filter's sums and texels with few neighbours to average get more samples.
// Deterministic: each iteration reads only the previous one's values, so the bytes do not depend on
// the thread count.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "lightmap/rasterize.h"
#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::lightmap {

struct DenoiseOptions {
  bool linear = true;          ///< weighted local linear fit instead of the weighted mean (no bias from one-sided taps)
  int iterations = 4;          ///< a-trous levels (steps 1, 2, 4, ...): footprint 2^(iterations+1) - 1 texels; 0..12
  float plane_sigma = 0.5f;    ///< tangent-plane distance scale, in texels' world size; > 0
  float normal_power = 64.0f;  ///< exponent of the normal weight; >= 0
  float value_sigma = 1.0f;    ///< transfer distance scale, in noise standard deviations; > 0 (infinity: no range weight)
  float value_floor = 0.25f;   ///< transfer distance scale floor at level 0, relative to |T_p| (noise-free regions); >= 0
  float floor_decay = 0.6f;    ///< value_floor shrinks by this factor per level (wider steps see larger real differences); (0, 1]
  float slope_ridge = 0.1f;    ///< ridge on the linear fit's slopes, relative to the weight sum; 0.001..10
  float twicing = 1.0f;        ///< add this share of the filtered residual (input - filtered) back; 0..1 (0: off)
  bool interleave = true;      ///< the bake gives the texels interleaved sample sets and frames (interleaved_sampling)
  int threads = 0;             ///< 0 = all cores; the output does not depend on it
};

/// The guides of a lightmap, one per texel (row-major, width x height); meaningful at covered texels.
struct DenoiseGuides {
  int width = 0, height = 0;
  std::vector<std::uint8_t> covered;   ///< 1 at covered texels (their transfer is filtered), else 0
  std::vector<glm::vec3> position, normal;  ///< the texel's sample point and unit normal (rasterize.h)
  std::vector<float> size;             ///< world size of a texel at the sample (charts.h), > 0
  std::vector<std::uint32_t> chart;    ///< the chart of the sample's triangle (charts.h)
};

/// The guides of `samples`, the texel samples of `mesh`'s lightmap (texel_bake.h, texel_samples).
DenoiseGuides denoise_guides(const mesh::Mesh& mesh, const TexelSamples& samples);

/// Interleaved sampling for a bake that will be denoised (Keller and Heidrich, "Interleaved Sampling",
/// EGWR 2001): per texel sample, in the order of samples.samples, the sample set it traces. The grid is cut into tiles of 2^L x 2^L texels, L = interleaved_tile_bits(S) (16 x 16
/// up to S = 1024 samples per texel), and the 4^L texels of a tile trace the 4^L different sets of
/// bake::make_interleaved_sample_sets (consecutive blocks of S points of one Sobol sequence): texel
/// (i, j) traces set k = k0 xor h_tile: the bits of k0 interleave those of x = (i xor j) mod 2^L
/// (bits 0, 2, ...) and y = i mod 2^L (bits 1, 3, ...) (k0 is the bit-reversed Bayer index), h_tile in
/// 0..4^L - 1 is hashed from (seed, tile). So every aligned 2 x 2 block traces 4 consecutive sets (for
/// S = 2^m together a (0,m+2,2)-net), every aligned 4 x 4 block 16 (a (0,m+4,2)-net), and so on up to
/// the tile (a XOR maps aligned blocks of sets onto aligned blocks): neighbouring texels sample
/// complementary strata in elevation and azimuth alike, and their noise largely cancels in the filter's
/// sums; h_tile keeps tiles from repeating one another's pattern. The frames are not turned (the bake sets
/// PassContext::unturned_frames): a turn per tile measured worse (docs/conventions.md). Each texel alone keeps an
/// S-direction set as good as an undenoised bake's.
/// BORDERS. An empty texel next to a covered one would have traced its set too: its covered neighbour
/// (the first covered of its left, right, lower, upper neighbours, then its four diagonal ones, in that
/// order) traces that set as an extra point at its own sample, and the texel's transfer is the mean of
/// its points. So the blocks at a chart's border still trace their whole nets, and a border texel, which
/// the filter can average only with the neighbours on one side, has 2-4 times the samples.
struct InterleavedSampling {
  int tile_bits = 0;              ///< L
  std::vector<std::uint8_t> set;  ///< 0..4^L - 1: the texel samples' sets, then the extra points' sets
  std::vector<std::uint32_t> extra_sample;  ///< per extra point: the texel sample (index in samples.samples) it adds to
};
InterleavedSampling interleaved_sampling(const TexelSamples& samples, int sample_count, std::uint32_t seed);

/// CONTACT. A texel on a steep falloff of the direct light (a contact shadow) can be averaged only with
/// few neighbours (the range weight stops at the falloff), so it traces more sets of its own: a texel
/// sample whose albedo-free direct transfer's first coefficient g (`dc`, per texel of the width x height
/// grid, read at covered texels of samples.coverage) differs by more than kContactContrast x Y_00 (g of an
/// unoccluded point) between the covered texels two texels away on its two sides, along u or along v,
/// gets kContactSets extra points at its own sample: its set xor 2^(2L-1), xor 2^(2L-2) and xor both (sets
/// from the other quarters of its tile), appended to `sampling` (set, extra_sample) in sample order.
/// Nothing for L = 0. Returns the number of texels that get them.
inline constexpr float kContactContrast = 0.4f;
inline constexpr int kContactSets = 3;
std::size_t add_contact_sets(const TexelSamples& samples, const std::vector<float>& dc, InterleavedSampling& sampling);

/// L: the largest in 0..4 with 4^L x sample_count <= 2^18 (the sets' directions and basis rows stay
/// under ~60 MB at 5 bands).
int interleaved_tile_bits(int sample_count);

/// Throws prt::OptionError naming the field for options out of range.
void validate_denoise_options(const DenoiseOptions& options);

/// Filters the covered texels of `values` (and of `bounce_only` unless it is empty; same layout, same
/// weights), blocks of `stride` floats per texel, in place. Gutter and empty texels are left as they
/// are: refill the gutters afterwards (gutter.h, fill_gutter). Throws prt::OptionError for options out
/// of range.
void denoise_texels(std::vector<float>& values, std::vector<float>& bounce_only, std::size_t stride,
                    const DenoiseGuides& guides, const DenoiseOptions& options, const std::vector<float>* noise = nullptr);

}  // namespace prt::lightmap
