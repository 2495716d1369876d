// Reading side of a compressed transfer: reconstruction of points, decompression and sizes. Kept apart
// from the compressor (compressed.cpp, cpca.cpp, metric.cpp) so that a reader of .cprt files, the fuzz
// target included, needs neither the CPCA fit nor the shading.
#include <algorithm>
#include <cmath>

#include "compress/compressed.h"
#include "core/error.h"

namespace prt::compress {

void reconstruct_point(const CompressedTransfer& c, std::size_t p, float* out) {
  const std::size_t D = c.point_dimension(), N = static_cast<std::size_t>(c.pca), k = c.cluster[p];
  const float* mean = &c.means[k * D];
  const float* w = &c.weights[p * N];
  for (std::size_t i = 0; i < D; ++i) {
    double s = mean[i];
    for (std::size_t n = 0; n < N; ++n) s += static_cast<double>(w[n]) * c.bases[(k * N + n) * D + i];
    out[i] = static_cast<float>(s);
  }
}

double ErrorSums::transfer_relative() const { return transfer_norm2 > 0.0 ? std::sqrt(transfer_error2 / transfer_norm2) : 0.0; }
double ErrorSums::radiance_relative() const { return radiance_norm2 > 0.0 ? std::sqrt(radiance_error2 / radiance_norm2) : 0.0; }

std::vector<std::size_t> point_blocks(const transfer::Header& h, const std::vector<std::uint8_t>& coverage) {
  std::vector<std::size_t> blocks;
  if (!h.is_texel()) {
    blocks.resize(static_cast<std::size_t>(h.vertex_count));
    for (std::size_t p = 0; p < blocks.size(); ++p) blocks[p] = p;
    return blocks;
  }
  for (std::size_t t = 0; t < coverage.size(); ++t)
    if (coverage[t] != transfer::kTexelEmpty) blocks.push_back(t);
  return blocks;
}

transfer::TransferData decompress(const CompressedTransfer& c) {
  transfer::TransferData t;
  t.header = c.source;
  t.header.scalar = transfer::Scalar::float32;
  t.header.bounce_only_section = c.bounce;
  t.coverage = c.coverage;
  const std::size_t D = c.dimension(), E = c.point_dimension();
  const std::vector<std::size_t> blocks = point_blocks(c.source, c.coverage);
  if (blocks.size() != c.cluster.size()) fail("internal: the compressed transfer's points do not match its coverage");
  t.values.assign(static_cast<std::size_t>(c.source.block_count()) * D, 0.0f);
  if (c.bounce) t.bounce_only.assign(t.values.size(), 0.0f);
  std::vector<float> block(E);
  for (std::size_t p = 0; p < blocks.size(); ++p) {
    reconstruct_point(c, p, block.data());
    std::copy_n(block.data(), D, &t.values[blocks[p] * D]);
    if (c.bounce) std::copy_n(block.data() + D, D, &t.bounce_only[blocks[p] * D]);
  }
  return t;
}

std::uint64_t uncompressed_bytes(const transfer::Header& header, transfer::Scalar scalar) {
  return header.block_count() * header.values_per_vertex() * (scalar == transfer::Scalar::float16 ? 2 : 4);
}

}  // namespace prt::compress
