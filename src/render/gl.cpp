#include "render/gl.h"

#include <cstdio>

#include "core/error.h"

namespace prt::render {

std::string describe_current_context() {
  auto text = [](GLenum name) {
    const GLubyte* value = glGetString(name);
    return value != nullptr ? std::string(reinterpret_cast<const char*>(value)) : std::string("?");
  };
  return text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

void check_gl(const char* what) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", first);
  fail(std::string(what) + ": OpenGL error " + code);
}

void delete_buffer(GLuint& buffer) {
  if (buffer != 0) glDeleteBuffers(1, &buffer);
  buffer = 0;
}

void delete_texture(GLuint& texture) {
  if (texture != 0) glDeleteTextures(1, &texture);
  texture = 0;
}

}  // namespace prt::render
