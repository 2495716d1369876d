#include "shade/shade.h"

#include <algorithm>

#include "core/error.h"

namespace prt::shade {

std::vector<glm::vec3> shade_diffuse(const transfer::TransferData& transfer, const sh::RgbCoefficients& lighting) {
  const transfer::Header& h = transfer.header;
  if (transfer::is_glossy(h.kind)) fail("shade_diffuse needs a diffuse transfer, not " + std::string(transfer::kind_name(h.kind)));
  const std::size_t coefficients = static_cast<std::size_t>(h.bands) * h.bands;
  const std::size_t used = std::min<std::size_t>(coefficients, lighting.values.size());
  const std::size_t stride = h.values_per_vertex();
  std::vector<glm::vec3> out(h.block_count());  // per vertex, or per texel of a lightmap
  for (std::size_t v = 0; v < out.size(); ++v) {
    const float* t = transfer.values.data() + v * stride;
    glm::dvec3 sum(0.0);
    for (int c = 0; c < 3; ++c) {
      const float* tc = t + (h.channels == 3 ? c : 0) * coefficients;
      double s = 0.0;
      for (std::size_t i = 0; i < used; ++i) s += static_cast<double>(tc[i]) * lighting.values[i][c];
      sum[c] = s;
    }
    out[v] = glm::vec3(sum);
  }
  return out;
}

int shading_bands(const transfer::Header& header, int requested) {
  const int transfer_bands = static_cast<int>(header.bands);
  if (requested < 0 || requested > transfer_bands)
    fail_option("bands", ": must be between 1 and the transfer's " + std::to_string(transfer_bands) + " bands, got " +
                             std::to_string(requested));
  return requested == 0 ? transfer_bands : requested;
}

}  // namespace prt::shade
