#include "render/shader_program.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

#include "core/atomic_file.h"
#include "core/error.h"

namespace prt::render {

// Defined in the generated embedded_shaders.cpp (see embed_shaders.cmake).
struct EmbeddedShader {
  const char* name;
  const char* text;
};
extern const EmbeddedShader kEmbeddedShaders[];
extern const int kEmbeddedShaderCount;

namespace {

std::string first_log_line(const std::string& log) {
  std::size_t start = log.find_first_not_of(" \t\r\n");
  if (start == std::string::npos) return "(no log)";
  std::size_t end = log.find_first_of("\r\n", start);
  std::string line = log.substr(start, end == std::string::npos ? std::string::npos : end - start);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.pop_back();
  return line;
}

GLenum stage_of(const std::string& name) {
  const std::string extension = std::filesystem::path(name).extension().string();
  if (extension == ".vert") return GL_VERTEX_SHADER;
  if (extension == ".frag") return GL_FRAGMENT_SHADER;
  if (extension == ".comp") return GL_COMPUTE_SHADER;
  fail("shaders/" + name + ": unknown shader stage (expected .vert, .frag or .comp)");
}

// The source with `defines` after its #version line (and a #line directive restoring the numbering).
std::string with_defines(const std::string& text, const std::string& defines) {
  if (defines.empty()) return text;
  const std::size_t version = text.find("#version");
  if (version == std::string::npos) return text;
  const std::size_t end_of_line = text.find('\n', version);
  if (end_of_line == std::string::npos) return text;
  std::size_t next_line = 1;  // 1-based number of the line after #version
  for (std::size_t i = 0; i <= end_of_line; ++i) next_line += text[i] == '\n';
  return text.substr(0, end_of_line + 1) + defines + "#line " + std::to_string(next_line) + "\n" +
         text.substr(end_of_line + 1);
}

// The source with each line `#include "<name>"` replaced by shaders/<name> (itself with its includes,
// nested at most kMaxIncludeDepth deep: sun_light.glsl includes sun_pcss.glsl), followed by a #line
// directive restoring the numbering.
constexpr int kMaxIncludeDepth = 4;
std::string with_includes(const std::string& text, int depth = 0) {
  const std::string directive = "#include \"";
  if (text.find(directive) == std::string::npos) return text;
  std::string out;
  std::size_t line_number = 1, start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    const std::size_t close = line.rfind('"');
    if (line.compare(0, directive.size(), directive) == 0 && close > directive.size()) {
      const std::string name = line.substr(directive.size(), close - directive.size());
      if (depth >= kMaxIncludeDepth) fail("shaders/" + name + ": includes nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
      out += with_includes(shader_source(name).text, depth + 1);
      out += "\n#line " + std::to_string(line_number + 1) + "\n";
    } else {
      out += line + "\n";
    }
    start = end + 1;
    ++line_number;
  }
  return out;
}

// The info log of a shader (glGetShaderiv, glGetShaderInfoLog) or a program (the glGetProgram pair).
template <typename GetIv, typename GetLog>
std::string info_log(GLuint id, GetIv get_iv, GetLog get_log) {
  GLint length = 0;
  get_iv(id, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  get_log(id, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log;
}

GLuint compile(const std::string& name, const std::string& defines) {
  const ShaderSource source = shader_source(name);
  GLuint shader = glCreateShader(stage_of(name));
  const std::string full_text = with_defines(with_includes(source.text), defines);
  const char* text = full_text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    fail_file(source.origin, "GLSL compile error: " + first_log_line(log));
  }
  return shader;
}

}  // namespace

ShaderSource shader_source(const std::string& name) {
  const char* folder = std::getenv("PRT_SHADER_DIR");
  if (folder != nullptr && folder[0] != '\0') {
    const std::string path = (std::filesystem::path(folder) / name).string();
    return {path, read_file(path)};
  }
  for (int i = 0; i < kEmbeddedShaderCount; ++i)
    if (name == kEmbeddedShaders[i].name) return {"shaders/" + name + " (embedded)", kEmbeddedShaders[i].text};
  fail("shaders/" + name + ": no such embedded shader");
}

std::vector<std::string> embedded_shader_names() {
  std::vector<std::string> names;
  for (int i = 0; i < kEmbeddedShaderCount; ++i) names.emplace_back(kEmbeddedShaders[i].name);
  return names;
}

Program::Program(const std::vector<std::string>& stage_names, const std::string& defines) {
  std::vector<GLuint> shaders;
  std::string origins;
  try {
    for (const std::string& name : stage_names) {
      shaders.push_back(compile(name, defines));
      origins += (origins.empty() ? "shaders/" : "+") + name;
    }
  } catch (...) {
    for (GLuint shader : shaders) glDeleteShader(shader);
    throw;
  }
  id_ = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(id_, shader);
  glLinkProgram(id_);
  for (GLuint shader : shaders) {
    glDetachShader(id_, shader);
    glDeleteShader(shader);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(id_, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(id_);
    id_ = 0;
    fail_file(origins, "GLSL link error: " + first_log_line(log));
  }
}

Program::~Program() {
  if (id_ != 0) glDeleteProgram(id_);
}

Program::Program(Program&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

GLint Program::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

}  // namespace prt::render
