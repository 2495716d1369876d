#pragma once
// Texel (lightmap) transfer on the GPU (renderer.h, PASSES: prt_lightmap). Internal to the renderer
// (renderer.cpp, renderer_lightmap.cpp).
//
// A texel transfer file (transfer_file.h, is_texel()) holds one block of channels x bands^2 values per
// texel of a W x H grid over the mesh's lightmap UVs. It is uploaded once as texture arrays, W x H texels
// per layer, four values per texel and layer: layer k holds values 4k .. 4k+3 of each texel's block
// (channel-major, then SH index, as in the file) in r, g, b, a, the last layer zero-padded; so
// ceil(channels bands^2 / 4) layers (19 for 5-band RGB). Internal format RGBA32F, or RGBA16F when the
// file's payload is float16 (exact: its values are halves already). Texel rows go up in file order,
// row 0 (v = 0) at t = 0, so the UV samples the array as it is (docs/conventions.md, "Lightmap
// texels"). Filtering: trilinear (GL_LINEAR_MIPMAP_LINEAR), clamped to the edge, over a full mip chain
// computed on the CPU from the coverage mask (lightmap_mips.h: each level averages only filled texels
// and is dilated by one texel, so a distant chart keeps its own values at its rim; the bake's gutters
// do the same for bilinear reads at level 0). A version-4 (interreflected) file's bounce-only section
// gets a second array of the same shape, which the discs' SH is applied to (formats.md, "Bounce-only
// section").
//
// Per frame the fragment shader (prt_lightmap.frag) samples every layer at the pixel's interpolated
// lightmap UV and takes, per channel, the dot product of the first k^2 filtered coefficients with the
// object-frame lighting (as the diffuse pass does per vertex); with discs it adds the bounce-only
// layers dotted with the discs' SH and each disc's direct light per pixel (sun_light.glsl), and clamps
// at 0 as prt::shade's split shading does. At a texel centre, where bilinear filtering returns the
// texel's own block, that is prt::shade::shade_diffuse of the texel's block.
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "render/frame_core.h"
#include "render/gl.h"
#include "render/renderer.h"
#include "render/shader_program.h"
#include "transfer/transfer_file.h"

namespace prt::render {

/// One texel transfer's texture arrays.
class LightmapTextures {
 public:
  /// Uploads `transfer` (a texel file's data: values, and bounce_only when present). Throws
  /// prt::Error("<origin>: ...") if it is not a diffuse texel transfer, its value count does not match
  /// its header, or the arrays exceed this OpenGL's texture size or layer limits.
  LightmapTextures(const transfer::TransferData& transfer, const std::string& origin);
  ~LightmapTextures();
  LightmapTextures(const LightmapTextures&) = delete;
  LightmapTextures& operator=(const LightmapTextures&) = delete;

  const transfer::Header& header() const { return header_; }
  int layers() const { return layers_; }
  GLuint transfer_texture() const { return transfer_; }
  GLuint bounce_texture() const { return bounce_; }  ///< 0 when the file has no bounce-only section
  /// Bytes on the GPU (both arrays, with their mip chains).
  std::size_t gpu_bytes() const { return bytes_; }

 private:
  GLuint upload(const std::vector<float>& values, const std::vector<std::uint8_t>& coverage, GLenum internal_format);
  transfer::Header header_;
  int layers_ = 0;
  GLuint transfer_ = 0, bounce_ = 0;
  std::size_t bytes_ = 0;
};

/// For the viewer's transfer list: ", lightmap 512x512, 100.7 MB" (both arrays and mip chains on the GPU).
std::string lightmap_memory_label(const transfer::Header& header);

/// What every lightmap pass's draw (prt_lightmap.vert) starts with: the depth test (off in texel space:
/// charts do not overlap), `program` in use with the camera's matrix, the empty vertex array, and the
/// mesh's indices, positions, normals and lightmap UVs bound as the vertex stage reads them.
void begin_lightmap_draw(FrameCore& core, const Program& program, bool texel_space);

/// Layers a texel block of `values_per_texel` values takes: ceil(values_per_texel / 4).
int lightmap_layers(std::uint64_t values_per_texel);


}  // namespace prt::render
