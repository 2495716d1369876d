// Runs of mesh triangles (triangle_runs.h).
#include "render/triangle_runs.h"

namespace prt::render {

TriangleRuns complement_runs(const TriangleRuns& runs, std::uint64_t triangle_count) {
  TriangleRuns out;
  std::uint64_t next = 0;
  for (const auto& [first, count] : runs) {
    if (first > next) out.emplace_back(next, first - next);
    next = first + count;
  }
  if (next < triangle_count) out.emplace_back(next, triangle_count - next);
  return out;
}

void draw_indexed_runs(const Program& program, const TriangleRuns* runs, std::uint64_t triangle_count) {
  draw_runs(program, runs, triangle_count, [](std::uint64_t first, std::uint64_t count) {
    const auto offset = static_cast<std::uintptr_t>(3 * first * sizeof(std::uint32_t));
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * count), GL_UNSIGNED_INT, reinterpret_cast<const void*>(offset));
  });
}

}  // namespace prt::render
