#include "mesh/texture_mips.h"

#include <algorithm>
#include <array>

#include "core/parallel.h"
#include "mesh/texture.h"

namespace prt::mesh {

namespace {

// Level k's block along an axis of `from` texels halved to `to`: [first(x), first(x + 1)).
std::size_t block_start(std::size_t x, std::size_t from, std::size_t to) { return x * from / to; }

// The next level down from `fine` (texture_mips.h): each texel the mean of its block, summed in float
// in row order, from the linear values `value(i)` of fine's value index i.
template <class Value>
Texture halve(const Texture& fine, Value value) {
  const std::size_t fw = std::size_t(fine.width), fh = std::size_t(fine.height);
  Texture coarse;
  coarse.width = std::max(1, fine.width / 2);
  coarse.height = std::max(1, fine.height / 2);
  coarse.source = fine.source;
  const std::size_t cw = std::size_t(coarse.width), ch = std::size_t(coarse.height);
  coarse.rgb.resize(cw * ch * 3);
  std::vector<std::size_t> columns(cw + 1);  // the blocks' first columns, and fw
  for (std::size_t x = 0; x <= cw; ++x) columns[x] = block_start(x, fw, cw);
  for (std::size_t y = 0; y < ch; ++y) {
    const std::size_t y0 = block_start(y, fh, ch), y1 = block_start(y + 1, fh, ch);
    for (std::size_t x = 0; x < cw; ++x) {
      const std::size_t x0 = columns[x], x1 = columns[x + 1];
      float* out = &coarse.rgb[(y * cw + x) * 3];
      if (x1 - x0 == 2 && y1 - y0 == 2) {  // the usual 2 x 2 block, unrolled: the same sums in the same order
        const std::size_t a = (y0 * fw + x0) * 3, b = a + fw * 3;
        for (std::size_t c = 0; c < 3; ++c) out[c] = (((value(a + c) + value(a + 3 + c)) + value(b + c)) + value(b + 3 + c)) / 4.0f;
        continue;
      }
      float sum[3] = {0.0f, 0.0f, 0.0f};
      for (std::size_t j = y0; j < y1; ++j)
        for (std::size_t i = x0; i < x1; ++i)
          for (std::size_t c = 0; c < 3; ++c) sum[c] += value((j * fw + i) * 3 + c);
      const float count = float((x1 - x0) * (y1 - y0));
      for (std::size_t c = 0; c < 3; ++c) out[c] = sum[c] / count;
    }
  }
  return coarse;
}

Texture halve(const Texture& fine) {
  if (fine.codes.empty()) return halve(fine, [rgb = fine.rgb.data()](std::size_t i) { return rgb[i]; });
  return halve(fine, [codes = fine.codes.data(), decode = srgb8_decode().data()](std::size_t i) { return decode[codes[i]]; });
}

}  // namespace

TextureMips::TextureMips(const Texture& texture) : base_(&texture) {
  int levels = 0;
  for (int w = texture.width, h = texture.height; w > 1 || h > 1; w = std::max(1, w / 2), h = std::max(1, h / 2)) ++levels;
  coarse_.reserve(std::size_t(levels));  // `fine` points into coarse_: no reallocation
  const Texture* fine = &texture;
  while (fine->width > 1 || fine->height > 1) {
    coarse_.push_back(halve(*fine));
    fine = &coarse_.back();
  }
}

std::uint64_t TextureMips::coarse_bytes(int width, int height) {
  std::uint64_t bytes = 0;
  for (std::uint64_t w = std::uint64_t(std::max(width, 1)), h = std::uint64_t(std::max(height, 1)); w > 1 || h > 1;) {
    w = std::max<std::uint64_t>(1, w / 2);
    h = std::max<std::uint64_t>(1, h / 2);
    bytes += 12 * w * h;
  }
  return bytes;
}

MeshMips build_mips(const std::vector<Texture>& textures, const std::vector<bool>& needed, int threads) {
  MeshMips mips(textures.size());
  parallel_for(textures.size(), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      if (needed[i]) mips[i] = std::make_unique<TextureMips>(textures[i]);
  });
  return mips;
}

}  // namespace prt::mesh
