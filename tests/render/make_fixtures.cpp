// Writes the renderer's test inputs into a folder (used by the viewer smoke test scripts): those of
// render_fixtures.h, and room.gltf, the mixed scene of tests/lightmap/mixed_scenes.h (a floor and a wall
// with lightmap UVs, a box on the floor; nodes "Floor", "Box", "Wall").
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "lightmap/mixed_scenes.h"  // tests/lightmap
#include "render_fixtures.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_render_fixtures FOLDER\n");
    return 2;
  }
  try {
    prt::render_test::write_fixture_files(argv[1]);
    std::vector<prt::test::NamedPart> parts;
    const prt::mesh::Mesh room = prt::test::room_with_box(true, parts);
    prt::test::write_gltf_parts(std::string(argv[1]) + "/room.gltf", room, parts);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "make_render_fixtures: %s\n", e.what());
    return 1;
  }
  return 0;
}
