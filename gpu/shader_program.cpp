#include "gpu/shader_program.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "gpu/shader_sources.h"

namespace trispline::gpu {
namespace {

std::string defines_text(const ShaderDefines& defines) {
  std::string s;
  for (const auto& [name, value] : defines) s += (s.empty() ? "" : " ") + name + (value.empty() ? "" : "=" + value);
  return s;
}

std::string shader_log(GLuint shader) {
  GLint len = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
  std::string log(std::size_t(std::max(len, 1)), '\0');
  glGetShaderInfoLog(shader, len, nullptr, log.data());
  log.resize(std::string(log.c_str()).size());
  return log;
}

std::string program_log(GLuint program) {
  GLint len = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
  std::string log(std::size_t(std::max(len, 1)), '\0');
  glGetProgramInfoLog(program, len, nullptr, log.data());
  log.resize(std::string(log.c_str()).size());
  return log;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

std::string specialise_source(std::string_view source, const ShaderDefines& defines, std::string_view file) {
  // The #version directive must be the first line (comments/blank lines before it are allowed by GLSL, but we
  // keep the files simple: line 1).
  const std::size_t eol = source.find('\n');
  const std::string_view first = source.substr(0, eol);
  if (first.rfind("#version", 0) != 0)
    throw ShaderError("gpu/shaders/" + std::string(file) + ": first line must be a #version directive");
  std::string out(first);
  out += '\n';
  for (const auto& [name, value] : defines) out += "#define " + name + (value.empty() ? "" : " " + value) + "\n";
  out += "#line 2\n";
  if (eol != std::string_view::npos) out += source.substr(eol + 1);
  return out;
}

GLenum shader_stage_from_name(std::string_view file) {
  if (ends_with(file, ".vert.glsl")) return GL_VERTEX_SHADER;
  if (ends_with(file, ".frag.glsl")) return GL_FRAGMENT_SHADER;
  if (ends_with(file, ".geom.glsl")) return GL_GEOMETRY_SHADER;
  if (ends_with(file, ".comp.glsl")) return GL_COMPUTE_SHADER;
  throw ShaderError("gpu/shaders/" + std::string(file) + ": unknown stage (expected *.vert|frag|geom|comp.glsl)");
}

ShaderProgram::ShaderProgram(const std::vector<std::string_view>& files, const ShaderDefines& defines) {
  for (std::string_view f : files) label_ += (label_.empty() ? "" : "+") + std::string(f);
  if (!defines.empty()) label_ += " [" + defines_text(defines) + "]";

  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (std::string_view f : files) {
    const GLenum stage = shader_stage_from_name(f);
    const std::string text = specialise_source(shader_source(f), defines, f);
    const GLuint s = glCreateShader(stage);
    shaders.push_back(s);
    const char* ptr = text.c_str();
    glShaderSource(s, 1, &ptr, nullptr);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string log = shader_log(s);
      cleanup();
      throw ShaderError("GLSL compile error in gpu/shaders/" + std::string(f) +
                        (defines.empty() ? "" : " [" + defines_text(defines) + "]") + ":\n" + log);
    }
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  glLinkProgram(id_);
  for (GLuint s : shaders) glDetachShader(id_, s);
  cleanup();
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = program_log(id_);
    glDeleteProgram(id_);
    id_ = 0;
    throw ShaderError("GLSL link error in " + label_ + ":\n" + log);
  }
  glObjectLabel(GL_PROGRAM, id_, GLsizei(label_.size()), label_.c_str());
}

ShaderProgram::~ShaderProgram() {
  if (id_) glDeleteProgram(id_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& o) noexcept
    : id_(std::exchange(o.id_, 0)), label_(std::move(o.label_)), uniforms_(std::move(o.uniforms_)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
    label_ = std::move(o.label_);
    uniforms_ = std::move(o.uniforms_);
  }
  return *this;
}

GLint ShaderProgram::uniform(const std::string& name) const {
  auto it = uniforms_.find(name);
  if (it != uniforms_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id_, name.c_str());
  uniforms_.emplace(name, loc);
  return loc;
}

void ShaderProgram::set(const std::string& name, const glm::mat3& m) const {
  glUniformMatrix3fv(uniform(name), 1, GL_FALSE, glm::value_ptr(m));
}

void ShaderProgram::set(const std::string& name, const glm::mat4& m) const {
  glUniformMatrix4fv(uniform(name), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace trispline::gpu
