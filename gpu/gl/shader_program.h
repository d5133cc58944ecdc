// trispline::gpu::ShaderProgram — compiles and links embedded .glsl files (gpu/shaders/, see shader_sources.h).
//
// Specialisation: a program variant is chosen by #define lines that are inserted right after the file's
// `#version` line (followed by `#line 2`, so the driver's line numbers still match the file). Code bodies are
// never assembled from C++ strings. Stage is taken from the file name: *.vert.glsl, *.frag.glsl, *.geom.glsl,
// *.comp.glsl; other embedded files (e.g. ffd_eval.glsl) are libraries, pulled in by a line
// `#include "ffd_eval.glsl"` (expanded before specialisation, so the library sees the defines; inside an `#ifdef`
// it only matters to the variants that define it). A library starts with `#version` too (dropped when included);
// its lines are reported as source string N (N = 1, 2, … in order of inclusion, named in ShaderError messages).
#pragma once

#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace trispline::gpu {

// Compile or link failure; what() names the file(s), the defines and holds the GLSL info log.
class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// #define NAME VALUE pairs (VALUE may be empty), e.g. {{"ORDER_U", "3"}, {"WITH_NORMALS", ""}}.
using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

// `source` with `#define` lines inserted after its #version line, then `#line 2`.
// Throws ShaderError if the source has no #version line (`file` names it in the message).
std::string specialise_source(std::string_view source, const ShaderDefines& defines, std::string_view file);

// Stage enum (GL_VERTEX_SHADER, ...) from a file name's suffix. Throws ShaderError for an unknown suffix.
GLenum shader_stage_from_name(std::string_view file);
// True for files with a stage suffix (shader_stage_from_name would not throw); false for include libraries.
bool is_shader_stage_file(std::string_view file);

// `source` (the text of embedded `file`) with every line `#include "name.glsl"` replaced by that embedded file
// minus its #version line, framed by `#line 2 N` / `#line L 0` so compiler messages keep file-relative line numbers.
// `included` (optional) receives the included names; source string N is included[N-1]. Nested includes are
// expanded too (depth ≤ 8). Throws ShaderError naming `file` for an unknown file or a malformed directive.
std::string expand_includes(std::string_view source, std::string_view file,
                            std::vector<std::string>* included = nullptr);

class ShaderProgram {
 public:
  ShaderProgram() = default;  // empty (id() == 0)
  // Links one program from embedded files (e.g. {"mesh.vert.glsl", "mesh.frag.glsl"} or {"ffd.comp.glsl"}),
  // each specialised with `defines`. `feedback_varyings` (optional): vertex outputs captured by transform feedback,
  // one buffer binding each (GL_SEPARATE_ATTRIBS), set before linking. Needs a current context. Throws ShaderError
  // or std::out_of_range (no such embedded file).
  ShaderProgram(const std::vector<std::string_view>& files, const ShaderDefines& defines = {},
                const std::vector<std::string>& feedback_varyings = {});
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& o) noexcept;
  ShaderProgram& operator=(ShaderProgram&& o) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  GLuint id() const { return id_; }
  const std::string& label() const { return label_; }  // "mesh.vert.glsl+mesh.frag.glsl [DEFINES]"
  void use() const { glUseProgram(id_); }
  // Uniform location (cached); -1 if the uniform is absent or optimised away (setting it is then a no-op).
  GLint uniform(const std::string& name) const;

  // Setters for the program, which must be in use.
  void set(const std::string& name, int v) const { glUniform1i(uniform(name), v); }
  void set(const std::string& name, unsigned v) const { glUniform1ui(uniform(name), v); }
  void set(const std::string& name, float v) const { glUniform1f(uniform(name), v); }
  void set(const std::string& name, const glm::vec2& v) const { glUniform2f(uniform(name), v.x, v.y); }
  void set(const std::string& name, const glm::vec3& v) const { glUniform3f(uniform(name), v.x, v.y, v.z); }
  void set(const std::string& name, const glm::vec4& v) const { glUniform4f(uniform(name), v.x, v.y, v.z, v.w); }
  void set(const std::string& name, const glm::mat3& m) const;
  void set(const std::string& name, const glm::mat4& m) const;

 private:
  GLuint id_ = 0;
  std::string label_;
  mutable std::unordered_map<std::string, GLint> uniforms_;
};

}  // namespace trispline::gpu
