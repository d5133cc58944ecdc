// FfdDisplay: per-object FFD evaluation for display, cached so an unchanged object costs nothing. See renderer_ffd.h.
#include "gpu/render/renderer_ffd.h"

#include <algorithm>
#include <chrono>
#include <unordered_set>

namespace trispline::gpu::detail {
namespace {

bool same_transform(const core::Transform& a, const core::Transform& b) {
  return a.translate == b.translate && a.rotate_deg == b.rotate_deg && a.scale == b.scale;
}

std::unique_ptr<core::FfdEvaluator> make_evaluator(core::FfdBackend b, const std::shared_ptr<FfdProgramCache>& p) {
  return core::is_gpu_backend(b) ? make_gl_ffd_evaluator(b, p) : core::make_cpu_ffd_evaluator(b);
}

}  // namespace

void FfdDisplay::sync_inputs(State& s, const core::SceneObject& object) {
  const std::shared_ptr<const core::FfdBinding>& binding = object.ffd;
  if (s.binding != binding) {
    // A press makes a new binding with new control points but the same parameters: keep those bound.
    const bool same_params = s.binding && s.binding->params == binding->params;
    if (!same_params) s.bound = false;
    s.binding = binding;
  }
  if (s.rest_mesh != object.rest_mesh || !same_transform(s.transform, object.transform) ||
      s.rest_normals.size() != binding->params.size()) {
    const core::TriMesh rest = object.world_rest_mesh();
    if (rest.normals.size() == rest.positions.size()) {
      s.rest_normals = rest.normals;
    } else {  // as MeshBuffers::upload does for meshes without normals
      const std::vector<glm::vec3> n = vertex_normals(rest);
      s.rest_normals.assign(n.begin(), n.end());
    }
    s.rest_mesh = object.rest_mesh;
    s.transform = object.transform;
    s.bound = false;
  }
}

FfdPlan FfdDisplay::prepare(const core::SceneObject& object, const DisplayBuffers& target, core::FfdBackend backend,
                            double time_s, std::uint64_t& generation_counter, std::size_t* vertices, double* cpu_ms,
                            int* uploads, std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> live_lattice) {
  State& s = states_[object.name];
  const glm::dvec3 offset = object.offset_at(time_s);
  core::FfdBackend eff = backend;
  // The compute path writes the buffers once per change; an offset that moves every frame is the vertex path's job.
  if (eff == core::FfdBackend::glsl_compute && object.offset_animated()) eff = core::FfdBackend::glsl_vertex;
  // The float backends take orders 2..4; any other lattice is shown by the CPU reference.
  const glm::ivec3 orders = object.ffd->lattice.orders();
  if (glm::any(glm::lessThan(orders, glm::ivec3(2))) || glm::any(glm::greaterThan(orders, glm::ivec3(4))))
    eff = core::FfdBackend::cpu_ref;
  if (eff == core::FfdBackend::cpu_ref && live_lattice) eff = core::FfdBackend::cpu_fast;  // world_mesh is stale
  if (eff == core::FfdBackend::cpu_ref && offset == object.offset_at(0.0)) {
    // world_mesh (the t = 0 pose) already is the CPU reference at this offset: draw it, restoring it if a backend
    // overwrote it.
    if (*target.overwritten) {
      target.buffers->upload(*target.mesh);
      *target.overwritten = false;
      *target.generation = ++generation_counter;
      ++*uploads;
    }
    return {};
  }
  const auto t0 = std::chrono::steady_clock::now();
  sync_inputs(s, object);
  if (!s.evaluator || s.backend != eff) {
    s.evaluator = make_evaluator(eff, programs_);
    s.backend = eff;
    s.bound = false;
    s.written_generation = 0;
  }
  if (!s.bound) {
    s.evaluator->bind_vertices(s.binding->params, s.rest_normals);
    s.bound = true;
    s.lattice_of = nullptr;
  }
  const core::TrivariateBSpline<glm::dvec3>& lattice = live_lattice ? *live_lattice : s.binding->lattice;
  if (s.lattice_of != &lattice) {
    s.evaluator->set_lattice(lattice, s.binding->embedding);
    s.lattice_of = &lattice;
  }
  if (live_lattice) s.live_hold = std::move(live_lattice);  // after the comparison: the old one stays alive until here
  const std::size_t nv = s.binding->params.size();
  if (eff == core::FfdBackend::glsl_vertex) {
    *vertices += nv;  // evaluated while drawing
    return {static_cast<GlslVertexFfdEvaluator*>(s.evaluator.get()), offset};
  }
  if (s.written_generation == *target.generation && s.written_lattice == &lattice && s.written_offset == offset &&
      s.written_backend == eff)
    return {};  // the buffers already hold this evaluation
  if (eff == core::FfdBackend::glsl_compute) {
    static_cast<GlslComputeFfdEvaluator*>(s.evaluator.get())->evaluate_into(*target.buffers, offset);
  } else {
    s.evaluator->evaluate(offset);
    s.evaluator->read_results_float(s.positions, s.normals);
    target.buffers->update_vertices(s.positions, s.normals);
    *cpu_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  *target.overwritten = true;
  *target.generation = ++generation_counter;
  s.written_generation = *target.generation;
  s.written_lattice = &lattice;
  s.written_offset = offset;
  s.written_backend = eff;
  *vertices += nv;
  return {};
}

void FfdDisplay::release_unused(const core::Scene& scene) {
  std::unordered_set<std::string> live;
  for (const core::SceneObject& o : scene.objects())
    if (o.ffd) live.insert(o.name);
  std::erase_if(states_, [&](const auto& kv) { return !live.count(kv.first); });
}

}  // namespace trispline::gpu::detail
