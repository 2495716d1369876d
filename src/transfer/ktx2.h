#pragma once
// KTX 2.0 textures of VK_FORMAT_R16G16B16A16_SFLOAT (four float16 channels per texel), uncompressed, one
// mip level, one face: what prt writes for engines (the Bevy irradiance volume, the lightmap transfer
// textures of `prt bake --lightmap --gltf`). Layout per the Khronos KTX 2.0 specification: the 80-byte
// header, one level index entry, a Basic Data Format Descriptor (model RGBSDA, primaries BT.709,
// linear transfer, samples R, G, B, A of 16 bits, FLOAT | SIGNED), a "KTXwriter" key/value, then the
// level data at an 8-byte aligned offset: texels x fastest, then rows y (row 0 first: KTX2's default
// orientation "rd", the top row), then slices z, then array layers.
#include <string>
#include <vector>

namespace prt::transfer {

/// A texture's size and texels, RGBA floats (converted to and from float16, nearest even).
struct Ktx2Image {
  int width = 0, height = 0;
  int depth = 0;   ///< 0 for a 2D texture, else the 3D texture's slices
  int layers = 0;  ///< 0: not an array, else the array's layer count
  /// 4 floats per texel, width * height * max(depth, 1) * max(layers, 1) texels in the order above.
  std::vector<float> rgba;
};

/// The KTX2 file's bytes. Throws prt::Error if a size is < 1 (depth, layers: < 0), both depth and
/// layers are set (a 3D array), or rgba has the wrong length.
std::string write_ktx2_rgba16f(const Ktx2Image& image);

/// Parses a file that write_ktx2_rgba16f wrote (identifier, format, DFD, one level, one face, no
/// supercompression, level size), throwing prt::Error("<name>: <problem>") otherwise.
Ktx2Image read_ktx2_rgba16f(const std::string& bytes, const std::string& name);

}  // namespace prt::transfer
