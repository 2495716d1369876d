#include "render/lightmap_mips.h"

#include <algorithm>

namespace prt::render {

namespace {

// Children of parent index p along an axis of `size` texels whose parent level has `parents`.
void children(int p, int size, int parents, int& first, int& last) {
  first = std::min(2 * p, size - 1);
  last = std::min(p == parents - 1 ? size - 1 : 2 * p + 1, size - 1);
}

}  // namespace

int mip_level_count(int width, int height) {
  int levels = 1;
  for (int side = std::max(width, height); side > 1; side /= 2) ++levels;
  return levels;
}

MipLevel next_mip_level(const MipLevel& level) {
  MipLevel out;
  out.width = std::max(1, level.width / 2);
  out.height = std::max(1, level.height / 2);
  const std::size_t count = static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height);
  out.rgba.assign(count * 4, 0.0f);
  out.filled.assign(count, 0);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      int x0, x1, y0, y1;
      children(x, level.width, out.width, x0, x1);
      children(y, level.height, out.height, y0, y1);
      float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      int n = 0;
      for (int cy = y0; cy <= y1; ++cy)
        for (int cx = x0; cx <= x1; ++cx) {
          const std::size_t c = static_cast<std::size_t>(cy) * level.width + cx;
          if (!level.filled[c]) continue;
          ++n;
          for (int k = 0; k < 4; ++k) sum[k] += level.rgba[4 * c + k];
        }
      if (n == 0) continue;
      const std::size_t t = static_cast<std::size_t>(y) * out.width + x;
      out.filled[t] = 1;
      for (int k = 0; k < 4; ++k) out.rgba[4 * t + k] = sum[k] / static_cast<float>(n);
    }
  // One round of dilation from the averaged level.
  const MipLevel averaged = out;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * out.width + x;
      if (averaged.filled[t]) continue;
      float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= out.width || ny >= out.height) continue;
          const std::size_t c = static_cast<std::size_t>(ny) * out.width + nx;
          if (!averaged.filled[c]) continue;
          ++n;
          for (int k = 0; k < 4; ++k) sum[k] += averaged.rgba[4 * c + k];
        }
      if (n == 0) continue;
      out.filled[t] = 1;
      for (int k = 0; k < 4; ++k) out.rgba[4 * t + k] = sum[k] / static_cast<float>(n);
    }
  return out;
}

}  // namespace prt::render
