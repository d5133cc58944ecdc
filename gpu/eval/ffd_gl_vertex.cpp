// GlslVertexFfdEvaluator: the FFD variant of mesh.vert.glsl, drawn by the renderer or captured by transform feedback.
#include <string>

#include "gpu/eval/ffd_gl.h"

namespace trispline::gpu {

GlslVertexFfdEvaluator::GlslVertexFfdEvaluator(std::shared_ptr<FfdProgramCache> programs, FfdOrderMode orders)
    : GlFfdEvaluatorBase(std::move(programs), orders), vao_(VertexArray::create()) {
  check_gl_error("GlslVertexFfdEvaluator()");
}

GlslVertexFfdEvaluator::~GlslVertexFfdEvaluator() = default;

void GlslVertexFfdEvaluator::prepare_programs() {
  ShaderDefines d = order_defines();
  d.emplace_back("FFD", "");
  std::vector<std::string> varyings = {"v_world"};
  if (normals_) varyings.push_back("v_normal");
  feedback_program_ = &programs_->get({"mesh.vert.glsl"}, d, varyings);
  setup_vertex_array();
}

// Attribute 2 = params, attribute 1 = rest normals (a constant when bound without normals); attribute 0 unused.
void GlslVertexFfdEvaluator::setup_vertex_array() {
  glBindVertexArray(vao_.id());
  float_attribute(2, params_.id(), 3);
  if (normals_) {
    float_attribute(1, rest_normals_.id(), 3);
  } else {
    glDisableVertexAttribArray(1);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GlslVertexFfdEvaluator::evaluate(const glm::dvec3& param_offset) {
  constexpr const char* where = "GlslVertexFfdEvaluator::evaluate";
  require_ready(where);
  evaluated_ = true;
  if (vertex_count_ == 0) return;
  const GLint previous_fbo = bind_complete_draw_framebuffer(fallback_fbo_, fallback_rb_);  // surfaceless EGL
  feedback_program_->use();
  feedback_program_->set("u_param_offset", shader_offset(param_offset));
  lattice_.bind();
  glBindVertexArray(vao_.id());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out_positions_.id());
  if (normals_) glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 1, out_normals_.id());
  const bool discard_was_on = glIsEnabled(GL_RASTERIZER_DISCARD);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, GLsizei(vertex_count_));
  glEndTransformFeedback();
  if (!discard_was_on) glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 1, 0);
  glBindVertexArray(0);
  glUseProgram(0);
  restore_draw_framebuffer(previous_fbo);
  check_gl_error(where);
}

const ShaderProgram& GlslVertexFfdEvaluator::draw_program(const ShaderDefines& variant) {
  require_ready("GlslVertexFfdEvaluator::draw_program");
  if (!normals_) throw std::logic_error("GlslVertexFfdEvaluator::draw_program: drawing needs rest normals");
  ShaderDefines d = order_defines();
  d.emplace_back("FFD", "");
  d.insert(d.end(), variant.begin(), variant.end());
  return programs_->get({"mesh.vert.glsl", "mesh.frag.glsl"}, d);
}

void GlslVertexFfdEvaluator::draw(const ShaderProgram& program, const MeshBuffers& mesh, const glm::dvec3& param_offset,
                                  std::optional<TriangleRange> range) {
  constexpr const char* where = "GlslVertexFfdEvaluator::draw";
  require_ready(where);
  if (mesh.vertex_count() != vertex_count_)
    throw std::invalid_argument(std::string(where) + ": mesh has " + std::to_string(mesh.vertex_count()) +
                                " vertices, " + std::to_string(vertex_count_) + " are bound");
  const TriangleRange r = range.value_or(TriangleRange{0, mesh.triangle_count()});
  if (r.first + r.count > mesh.triangle_count())
    throw std::invalid_argument(std::string(where) + ": triangle range outside the mesh's " +
                                std::to_string(mesh.triangle_count()) + " triangles");
  if (r.count == 0) return;
  program.set("u_param_offset", shader_offset(param_offset));
  lattice_.bind();
  glBindVertexArray(vao_.id());
  mesh.bind_uvs_to_bound_vao();  // texture coordinates ride along with the evaluated positions
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.index_buffer());  // VAO state: the mesh's triangles
  glDrawElements(GL_TRIANGLES, GLsizei(r.count * 3), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(r.first * sizeof(glm::uvec3)));
  glBindVertexArray(0);
  check_gl_error(where);
}

}  // namespace trispline::gpu
