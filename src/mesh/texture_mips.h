#pragma once
// Box-filtered mip levels of a base colour texture: the texture at coarser resolutions, each texel the
// mean of the texels it covers, for lookups whose footprint spans many texels (a bounce hit's ray cone,
// a large triangle's quadrature: mesh/texture.h). One pyramid per texture, built once, deterministically.
#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/material.h"

namespace prt::mesh {

/// Level 0 is the texture itself (not copied: the pyramid holds a pointer, so the texture must outlive
/// it and not move). Level k >= 1 is width_k x height_k, width_k = max(1, floor(width_{k-1} / 2)) (the
/// same for height), linear RGB floats (Texture::rgb; codes empty); its texel (x, y) is the mean, summed
/// in float in row order, of the level k-1 texels with column in [floor(x width_{k-1} / width_k),
/// floor((x + 1) width_{k-1} / width_k)) and row likewise: blocks of 2 x 2 texels, 3 where a size was
/// odd, 1 along an axis already 1 texel wide. For a power-of-two texture, a level-k texel is the mean
/// (up to float rounding) of the 2^k x 2^k level-0 texels it covers. Levels stop at 1 x 1.
class TextureMips {
 public:
  /// Builds levels 1.. from `texture` (rgb or codes; width, height >= 1). Cost: about 4/3 x the
  /// texture's texel count of reads; memory coarse_bytes(width, height).
  explicit TextureMips(const Texture& texture);

  /// The bytes that levels 1.. of a width x height texture's pyramid hold (each side halved, rounded
  /// down, at least 1; 3 floats per texel): about 4 per level-0 texel, up to 12 for a texture one texel thin.
  static std::uint64_t coarse_bytes(int width, int height);

  /// The number of levels, level 0 included: floor(log2(max(width, height))) + 1.
  int level_count() const { return static_cast<int>(coarse_.size()) + 1; }
  /// Level k, 0 <= k < level_count().
  const Texture& level(int k) const { return k == 0 ? *base_ : coarse_[static_cast<std::size_t>(k - 1)]; }

 private:
  const Texture* base_;
  std::vector<Texture> coarse_;
};

/// The pyramids of a mesh's textures, by image index (Mesh::textures); null where not built.
using MeshMips = std::vector<std::unique_ptr<TextureMips>>;

/// A pyramid for each texture i of `textures` with needed[i] (needed.size() == textures.size()), null
/// for the others; textures in parallel on `threads` threads (0: all), each built by one thread alone, so
/// the levels do not depend on the thread count. The pyramids point into `textures`.
MeshMips build_mips(const std::vector<Texture>& textures, const std::vector<bool>& needed, int threads);

}  // namespace prt::mesh
