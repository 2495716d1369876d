#pragma once
// GLSL sources and programs.
//
// SHADER SOURCES: the files in shaders/ (named <pass>.<stage>) are embedded in the binary at build time
// (CMake turns them into a generated C++ file), so `prt` is self-contained. If the environment variable
// PRT_SHADER_DIR is set, every shader is read from that folder instead, at program creation, so shaders
// can be edited without rebuilding (e.g. PRT_SHADER_DIR=shaders prt view ...).
#include <string>
#include <vector>

#include "render/gl.h"

namespace prt::render {

/// One shader source: where it came from (a path under PRT_SHADER_DIR, or "shaders/<name> (embedded)")
/// and its text.
struct ShaderSource {
  std::string origin;
  std::string text;
};

/// The source of shaders/<name>, from PRT_SHADER_DIR if set, else embedded. Throws
/// prt::Error("<path>: <problem>") if PRT_SHADER_DIR is set and the file cannot be read, or
/// prt::Error if no shader of that name was embedded.
ShaderSource shader_source(const std::string& name);

/// Names of the embedded shaders (for tests and `PRT_SHADER_DIR` checks).
std::vector<std::string> embedded_shader_names();

/// A linked GLSL program. Move-only; deletes the program when destroyed.
class Program {
 public:
  Program() = default;
  /// Compiles each stage (names under shaders/; the stage follows the extension: .vert, .frag, .comp)
  /// and links them. `defines` (e.g. "#define CHANNELS 3\n") is inserted after each source's #version
  /// line, followed by a #line directive so that log line numbers still match the file. Throws
  /// prt::Error("<origin>: GLSL compile error: <first line of the log>") or ("<origins>: GLSL link
  /// error: ...").
  explicit Program(const std::vector<std::string>& stage_names, const std::string& defines = "");
  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  /// Location of a uniform (-1 if the linker removed it, which GL ignores on upload).
  GLint uniform(const char* name) const;

 private:
  GLuint id_ = 0;
};

}  // namespace prt::render
