// trispline::gpu GLSL FFD evaluators (seed ch. 4 "Real-time FFD using programmable hardware").
//
// Two backends of core::FfdEvaluator (core/ffd/ffd_evaluator.h: same calls as the CPU backends, checked against
// the double reference in tests/gpu/test_ffd_gl.cpp within 1e-5 × lattice diagonal, normals within 1e-4 rad):
//   GlslComputeFfdEvaluator  compute shader ffd.comp.glsl; writes #V × 3 float positions / normals into its own
//                            buffers (evaluate) or straight into the buffers the renderer draws (evaluate_into).
//   GlslVertexFfdEvaluator   seed §4.2.1 single phase: the FFD variant of mesh.vert.glsl evaluates F per vertex while
//                            drawing (draw_program + draw); evaluate() runs the same shader with transform feedback
//                            and GL_RASTERIZER_DISCARD, for read_results, tests and the benchmark.
// Both evaluate core::FfdPackedLattice (the float tables every float backend shares; its header is the numerics
// spec) through ffd_eval.glsl; orders 2..4 per axis (FfdOrderMode: specialised per order combination through
// ORDER_U/V/W defines, or generic; programs compiled at set_lattice and cached in an FfdProgramCache), clamped /
// floating / non-uniform / periodic knot vectors, exact normals
// n' ∝ cof(J_F·A)·n (seed §4.3), float throughout, positions relative to the lattice centre.
//
// GL objects (all need the creating context current): SSBO bindings 0 params, 1 rest normals, 2 / 3 output
// positions / normals (compute), 4 knot tables, 5 control points + centre + embedding (ffd_gl_lattice.h).
// Every call that reaches GL checks glGetError and throws GlError naming the call; shader problems throw
// ShaderError with the GLSL log.
//
// Benchmark recipe (bench ffd): "dispatch only" = evaluate() then glFinish() (programs are compiled and the lattice
// uploaded by set_lattice, so evaluate() only issues the pass); "including upload/readback" = bind_vertices +
// set_lattice + evaluate + read_results. Both evaluators are reusable: bind once, set_lattice per press.
#pragma once

#include <epoxy/gl.h>

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ffd/ffd_evaluator.h"
#include "core/ffd/ffd_packed.h"
#include "gpu/eval/ffd_gl_lattice.h"
#include "gpu/gl/gl_resource.h"
#include "gpu/gl/mesh_buffers.h"
#include "gpu/gl/shader_program.h"

namespace trispline::gpu {

// How the shaders get the orders. specialised: ORDER_U/V/W defines, one program per order combination with fully
// unrolled loops (fastest on GPUs). generic: orders read from the knot tables at run time, one program for every
// combination (llvmpipe JIT-compiles each program variant at its first use, about a second each, so 27
// specialised variants would cost half a minute). automatic: generic on software renderers
// (is_software_renderer()), specialised otherwise. Both are the same ffd_eval.glsl code and are tested alike.
enum class FfdOrderMode { automatic, specialised, generic };

// Linked programs keyed by files + defines + transform-feedback varyings, so evaluators on one context (e.g. one per
// deformed object in the renderer) compile each order combination once. Needs the context current when used.
class FfdProgramCache {
 public:
  // The program, compiled now if new. Throws ShaderError.
  const ShaderProgram& get(const std::vector<std::string_view>& files, const ShaderDefines& defines,
                           const std::vector<std::string>& feedback_varyings = {});
  std::size_t size() const { return programs_.size(); }

 private:
  std::map<std::string, std::unique_ptr<ShaderProgram>> programs_;
};

// What both GL evaluators share: per-vertex input buffers, output buffers, the lattice SSBOs, state checks.
class GlFfdEvaluatorBase : public core::FfdEvaluator {
 public:
  ~GlFfdEvaluatorBase() override;
  // params / rest_normals #V × 3 (see core::FfdEvaluator). Uploads them as float32 and sizes the output buffers
  // (#V × 3 floats each). Throws std::invalid_argument (size mismatch, non-finite), GlError.
  void bind_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals) override;
  // Builds the FfdPackedLattice, uploads control points (+ centre, embedding) and, only when they changed, the knot
  // tables; compiles/fetches the program for the lattice's orders. Throws std::invalid_argument (order outside
  // 2..4), ShaderError, GlError.
  void set_lattice(const core::TrivariateBSpline<glm::dvec3>& lattice, const core::Embedding& embedding) override;
  // Waits for the last evaluate() and copies its output buffers: positions #V × 3 world units, normals #V × 3
  // (cleared without normals). Throws std::logic_error before the first evaluate().
  void read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) override;
  std::size_t vertex_count() const override { return vertex_count_; }
  bool has_normals() const override { return normals_; }

  GLuint params_buffer() const { return params_.id(); }                  // #V × 3 float (u,v,w)
  GLuint rest_normals_buffer() const { return rest_normals_.id(); }      // #V × 3 float, empty without normals
  GLuint output_position_buffer() const { return out_positions_.id(); }  // #V × 3 float, world units
  GLuint output_normal_buffer() const { return out_normals_.id(); }      // #V × 3 float, unit
  const FfdLatticeBuffers& lattice_buffers() const { return lattice_; }
  const core::FfdPackedLattice& packed_lattice() const { return packed_; }  // valid after set_lattice
  bool specialised_orders() const { return specialised_; }                  // FfdOrderMode after resolving `automatic`
  // The offset as the shaders get it: on periodic axes reduced to [0,1) in double first (exact: F wraps there), so
  // a large offset loses no precision in float.
  glm::vec3 shader_offset(const glm::dvec3& param_offset) const;

 protected:
  GlFfdEvaluatorBase(std::shared_ptr<FfdProgramCache> programs, FfdOrderMode orders);
  void require_ready(const char* where) const;  // throws std::logic_error before bind_vertices / set_lattice
  ShaderDefines order_defines() const;          // ORDER_U/V/W when specialised, FFD_NORMALS when bound with normals
  virtual void prepare_programs() = 0;          // called when orders or the normals setting changed

  std::shared_ptr<FfdProgramCache> programs_;
  Buffer params_, rest_normals_, out_positions_, out_normals_;
  FfdLatticeBuffers lattice_;
  core::FfdPackedLattice packed_;
  std::size_t vertex_count_ = 0;
  bool specialised_ = false;
  bool bound_ = false, lattice_set_ = false, evaluated_ = false, normals_ = false;
};

class GlslComputeFfdEvaluator final : public GlFfdEvaluatorBase {
 public:
  static constexpr int kDefaultLocalSize = 128;  // invocations per work group (measured, see gpu/README.md)
  // Needs a current GL 4.3 context. `programs` may be shared among evaluators (a private cache when null).
  // Throws std::invalid_argument for a local size outside 1..1024.
  explicit GlslComputeFfdEvaluator(std::shared_ptr<FfdProgramCache> programs = nullptr,
                                   FfdOrderMode orders = FfdOrderMode::automatic, int local_size = kDefaultLocalSize);
  core::FfdBackend backend() const override { return core::FfdBackend::glsl_compute; }
  // One dispatch into the evaluator's own output buffers (for read_results). Returns without waiting.
  // Throws std::logic_error before bind_vertices / set_lattice, GlError.
  void evaluate(const glm::dvec3& param_offset = glm::dvec3(0.0)) override;
  // One dispatch writing straight into `mesh`'s position (and, when bound with normals, normal) buffer — the buffers
  // the renderer draws (attributes 0/1), no CPU round trip; a memory barrier makes them ready for vertex fetch.
  // Does not touch the own output buffers (read_results still returns the last evaluate()).
  // Throws std::invalid_argument if mesh.vertex_count() != vertex_count(), std::logic_error, GlError.
  void evaluate_into(MeshBuffers& mesh, const glm::dvec3& param_offset = glm::dvec3(0.0));
  // Same into any buffers of ≥ #V × 3 floats (normals ignored without rest normals; may be 0 then).
  void evaluate_into(GLuint position_buffer, GLuint normal_buffer, const glm::dvec3& param_offset);
  int local_size() const { return local_size_; }

 private:
  void prepare_programs() override;
  void dispatch(GLuint positions, GLuint normals, const glm::dvec3& param_offset, const char* where);
  int local_size_;
  std::size_t max_block_bytes_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  const ShaderProgram* program_ = nullptr;
};

class GlslVertexFfdEvaluator final : public GlFfdEvaluatorBase {
 public:
  // Needs a current GL 4.3 context. `programs` may be shared among evaluators (a private cache when null).
  explicit GlslVertexFfdEvaluator(std::shared_ptr<FfdProgramCache> programs = nullptr,
                                  FfdOrderMode orders = FfdOrderMode::automatic);
  ~GlslVertexFfdEvaluator() override;
  core::FfdBackend backend() const override { return core::FfdBackend::glsl_vertex; }
  // The FFD vertex shader captured by transform feedback (GL_RASTERIZER_DISCARD, one GL_POINTS vertex per mesh
  // vertex) into the own output buffers. Binds a private 1×1 framebuffer while it runs if the bound one is
  // incomplete (surfaceless EGL has no default framebuffer). Returns without waiting.
  void evaluate(const glm::dvec3& param_offset = glm::dvec3(0.0)) override;

  // Drawing program: mesh.vert.glsl [FFD, FFD_NORMALS, orders, + variant] + mesh.frag.glsl [variant] (variant e.g.
  // {} shaded, {{"FLAT_COLOR",""}}, {{"OUTLINE",""},{"FLAT_COLOR",""}}), from the cache. Needs set_lattice and
  // rest normals (throws std::logic_error otherwise).
  const ShaderProgram& draw_program(const ShaderDefines& variant = {});
  // Draws `mesh`'s triangles (its index buffer; only `range` when given, e.g. mesh.inside_range()) with positions
  // and normals evaluated per vertex at params + param_offset. `program` comes from draw_program, is in use and has
  // its other uniforms set. Throws std::invalid_argument if mesh.vertex_count() != vertex_count() or `range` lies
  // outside the mesh's triangles, std::logic_error, GlError.
  void draw(const ShaderProgram& program, const MeshBuffers& mesh, const glm::dvec3& param_offset,
            std::optional<TriangleRange> range = std::nullopt);

 private:
  void prepare_programs() override;
  void setup_vertex_array();
  VertexArray vao_;  // attribute 1 = rest normal, 2 = params (indices bound per draw)
  Framebuffer fallback_fbo_;
  Renderbuffer fallback_rb_;
  const ShaderProgram* feedback_program_ = nullptr;
};

// glsl_compute → GlslComputeFfdEvaluator, glsl_vertex → GlslVertexFfdEvaluator (needs a current GL 4.3 context).
// Throws std::invalid_argument for a CPU backend (use core::make_cpu_ffd_evaluator).
std::unique_ptr<core::FfdEvaluator> make_gl_ffd_evaluator(core::FfdBackend backend,
                                                          std::shared_ptr<FfdProgramCache> programs = nullptr,
                                                          FfdOrderMode orders = FfdOrderMode::automatic);

}  // namespace trispline::gpu
