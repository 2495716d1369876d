#pragma once
// A texel (lightmap) transfer for a mesh, built in code for tests that need one without the baker.
#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::test {

/// The header of a width x height texel transfer of `mesh` (its vertex and triangle counts, mesh and
/// UV fingerprints), kind interreflected with a bounce-only section when `bounce` (else shadowed), float32;
/// values (and bounce_only) zero and every texel empty: the caller fills blocks and coverage.
transfer::TransferData empty_texel_transfer(const mesh::Mesh& mesh, int width, int height, int bands, int channels, bool bounce);

}  // namespace prt::test
