// GlslComputeFfdEvaluator: ffd.comp.glsl dispatched over #V vertices (2D grid of work groups), writing its own
// output buffers or the renderer's MeshBuffers.
#include <algorithm>
#include <string>

#include "gpu/eval/ffd_gl.h"

namespace trispline::gpu {

GlslComputeFfdEvaluator::GlslComputeFfdEvaluator(std::shared_ptr<FfdProgramCache> programs, FfdOrderMode orders,
                                                 int local_size)
    : GlFfdEvaluatorBase(std::move(programs), orders), local_size_(local_size) {
  if (local_size < 1 || local_size > 1024)
    throw std::invalid_argument("GlslComputeFfdEvaluator: local size " + std::to_string(local_size) +
                                " outside 1..1024");
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  max_block_bytes_ = std::size_t(max_block);
  check_gl_error("GlslComputeFfdEvaluator()");
}

void GlslComputeFfdEvaluator::prepare_programs() {
  ShaderDefines d = order_defines();
  d.emplace_back("LOCAL_SIZE", std::to_string(local_size_));
  program_ = &programs_->get({"ffd.comp.glsl"}, d);
}

void GlslComputeFfdEvaluator::evaluate(const glm::dvec3& param_offset) {
  dispatch(out_positions_.id(), out_normals_.id(), param_offset, "GlslComputeFfdEvaluator::evaluate");
  evaluated_ = true;
}

void GlslComputeFfdEvaluator::evaluate_into(MeshBuffers& mesh, const glm::dvec3& param_offset) {
  if (mesh.vertex_count() != vertex_count_)
    throw std::invalid_argument("GlslComputeFfdEvaluator::evaluate_into: mesh has " +
                                std::to_string(mesh.vertex_count()) + " vertices, " + std::to_string(vertex_count_) +
                                " are bound");
  dispatch(mesh.position_buffer(), mesh.normal_buffer(), param_offset, "GlslComputeFfdEvaluator::evaluate_into");
}

void GlslComputeFfdEvaluator::evaluate_into(GLuint position_buffer, GLuint normal_buffer,
                                            const glm::dvec3& param_offset) {
  dispatch(position_buffer, normal_buffer, param_offset, "GlslComputeFfdEvaluator::evaluate_into");
}

void GlslComputeFfdEvaluator::dispatch(GLuint positions, GLuint normals, const glm::dvec3& param_offset,
                                       const char* where) {
  require_ready(where);
  if (vertex_count_ == 0) return;
  const std::size_t groups = (vertex_count_ + std::size_t(local_size_) - 1) / std::size_t(local_size_);
  const std::size_t gx = std::min<std::size_t>(groups, 65535);  // GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] ≥ 65535
  const std::size_t gy = (groups + gx - 1) / gx;
  if (gy > 65535 || 3 * sizeof(float) * vertex_count_ > max_block_bytes_)
    throw std::invalid_argument(std::string(where) + ": " + std::to_string(vertex_count_) +
                                " vertices exceed one dispatch (GL_MAX_SHADER_STORAGE_BLOCK_SIZE " +
                                std::to_string(max_block_bytes_) + " bytes)");
  program_->use();
  program_->set("u_param_offset", shader_offset(param_offset));
  program_->set("u_vertex_count", unsigned(vertex_count_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, params_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, positions);
  if (normals_) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, rest_normals_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, normals);
  }
  lattice_.bind();
  glDispatchCompute(GLuint(gx), GLuint(gy), 1);
  // The outputs are next read as vertex attributes (renderer), by glGetBufferSubData / glBufferSubData (read-back,
  // CPU updates) or by another dispatch.
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  for (GLuint b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
  glUseProgram(0);
  check_gl_error(where);
}

}  // namespace trispline::gpu
