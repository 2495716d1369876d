#pragma once
// The mip chain of a lightmap layer (renderer_lightmap.h), computed on the CPU because a plain box
// filter would average a chart's texels with the empty texels around it and darken every chart's rim
// at a distance. No GL here.
//
// RULE: level l+1 has max(1, w/2) x max(1, h/2) texels (OpenGL's sizes). Its texel (x, y) is the mean of
// the FILLED texels among its children (2x, 2x+1) x (2y, 2y+1) of level l (the last row or column of an
// odd size also takes the leftover child), and is filled if any child is. Then one round of dilation:
// each unfilled texel with a filled 8-neighbour gets the mean of its filled 8-neighbours (computed from
// the level before the round) and becomes filled, so that bilinear reads one texel outside a chart stay
// in its values, as the bake's gutters do at level 0. Level 0 is the file's texels, filled where the
// coverage mask is not empty.
#include <cstdint>
#include <vector>

namespace prt::render {

struct MipLevel {
  int width = 0, height = 0;
  std::vector<float> rgba;            ///< 4 floats per texel, row-major
  std::vector<std::uint8_t> filled;   ///< 1 per texel
};

/// The next level of `level` by the rule above. Precondition: level.width > 1 or level.height > 1.
MipLevel next_mip_level(const MipLevel& level);

/// Levels a w x h texture's full chain has: 1 + floor(log2(max(w, h))).
int mip_level_count(int width, int height);

}  // namespace prt::render
