#pragma once
// `prt bake MESH --lightmap WxH`: the texel (lightmap) variant of prt bake (src/lightmap).
#include <string>

#include "bake/bake.h"

namespace prt::cli {

struct LightmapBakeRequest {
  std::string mesh_path, output, gltf_output;
  std::string size;  ///< "WxH" or "SIZE"
  int gutter = 2;
  bool repair = true;
  bool float16 = false;
  bool quiet = false;
  int clusters = 0, pca = 0;  ///< > 0: compress with CPCA (prt compress, no lighting) and write a .cprt
  int threads = 0;
  std::string canonical_options;  ///< the bake options as text, compared across the ranks of an MPI job
};

/// Checks everything (options, outputs, the mesh's UVs, memory), bakes and writes the texel .prt (or,
/// with clusters > 0, its CPCA .cprt as `prt compress` without lighting writes it, seeded by the bake's
/// seed) atomically, and prints the one-line summary unless quiet. Under mpirun the ranks check that they
/// read the same mesh and options, split the texels, and rank 0 alone writes (docs/distributed.md).
void run_bake_lightmap(const bake::BakeOptions& options, const LightmapBakeRequest& request);

}  // namespace prt::cli
