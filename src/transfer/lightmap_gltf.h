#pragma once
// The texture half of `prt bake --lightmap --gltf OUT.glb` (docs/formats.md, "Lightmap transfer in
// glTF"): a texel transfer's values as KTX2 float16 2D-array textures and the glTF extension object
// PRT_lightmap_transfer that references them. mesh::write_glb_textured writes the file.
#include <string>
#include <vector>

#include "transfer/transfer_file.h"

namespace prt::transfer {

/// Extension name, in extensionsUsed (not extensionsRequired: an engine without it still loads the mesh).
inline constexpr const char* kLightmapExtension = "PRT_lightmap_transfer";

/// A texel transfer's textures: KTX2 RGBA16F 2D arrays of texel_width x texel_height and
/// ceil(channels bands^2 / 4) layers. Layer k, texel (i, j) holds the texel's values 4k .. 4k+3 (its
/// block in the file's order: channel-major, then SH index), the last layer zero-padded; rows top
/// (v = 0) first, as the file's texels. One texture for the transfer, a second for its bounce-only
/// section when the file has one. Throws prt::Error for a per-vertex or glossy transfer, or values
/// that do not match the header.
std::vector<std::string> lightmap_ktx2_textures(const TransferData& transfer);

/// The extension object (JSON text) for a primitive whose TEXCOORD_<texcoord> is the lightmap UV,
/// with the textures of lightmap_ktx2_textures as images first_image, first_image + 1:
/// {"texCoord", "kind", "bands", "channels", "width", "height", "layers", "layout", "transfer" (image
/// index), "bounceOnly" (image index, only with a bounce-only section)}.
std::string lightmap_extension_json(const Header& header, int texcoord, int first_image);

}  // namespace prt::transfer
