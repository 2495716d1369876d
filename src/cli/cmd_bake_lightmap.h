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
  std::string canonical_options;  ///< the bake options as text, compared across the ranks of an MPI job
};

/// Checks everything (options, outputs, the mesh's UVs, memory), bakes and writes the texel .prt
/// atomically, and prints the one-line summary unless quiet. Under mpirun the ranks check that they
/// read the same mesh and options, split the texels, and rank 0 alone writes (docs/distributed.md).
void run_bake_lightmap(const bake::BakeOptions& options, const LightmapBakeRequest& request);

}  // namespace prt::cli
