// trispline::gpu::FfdLatticeBuffers — a core::FfdPackedLattice in two std430 SSBOs for the GLSL FFD evaluators
// (layout declared in gpu/shaders/ffd_eval.glsl, which must match):
//   binding 4  FfdTables:   FfdAxisHeader[3] (48 bytes each), then float tables[] (span_begin #S+1, inv_span_len
//                            #S, first_index #S as int bits, coef #S·order² per axis); header offsets index tables[].
//                            Changes rarely: re-uploaded only when its bytes differ from the last upload.
//   binding 5  FfdControls: vec4 centre (world units), vec4 linear[3] (embedding A's columns), then the control
//                            points #controls × vec4 (u fastest, relative to centre). Uploaded on every upload().
// Plus GlError and check_gl_error, the GL error → exception helper of the FFD code.
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <stdexcept>
#include <vector>

#include "core/ffd/ffd_packed.h"
#include "gpu/gl/gl_resource.h"

namespace trispline::gpu {

// An OpenGL error reported by glGetError; what() names the operation and the error (e.g. GL_INVALID_OPERATION).
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GlError "<where>: GL_INVALID_... (0x....)" if glGetError reports anything (all pending errors are read).
void check_gl_error(const char* where);

// std430 mirror of `struct FfdAxis` in ffd_eval.glsl.
struct FfdAxisHeader {
  std::int32_t order, count, periodic, uniform_spans;
  float domain_min, domain_max, inv_uniform_len;
  std::int32_t span_count;
  std::int32_t span_begin, inv_span_len, first_index, coef;  // offsets into tables[] (floats)
};
static_assert(sizeof(FfdAxisHeader) == 48, "std430 layout of FfdAxis");

class FfdLatticeBuffers {
 public:
  static constexpr GLuint kTablesBinding = 4, kControlsBinding = 5;
  // Creates the buffers (needs a current context).
  FfdLatticeBuffers();
  // Uploads `packed` (see the header comment). Throws std::invalid_argument if the control point count does not
  // match the axes' counts, GlError.
  void upload(const core::FfdPackedLattice& packed);
  // Binds both SSBOs at kTablesBinding / kControlsBinding.
  void bind() const;
  bool empty() const { return table_words_.empty(); }
  int table_uploads() const { return table_uploads_; }      // knot-table uploads so far
  int control_uploads() const { return control_uploads_; }  // control-point uploads so far
  GLuint tables_buffer() const { return tables_.id(); }
  GLuint controls_buffer() const { return controls_.id(); }

  // The tables buffer's contents for `packed` (header + tables as 32-bit words).
  static std::vector<std::uint32_t> table_words(const core::FfdPackedLattice& packed);

 private:
  Buffer tables_, controls_;
  std::vector<std::uint32_t> table_words_;  // last uploaded
  std::size_t controls_bytes_ = 0;
  int table_uploads_ = 0, control_uploads_ = 0;
};

}  // namespace trispline::gpu
