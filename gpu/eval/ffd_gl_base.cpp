// What the GLSL FFD evaluators share: program cache, per-vertex buffers, lattice upload, read-back, the factory.
#include <cmath>
#include <string>

#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/gl_context.h"

namespace trispline::gpu {
namespace {

bool finite3(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// #V × 3 doubles → float32, throwing on non-finite input.
std::vector<float> to_float3(const std::vector<glm::dvec3>& v, const char* what) {
  std::vector<float> out(v.size() * 3);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!finite3(v[i]))
      throw std::invalid_argument(std::string("GLSL FFD bind_vertices: ") + what + " " + std::to_string(i) +
                                  " is not finite");
    out[3 * i + 0] = float(v[i].x);
    out[3 * i + 1] = float(v[i].y);
    out[3 * i + 2] = float(v[i].z);
  }
  return out;
}

void buffer_data(GLuint buffer, const std::vector<float>& data, std::size_t floats) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(floats * sizeof(float)), data.empty() ? nullptr : data.data(),
               GL_STATIC_DRAW);
}

void read_float3(GLuint buffer, std::size_t n, std::vector<glm::dvec3>& out) {
  std::vector<float> f(n * 3);
  out.resize(n);
  if (n == 0) return;
  glBindBuffer(GL_COPY_READ_BUFFER, buffer);
  glGetBufferSubData(GL_COPY_READ_BUFFER, 0, GLsizeiptr(f.size() * sizeof(float)), f.data());
  glBindBuffer(GL_COPY_READ_BUFFER, 0);
  for (std::size_t i = 0; i < n; ++i) out[i] = glm::dvec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
}

}  // namespace

const ShaderProgram& FfdProgramCache::get(const std::vector<std::string_view>& files, const ShaderDefines& defines,
                                          const std::vector<std::string>& feedback_varyings) {
  std::string key;
  for (std::string_view f : files) key += std::string(f) + "+";
  for (const auto& [name, value] : defines) key += " " + name + "=" + value;
  for (const std::string& v : feedback_varyings) key += " xfb:" + v;
  auto it = programs_.find(key);
  if (it == programs_.end())
    it = programs_.emplace(key, std::make_unique<ShaderProgram>(files, defines, feedback_varyings)).first;
  return *it->second;
}

GlFfdEvaluatorBase::GlFfdEvaluatorBase(std::shared_ptr<FfdProgramCache> programs, FfdOrderMode orders)
    : programs_(programs ? std::move(programs) : std::make_shared<FfdProgramCache>()),
      params_(Buffer::create()),
      rest_normals_(Buffer::create()),
      out_positions_(Buffer::create()),
      out_normals_(Buffer::create()),
      specialised_(orders == FfdOrderMode::specialised ||
                   (orders == FfdOrderMode::automatic && !is_software_renderer())) {}

GlFfdEvaluatorBase::~GlFfdEvaluatorBase() = default;

void GlFfdEvaluatorBase::bind_vertices(const std::vector<glm::dvec3>& params,
                                       const std::vector<glm::dvec3>& rest_normals) {
  if (!rest_normals.empty() && rest_normals.size() != params.size())
    throw std::invalid_argument("GLSL FFD bind_vertices: " + std::to_string(rest_normals.size()) +
                                " rest normals for " + std::to_string(params.size()) +
                                " parameters (give #V normals or none)");
  const std::vector<float> p = to_float3(params, "parameter");
  const std::vector<float> n = to_float3(rest_normals, "rest normal");
  const std::size_t nv = params.size();
  buffer_data(params_.id(), p, 3 * nv);
  buffer_data(rest_normals_.id(), n, n.size());
  buffer_data(out_positions_.id(), {}, 3 * nv);
  buffer_data(out_normals_.id(), {}, rest_normals.empty() ? 0 : 3 * nv);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  check_gl_error("GLSL FFD bind_vertices");
  const bool normals_changed = normals_ != !rest_normals.empty();
  vertex_count_ = nv;
  normals_ = !rest_normals.empty();
  bound_ = true;
  evaluated_ = false;
  if (lattice_set_ && normals_changed) prepare_programs();
}

void GlFfdEvaluatorBase::set_lattice(const core::TrivariateBSpline<glm::dvec3>& lattice,
                                     const core::Embedding& embedding) {
  core::FfdPackedLattice packed = core::FfdPackedLattice::build(lattice, embedding);  // validates orders
  const bool orders_changed = !lattice_set_ || (specialised_ && (packed.axes[0].order != packed_.axes[0].order ||
                                                                 packed.axes[1].order != packed_.axes[1].order ||
                                                                 packed.axes[2].order != packed_.axes[2].order));
  lattice_.upload(packed);
  packed_ = std::move(packed);
  lattice_set_ = true;
  if (orders_changed) prepare_programs();
}

void GlFfdEvaluatorBase::read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) {
  if (!evaluated_) throw std::logic_error("GLSL FFD read_results: no evaluate() since bind_vertices");
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // shader / transform-feedback writes before the read-back
  read_float3(out_positions_.id(), vertex_count_, positions);
  if (normals_)
    read_float3(out_normals_.id(), vertex_count_, normals);
  else
    normals.clear();
  check_gl_error("GLSL FFD read_results");
}

glm::vec3 GlFfdEvaluatorBase::shader_offset(const glm::dvec3& param_offset) const {
  glm::dvec3 o = param_offset;
  for (int a = 0; a < 3; ++a)
    if (lattice_set_ && packed_.axes[a].periodic) o[a] -= std::floor(o[a]);
  return glm::vec3(o);
}

void GlFfdEvaluatorBase::require_ready(const char* where) const {
  if (!bound_) throw std::logic_error(std::string(where) + ": bind_vertices first");
  if (!lattice_set_) throw std::logic_error(std::string(where) + ": set_lattice first");
}

ShaderDefines GlFfdEvaluatorBase::order_defines() const {
  ShaderDefines d;
  if (specialised_)
    d = {{"ORDER_U", std::to_string(packed_.axes[0].order)},
         {"ORDER_V", std::to_string(packed_.axes[1].order)},
         {"ORDER_W", std::to_string(packed_.axes[2].order)}};
  if (normals_) d.emplace_back("FFD_NORMALS", "");
  return d;
}

std::unique_ptr<core::FfdEvaluator> make_gl_ffd_evaluator(core::FfdBackend backend,
                                                          std::shared_ptr<FfdProgramCache> programs,
                                                          FfdOrderMode orders) {
  switch (backend) {
    case core::FfdBackend::glsl_compute:
      return std::make_unique<GlslComputeFfdEvaluator>(std::move(programs), orders);
    case core::FfdBackend::glsl_vertex:
      return std::make_unique<GlslVertexFfdEvaluator>(std::move(programs), orders);
    default:
      throw std::invalid_argument(std::string("make_gl_ffd_evaluator: ") + core::to_string(backend) +
                                  " is a CPU backend (use core::make_cpu_ffd_evaluator)");
  }
}

}  // namespace trispline::gpu
