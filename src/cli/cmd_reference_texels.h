#pragma once
// `prt reference --texels LIGHTMAP.prt`: the path-traced reference at a lightmap's texel sample points.
#include <string>

#include "mesh/mesh.h"
#include "reference/environment_sampler.h"
#include "reference/reference.h"

namespace prt::cli {

/// Recomputes the sample points of the texel file `texels_path` (baked for `mesh`: fingerprints
/// checked) exactly as the baker placed them (lightmap::texel_samples with the file's size, repair
/// flag and seed), path-traces the outgoing radiance there (reference::point_radiance) and writes
/// `output` (.exr): width x height linear RGB, covered texels only (others 0; no gutter).
void run_reference_texels(const mesh::Mesh& mesh, const std::string& mesh_path, const reference::EnvironmentSampler& sampler,
                          const reference::ReferenceOptions& options, const std::string& texels_path, const std::string& output,
                          bool quiet);

}  // namespace prt::cli
