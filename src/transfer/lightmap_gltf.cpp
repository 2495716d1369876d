// Lightmap transfer textures for glTF (lightmap_gltf.h).
#include "transfer/lightmap_gltf.h"

#include "core/error.h"
#include "transfer/ktx2.h"

namespace prt::transfer {

namespace {

Ktx2Image layered(const Header& header, const std::vector<float>& values) {
  const std::size_t texels = static_cast<std::size_t>(header.texel_width) * header.texel_height;
  const std::size_t per_texel = static_cast<std::size_t>(header.values_per_vertex());
  Ktx2Image image;
  image.width = static_cast<int>(header.texel_width);
  image.height = static_cast<int>(header.texel_height);
  image.layers = static_cast<int>((per_texel + 3) / 4);
  image.rgba.assign(texels * 4 * static_cast<std::size_t>(image.layers), 0.0f);
  for (std::size_t b = 0; b < texels; ++b)
    for (std::size_t v = 0; v < per_texel; ++v) image.rgba[((v / 4) * texels + b) * 4 + v % 4] = values[b * per_texel + v];
  return image;
}

}  // namespace

std::vector<std::string> lightmap_ktx2_textures(const TransferData& transfer) {
  const Header& h = transfer.header;
  if (!h.is_texel()) fail("glTF lightmap: the transfer is per vertex, not a texel (lightmap) transfer");
  if (is_glossy(h.kind)) fail("glTF lightmap: glossy texel transfer is not supported");
  const std::uint64_t count = static_cast<std::uint64_t>(h.texel_width) * h.texel_height * h.values_per_vertex();
  if (transfer.values.size() != count || (!transfer.bounce_only.empty() && transfer.bounce_only.size() != count))
    fail("glTF lightmap: the transfer's values do not match its header");
  std::vector<std::string> out{write_ktx2_rgba16f(layered(h, transfer.values))};
  if (!transfer.bounce_only.empty()) out.push_back(write_ktx2_rgba16f(layered(h, transfer.bounce_only)));
  return out;
}

std::string lightmap_extension_json(const Header& header, int texcoord, int first_image) {
  const std::uint64_t per_texel = header.values_per_vertex();
  std::string json = "{\"texCoord\":" + std::to_string(texcoord) + ",\"kind\":\"" + kind_name(header.kind) +
                     "\",\"bands\":" + std::to_string(header.bands) + ",\"channels\":" + std::to_string(header.channels) +
                     ",\"width\":" + std::to_string(header.texel_width) + ",\"height\":" + std::to_string(header.texel_height) +
                     ",\"layers\":" + std::to_string((per_texel + 3) / 4) +
                     ",\"layout\":\"value 4k+c of a texel's block (channel-major, then SH index l(l+1)+m) in component c of layer k\"" +
                     ",\"transfer\":" + std::to_string(first_image);
  if (header.bounce_only_section) json += ",\"bounceOnly\":" + std::to_string(first_image + 1);
  return json + "}";
}

}  // namespace prt::transfer
