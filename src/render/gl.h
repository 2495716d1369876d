#pragma once
// The one place the renderer includes OpenGL. Core-profile declarations only (<GL/glcorearb.h>), with
// prototypes: libOpenGL (GLVND) exports every entry point up to GL 4.5, so no loader is needed.
// Only files in src/render include this header.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace prt::render {

/// The OpenGL version every renderer context is created with (4.5 core: the newest Mesa's llvmpipe has).
inline constexpr int kGlMajor = 4;
inline constexpr int kGlMinor = 5;

/// GL_RENDERER and GL_VERSION of the current context, as "<renderer>, OpenGL <version>".
std::string describe_current_context();

/// Throws prt::Error("<what>: OpenGL error 0x...") if glGetError reports an error (draining all flags).
void check_gl(const char* what);

/// Deletes the buffer (texture) if it is not 0 and sets the name to 0.
void delete_buffer(GLuint& buffer);
void delete_texture(GLuint& texture);

}  // namespace prt::render
