#pragma once
// Drawing a mixed scene (transfer/mixed_parts.h; docs/conventions.md "Mixed scenes"): a texel
// transfer file for some parts and a per-vertex file for the others, baked together. The frame is
// drawn once with each transfer (the same mesh, camera and lighting, so the same pixels, depths and
// triangle ids), and each covered pixel keeps the frame of its triangle's kind: the lightmap pass for
// texel triangles, the per-vertex pass for per-vertex ones. Background pixels are the same in both.
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/renderer.h"
#include "render/scene_inputs.h"

namespace prt::render {

/// The transfer files to load for `path`: {path} for a file of one kind; for a .prt of a mixed pair,
/// the texel file then the per-vertex file (whichever of them `path` is). Throws prt::Error naming the
/// file for a malformed "mixed" entry or a partner that cannot be read.
std::vector<std::string> mixed_transfer_paths(const std::string& path);

/// Per triangle, 1 where a mixed scene draws the per-vertex transfer: from the "mixed" entry of
/// scene.transfers[0] (loaded from mixed_transfer_paths). Throws prt::Error naming the file if the two
/// files' entries or kinds do not make a pair (texel then vertex, the same per-vertex triangles).
std::vector<std::uint8_t> mixed_vertex_triangles(const SceneInputs& scene);

/// Overwrites the pixels of `frame` whose triangle id (`ids`, row-major as the image, kNoTriangle for
/// background) `vertex_triangle` marks with those of `vertex_frame` (same size, same channels).
void composite_mixed(image::Image& frame, const image::Image& vertex_frame, const std::vector<std::uint32_t>& ids,
                     const std::vector<std::uint8_t>& vertex_triangle);

/// Renders `settings` with transfer `texel` and with transfer `vertex` and composites them as above;
/// returns the radiance (Renderer::read_radiance's layout). The renderer is left holding the second frame.
image::Image render_mixed(Renderer& renderer, FrameSettings settings, int texel, int vertex,
                          const std::vector<std::uint8_t>& vertex_triangle, int width, int height);

}  // namespace prt::render
