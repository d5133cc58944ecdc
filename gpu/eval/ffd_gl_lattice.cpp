// FfdLatticeBuffers: FfdPackedLattice → SSBOs 4 (knot tables, uploaded when changed) and 5 (control points).
#include "gpu/eval/ffd_gl_lattice.h"

#include <cstdio>
#include <cstring>
#include <string>

#include "core/base/enum_names.h"

namespace trispline::gpu {
namespace {

const char* gl_error_name(GLenum e) {
  return core::code_name<GLenum>(e,
                                 {{GL_INVALID_ENUM, "GL_INVALID_ENUM"},
                                  {GL_INVALID_VALUE, "GL_INVALID_VALUE"},
                                  {GL_INVALID_OPERATION, "GL_INVALID_OPERATION"},
                                  {GL_INVALID_FRAMEBUFFER_OPERATION, "GL_INVALID_FRAMEBUFFER_OPERATION"},
                                  {GL_OUT_OF_MEMORY, "GL_OUT_OF_MEMORY"},
                                  {GL_STACK_UNDERFLOW, "GL_STACK_UNDERFLOW"},
                                  {GL_STACK_OVERFLOW, "GL_STACK_OVERFLOW"}},
                                 "unknown GL error");
}

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

std::uint32_t bits(std::int32_t i) {
  std::uint32_t u;
  std::memcpy(&u, &i, sizeof u);
  return u;
}

}  // namespace

void check_gl_error(const char* where) {
  std::string errors;
  for (int n = 0; n < 16; ++n) {  // bounded: a lost context can report errors forever
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", unsigned(e));
    errors += (errors.empty() ? "" : ", ") + std::string(gl_error_name(e)) + " (" + code + ")";
  }
  if (!errors.empty()) throw GlError(std::string(where) + ": " + errors);
}

FfdLatticeBuffers::FfdLatticeBuffers() : tables_(Buffer::create()), controls_(Buffer::create()) {}

std::vector<std::uint32_t> FfdLatticeBuffers::table_words(const core::FfdPackedLattice& packed) {
  constexpr std::size_t kHeaderWords = 3 * sizeof(FfdAxisHeader) / 4;
  std::vector<std::uint32_t> tables;
  FfdAxisHeader headers[3];
  for (int a = 0; a < 3; ++a) {
    const core::FfdPackedAxis& ax = packed.axes[a];
    FfdAxisHeader& h = headers[a];
    h.order = ax.order;
    h.count = ax.count;
    h.periodic = ax.periodic ? 1 : 0;
    h.uniform_spans = ax.uniform_spans ? 1 : 0;
    h.domain_min = ax.domain_min;
    h.domain_max = ax.domain_max;
    h.inv_uniform_len = ax.inv_uniform_len;
    h.span_count = ax.span_count();
    h.span_begin = std::int32_t(tables.size());
    for (float f : ax.span_begin) tables.push_back(bits(f));
    h.inv_span_len = std::int32_t(tables.size());
    for (float f : ax.inv_span_len) tables.push_back(bits(f));
    h.first_index = std::int32_t(tables.size());
    for (int i : ax.first_index) tables.push_back(bits(std::int32_t(i)));
    h.coef = std::int32_t(tables.size());
    for (float f : ax.coef) tables.push_back(bits(f));
  }
  std::vector<std::uint32_t> words(kHeaderWords + tables.size());
  std::memcpy(words.data(), headers, sizeof headers);
  std::memcpy(words.data() + kHeaderWords, tables.data(), tables.size() * 4);
  return words;
}

void FfdLatticeBuffers::upload(const core::FfdPackedLattice& packed) {
  const std::size_t controls =
      std::size_t(packed.axes[0].count) * std::size_t(packed.axes[1].count) * std::size_t(packed.axes[2].count);
  if (packed.control_points.size() != 4 * controls)
    throw std::invalid_argument("FfdLatticeBuffers::upload: " + std::to_string(packed.control_points.size() / 4) +
                                " control points for a " + std::to_string(packed.axes[0].count) + "×" +
                                std::to_string(packed.axes[1].count) + "×" + std::to_string(packed.axes[2].count) +
                                " lattice");
  std::vector<std::uint32_t> words = table_words(packed);
  if (words != table_words_) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, tables_.id());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(words.size() * 4), words.data(), GL_STATIC_DRAW);
    table_words_ = std::move(words);
    ++table_uploads_;
  }
  // Header: centre, then the embedding's linear part A column by column (vec4 each, std430).
  float header[16] = {};
  for (int c = 0; c < 3; ++c) header[c] = float(packed.centre[c]);
  for (int col = 0; col < 3; ++col)
    for (int r = 0; r < 3; ++r) header[4 + 4 * col + r] = packed.embedding_linear[col][r];
  const std::size_t bytes = sizeof header + packed.control_points.size() * sizeof(float);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, controls_.id());
  if (bytes != controls_bytes_) {
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    controls_bytes_ = bytes;
  }
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, header);
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, sizeof header, GLsizeiptr(packed.control_points.size() * sizeof(float)),
                  packed.control_points.data());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  ++control_uploads_;
  check_gl_error("FfdLatticeBuffers::upload");
}

void FfdLatticeBuffers::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTablesBinding, tables_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kControlsBinding, controls_.id());
}

}  // namespace trispline::gpu
