#include "gpu/gl/shader_program.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "gpu/gl/shader_sources.h"

namespace trispline::gpu {
namespace {

std::string defines_text(const ShaderDefines& defines) {
  std::string s;
  for (const auto& [name, value] : defines) s += (s.empty() ? "" : " ") + name + (value.empty() ? "" : "=" + value);
  return s;
}

// A shader's or a program's info log (`get_iv` / `get_log`: glGetShaderiv and glGetShaderInfoLog, or the program's).
std::string info_log(GLuint id, void (*get_iv)(GLuint, GLenum, GLint*),
                     void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint len = 0;
  get_iv(id, GL_INFO_LOG_LENGTH, &len);
  std::string log(std::size_t(std::max(len, 1)), '\0');
  get_log(id, len, nullptr, log.data());
  log.resize(std::string(log.c_str()).size());
  return log;
}

std::string shader_log(GLuint shader) { return info_log(shader, glGetShaderiv, glGetShaderInfoLog); }
std::string program_log(GLuint program) { return info_log(program, glGetProgramiv, glGetProgramInfoLog); }

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

namespace {

// `name` from a line `#include "name"` (leading blanks allowed); empty if the line is no include directive.
// Throws ShaderError for `#include` without a quoted name.
std::string include_target(std::string_view line, std::string_view file, int line_no) {
  const std::size_t p = line.find_first_not_of(" \t");
  if (p == std::string_view::npos || line.substr(p, 8) != "#include") return {};
  const std::size_t a = line.find('"', p + 8);
  const std::size_t b = a == std::string_view::npos ? a : line.find('"', a + 1);
  if (b == std::string_view::npos || b == a + 1)
    throw ShaderError("gpu/shaders/" + std::string(file) + ":" + std::to_string(line_no) +
                      ": malformed #include (expected #include \"name.glsl\")");
  return std::string(line.substr(a + 1, b - a - 1));
}

void expand_into(std::string& out, std::string_view source, std::string_view file, int source_number,
                 std::vector<std::string>& included, int depth) {
  if (depth > 8) throw ShaderError("gpu/shaders/" + std::string(file) + ": #include nested deeper than 8");
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < source.size()) {
    const std::size_t eol = source.find('\n', pos);
    const std::string_view line = source.substr(pos, eol == std::string_view::npos ? eol : eol - pos);
    pos = eol == std::string_view::npos ? source.size() : eol + 1;
    ++line_no;
    const std::string target = include_target(line, file, line_no);
    if (target.empty()) {
      out += line;
      out += '\n';
      continue;
    }
    std::string_view text;
    try {
      text = shader_source(target);
    } catch (const std::out_of_range& e) {
      throw ShaderError("gpu/shaders/" + std::string(file) + ":" + std::to_string(line_no) + ": " + e.what());
    }
    if (text.rfind("#version", 0) != 0)
      throw ShaderError("gpu/shaders/" + target + ": first line must be a #version directive");
    included.push_back(target);
    const int number = int(included.size());
    const std::size_t body = text.find('\n');
    out += "#line 2 " + std::to_string(number) + "\n";
    if (body != std::string_view::npos) expand_into(out, text.substr(body + 1), target, number, included, depth + 1);
    out += "#line " + std::to_string(line_no + 1) + " " + std::to_string(source_number) + "\n";
  }
}

std::string source_numbers_text(const std::vector<std::string>& included) {
  std::string s;
  for (std::size_t i = 0; i < included.size(); ++i)
    s += "\n(source string " + std::to_string(i + 1) + " = gpu/shaders/" + included[i] + ")";
  return s;
}

}  // namespace

std::string expand_includes(std::string_view source, std::string_view file, std::vector<std::string>* included) {
  std::vector<std::string> names;
  std::string out;
  out.reserve(source.size());
  expand_into(out, source, file, 0, names, 0);
  if (!source.empty() && source.back() != '\n') out.pop_back();  // keep the original ending
  if (included) *included = std::move(names);
  return out;
}

bool is_shader_stage_file(std::string_view file) {
  return ends_with(file, ".vert.glsl") || ends_with(file, ".frag.glsl") || ends_with(file, ".geom.glsl") ||
         ends_with(file, ".comp.glsl");
}

GLenum shader_stage_from_name(std::string_view file) {
  if (ends_with(file, ".vert.glsl")) return GL_VERTEX_SHADER;
  if (ends_with(file, ".frag.glsl")) return GL_FRAGMENT_SHADER;
  if (ends_with(file, ".geom.glsl")) return GL_GEOMETRY_SHADER;
  if (ends_with(file, ".comp.glsl")) return GL_COMPUTE_SHADER;
  throw ShaderError("gpu/shaders/" + std::string(file) + ": unknown stage (expected *.vert|frag|geom|comp.glsl)");
}

ShaderProgram::ShaderProgram(const std::vector<std::string_view>& files, const ShaderDefines& defines,
                             const std::vector<std::string>& feedback_varyings) {
  for (std::string_view f : files) label_ += (label_.empty() ? "" : "+") + std::string(f);
  if (!defines.empty()) label_ += " [" + defines_text(defines) + "]";
  if (!feedback_varyings.empty()) label_ += " (transform feedback)";

  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (std::string_view f : files) {
    const GLenum stage = shader_stage_from_name(f);
    std::vector<std::string> included;
    const std::string text = specialise_source(expand_includes(shader_source(f), f, &included), defines, f);
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
                        (defines.empty() ? "" : " [" + defines_text(defines) + "]") + ":\n" + log +
                        source_numbers_text(included));
    }
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  if (!feedback_varyings.empty()) {
    std::vector<const char*> names;
    for (const std::string& v : feedback_varyings) names.push_back(v.c_str());
    glTransformFeedbackVaryings(id_, GLsizei(names.size()), names.data(), GL_SEPARATE_ATTRIBS);
  }
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
