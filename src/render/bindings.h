#pragma once
// Internal to the renderer: the limits and buffer binding points that several passes and their shaders
// share (the GLSL declares the same numbers in its layout(binding = N) qualifiers).
#include "render/gl.h"
#include "sh/basis.h"

namespace prt::render {

/// Capacity, in SH coefficients, of every lighting buffer: the largest band count prt supports, squared.
inline constexpr int kMaxCoefficients = sh::kMaxBands * sh::kMaxBands;

/// Shader-storage bindings of the mesh as the per-pixel and compute shaders read it: triangle indices
/// (uint, 3 per triangle), positions and normals (vec4 per vertex, w unused).
inline constexpr GLuint kIndicesBinding = 3;
inline constexpr GLuint kPositionsBinding = 4;
inline constexpr GLuint kNormalsBinding = 5;

}  // namespace prt::render
