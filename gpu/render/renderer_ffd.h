// trispline::gpu::FfdDisplay — how the Renderer shows deformed objects: per object, the selected FFD
// backend (ViewOptions::ffd_backend) evaluates F(E(x) + offset) for display, offset = param_offset +
// offset_velocity · time_s (seed §4.5), with nothing visible changing between backends except speed:
//   glsl_compute  compute dispatch straight into the object's MeshBuffers (the buffers the renderer draws); objects
//                 whose offset changes every frame (offset_velocity ≠ 0) use the vertex path instead
//   glsl_vertex   the FFD vertex shader evaluates while drawing (nothing is written)
//   cpu_fast      core cpu_fast evaluator + MeshBuffers::update_vertices
//   cpu_ref       world_mesh as is (it is the CPU reference at param_offset); other offsets: cpu_ref evaluator;
//                 also used under any backend for lattices with an order outside 2..4
// Cached per object (by name): the evaluator, the rest normals (from world_rest_mesh(), once per binding / rest mesh
// / transform, not per frame), the bound parameters (kept across presses when the new binding has the same ones),
// and the last (binding, offset, backend, buffer generation) written, so nothing is recomputed when nothing changed.
// Internal to the renderer (renderer.cpp); not a public API.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/scene/scene.h"
#include "gpu/eval/ffd_gl.h"
#include "gpu/gl/mesh_buffers.h"

namespace trispline::gpu::detail {

// The renderer's GPU copy of one world_mesh, as FfdDisplay sees it.
struct DisplayBuffers {
  MeshBuffers* buffers = nullptr;
  std::uint64_t* generation = nullptr;  // bumped by whoever overwrites or re-uploads the buffers
  bool* overwritten = nullptr;          // true while the buffers hold something other than world_mesh
  const core::TriMesh* mesh = nullptr;  // world_mesh (for re-uploads)
};

// How one deformed object is drawn this frame.
struct FfdPlan {
  GlslVertexFfdEvaluator* vertex = nullptr;  // non-null: draw through the FFD vertex shader at `offset`
  glm::dvec3 offset{0.0};
};

class FfdDisplay {
 public:
  explicit FfdDisplay(std::shared_ptr<FfdProgramCache> programs) : programs_(std::move(programs)) {}
  // Brings `target` up to date for `object` (must have ffd and a world_mesh) under `backend` at `time_s`.
  // Returns how to draw it. Adds evaluated vertices to *vertices, CPU evaluation time to *cpu_ms, re-uploads to
  // *uploads. Throws what the evaluators throw (std::invalid_argument, ShaderError, GlError).
  // `live_lattice` (optional): a lattice to evaluate instead of object.ffd->lattice (same control counts, orders and
  // knots), e.g. the Press tool's drag preview; the binding's parameters stay bound.
  FfdPlan prepare(const core::SceneObject& object, const DisplayBuffers& target, core::FfdBackend backend,
                  double time_s, std::uint64_t& generation_counter, std::size_t* vertices, double* cpu_ms, int* uploads,
                  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> live_lattice = nullptr);
  // Drops the state of objects that are gone or no longer deformed.
  void release_unused(const core::Scene& scene);
  std::size_t cached() const { return states_.size(); }

 private:
  struct State {
    std::shared_ptr<const core::FfdBinding> binding;  // whose params are bound / lattice is set
    std::shared_ptr<const core::TriMesh> rest_mesh;   // what rest_normals came from (with transform)
    core::Transform transform;
    std::vector<glm::dvec3> rest_normals;  // #V × 3 world rest space, unit
    core::FfdBackend backend = core::FfdBackend::cpu_ref;
    std::unique_ptr<core::FfdEvaluator> evaluator;
    bool bound = false;                // evaluator has the binding's params
    const void* lattice_of = nullptr;  // lattice the evaluator holds (the binding's, or a live override)
    // The live override last used, held so its address cannot be reused by a newer one (lattice_of compares addresses).
    std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> live_hold;
    std::uint64_t written_generation = 0;  // buffers' generation after our last write (0 = none)
    const void* written_lattice = nullptr;
    glm::dvec3 written_offset{0.0};
    core::FfdBackend written_backend = core::FfdBackend::cpu_ref;
    std::vector<glm::vec3> positions, normals;  // CPU results in float, as uploaded (scratch)
  };
  void sync_inputs(State& s, const core::SceneObject& object);

  std::shared_ptr<FfdProgramCache> programs_;
  std::unordered_map<std::string, State> states_;
};

}  // namespace trispline::gpu::detail
