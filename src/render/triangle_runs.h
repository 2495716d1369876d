#pragma once
// Internal to the renderer: runs of mesh triangles, the share of a frame one pass draws (a mixed scene,
// pass_mixed.cpp), and drawing them so that the triangle-id attachment keeps mesh triangle indices.
#include <cstdint>
#include <utility>
#include <vector>

#include "render/gl.h"
#include "render/shader_program.h"

namespace prt::render {

/// Runs [first, first + count) of mesh triangle indices, increasing and disjoint: the share of a frame
/// one pass draws (pass_mixed.cpp; transfer/mixed_parts.h writes them).
using TriangleRuns = std::vector<std::pair<std::uint64_t, std::uint64_t>>;

/// The triangles of [0, triangle_count) that `runs` leaves out, as runs. Precondition: `runs` increasing,
/// disjoint, inside [0, triangle_count).
TriangleRuns complement_runs(const TriangleRuns& runs, std::uint64_t triangle_count);

/// Draws the triangles of `runs`, or all `triangle_count` of them when `runs` is null, with `program`
/// in use: one draw(first, count) per run (count > 0), after setting the program's uniform
/// first_triangle to `first` (surface.frag and prt_lightmap.frag add it to gl_PrimitiveID, which counts
/// from 0 in every draw, so the triangle-id attachment keeps mesh triangle indices; 0 for a whole draw).
template <class Draw>
void draw_runs(const Program& program, const TriangleRuns* runs, std::uint64_t triangle_count, Draw draw) {
  const GLint location = program.uniform("first_triangle");
  if (runs == nullptr) {
    glUniform1ui(location, 0u);
    draw(std::uint64_t{0}, triangle_count);
    return;
  }
  for (const auto& [first, count] : *runs) {
    if (count == 0) continue;
    glUniform1ui(location, static_cast<GLuint>(first));
    draw(first, count);
  }
}

/// draw_runs with glDrawElements over the bound vertex array's index buffer, which holds three
/// GL_UNSIGNED_INT indices per mesh triangle in triangle order.
void draw_indexed_runs(const Program& program, const TriangleRuns* runs, std::uint64_t triangle_count);

}  // namespace prt::render
