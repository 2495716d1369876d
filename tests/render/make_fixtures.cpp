// Writes the renderer's test inputs into a folder (used by the viewer smoke test script).
#include <cstdio>

#include "core/error.h"
#include "render_fixtures.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_render_fixtures FOLDER\n");
    return 2;
  }
  try {
    prt::render_test::write_fixture_files(argv[1]);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "make_render_fixtures: %s\n", e.what());
    return 1;
  }
  return 0;
}
