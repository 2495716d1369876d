// Writes a texel transfer and its lightmap glTF for tests/engines/test_lightmap_gltf.mjs, independently
// of the baker: a mesh of two charts (a floor quad and a wall quad sharing an edge whose vertices get
// different UVs on each side, so the writer must split them) and synthetic texel blocks.
// Usage: lightmap_glb_fixture OUT_DIR  -> OUT_DIR/{lightmap.prt, lightmap.glb, lightmap_grey.prt, lightmap_grey.glb}, and the
// mesh as OUT_DIR/scene.obj (with vt) for `prt bake --lightmap --gltf`.
#include <cmath>
#include <cstdio>
#include <string>

#include "pipeline/transfer_outputs.h"
#include "core/error.h"
#include "mesh/mesh.h"
#include "lightmap/lightmap_scenes.h"  // tests/lightmap
#include "support/texel_transfer.h"
#include "transfer/transfer_file.h"

using namespace prt;

namespace {

mesh::Mesh two_charts() {
  mesh::Mesh m;
  m.positions = {{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, {1, 1, -1}, {-1, 1, -1}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3, 3, 2, 4, 3, 4, 5};
  // Floor on the left half of the lightmap, wall on the right: vertices 2 and 3 have two UVs each.
  m.lightmap_uv = {{0.05f, 0.95f}, {0.45f, 0.95f}, {0.45f, 0.05f}, {0.05f, 0.95f}, {0.45f, 0.05f}, {0.05f, 0.05f},
                   {0.55f, 0.95f}, {0.95f, 0.95f}, {0.95f, 0.05f}, {0.55f, 0.95f}, {0.95f, 0.05f}, {0.55f, 0.05f}};
  return m;
}

transfer::TransferData synthetic(const mesh::Mesh& mesh, int width, int height, int bands, int channels, bool bounce) {
  transfer::TransferData t = test::empty_texel_transfer(mesh, width, height, bands, channels, bounce);
  const std::size_t per = t.header.values_per_vertex();
  for (int j = 1; j + 1 < height; ++j)
    for (int i = 1; i + 1 < width; ++i) {
      const std::size_t b = static_cast<std::size_t>(j) * width + i;
      t.coverage[b] = (i == 1 || j == 1 || i + 2 == width || j + 2 == height) ? transfer::kTexelGutter : transfer::kTexelCovered;
      for (std::size_t k = 0; k < per; ++k) {
        // Values over several binades, signs mixed, some tiny (float16 subnormals).
        const double x = std::sin(0.37 * i + 1.3 * j + 0.71 * static_cast<double>(k)) * std::pow(10.0, static_cast<double>(k % 5) - 3.0);
        t.values[b * per + k] = static_cast<float>(x);
        if (bounce) t.bounce_only[b * per + k] = static_cast<float>(0.25 * x);
      }
    }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lightmap_glb_fixture OUT_DIR\n");
    return 2;
  }
  try {
    const std::string dir = argv[1];
    mesh::Mesh mesh = two_charts();
    test::write_obj_with_uv(dir + "/scene.obj", mesh);
    mesh = mesh::load_mesh(dir + "/scene.obj", nullptr, true);  // as prt loads it (its fingerprints)
    const transfer::TransferData rgb = synthetic(mesh, 37, 23, 3, 3, true);  // 27 values: 7 layers, the last padded
    transfer::write_transfer(dir + "/lightmap.prt", rgb);
    pipeline::write_lightmap_glb(dir + "/lightmap.glb", mesh, rgb);
    const transfer::TransferData grey = synthetic(mesh, 16, 16, 4, 1, false);  // 16 values: 4 layers, none padded
    transfer::write_transfer(dir + "/lightmap_grey.prt", grey);
    pipeline::write_lightmap_glb(dir + "/lightmap_grey.glb", mesh, grey);
  } catch (const Error& e) {
    std::fprintf(stderr, "prt: %s\n", e.what());
    return 1;
  }
  return 0;
}
