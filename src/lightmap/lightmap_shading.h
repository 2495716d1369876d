#pragma once
// The lit lightmap on the CPU (`prt shade --lightmap`): a plain baked lightmap for static lighting,
// and the reference that GPU lightmap rendering is checked against.
//
// Per covered texel, at its sample point (texel_bake.h, texel_samples: recomputed from the mesh and
// the file's parameters), the split lighting of shade/scene_shading.h:
//   L_o = T . L_sky + T_bounce . L_discs + direct(discs)
// where direct(discs) is the disc's exact direct light with Embree shadow rays from the sample point
// (none for unshadowed transfer), as `prt shade` computes it per vertex. Gutter texels then get the
// gutter rule's dilation of the lit values (gutter.h), empty texels 0.
#include <string>
#include <vector>

#include "image/image.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "shade/disc_direct.h"
#include "shade/scene_shading.h"
#include "transfer/transfer_file.h"

namespace prt::lightmap {

/// The lit lightmap: width x height RGB, linear radiance, rows from the top (row 0 = v near 0).
/// `transfer` must be a texel file baked for `mesh` (checked: mesh and UV fingerprints); `origin`
/// names it in errors.
image::Image shade_lightmap(const mesh::Mesh& mesh, const transfer::TransferData& transfer, const light::SceneLighting& lighting,
                            const std::string& origin, const shade::DiscShadingOptions& options = {},
                            shade::SplitReport* report = nullptr);

}  // namespace prt::lightmap
