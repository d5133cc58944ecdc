// trispline::core::DdmLayerDeformation — tile layers that follow their object (seed ch. 5 after ch. 2, 4 and 6): a
// layer's tiles are laid on the object's rest surface (T, the DDM, object space); the object's own deformation then
// carries them, T first, then the deformation, exactly as it carries the object's vertices:
//
//   1. host map H_i (per instance i, object space): where the rest surface itself has moved — a glTF clip posing the
//      mesh, an incision cutting and opening it, the opening's morph — the tile follows the triangle of the layer's
//      host mesh (DdmLayer::host_mesh) under its root (the base point at the cell centre): H_i is the similarity
//      (rotation × uniform scale: the polar factor of the map taking the triangle's rest frame [e₁, e₂, n̂·√|e₁×e₂|]
//      to its current one, scaled by its size change) anchored at the triangle's vertex nearest the root. Tiles keep
//      their shape; a tile whose triangle a cut tears apart rides with its nearest vertex's side; H_i = I exactly
//      where the triangle has not moved.
//   2. the object's transform M (object → world units);
//   3. the object's FFD F (placement, pressing, ring; seed Eq. 2.1) or DFFD rig (seed ch. 6): p = E(x) + offset(t),
//      x' = F(p), normals through cof(J_F·A) (seed §4.3) — the composed Jacobian of F∘E∘M∘H_i∘T acting on the tile's
//      normal, which step 1–2 already mapped through cof(H_i) and M⁻ᵀ. On a DFFD every instance stays on the side of
//      every break its root is on (its parameters are clamped to that side, u0 ∓ eps): a cut opens between tiles and
//      never tears one apart; outside the rig's box the identity E⁻¹ (as dffd_apply).
//
// The same steps, in float, are what the renderer's instanced DDM path runs (gpu/shaders/ddm.vert.glsl, FFD variant);
// this is the CPU reference it is held to (positions to 1e-5 × the object's size).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/ddm/ddm_layer.h"
#include "core/mesh/tri_mesh.h"
#include "core/scene/scene.h"

namespace trispline::core {

class FfdFastEvaluator;

// An affine map of object space: x ↦ linear·x + shift; normals by cof(linear) (= det·linear⁻ᵀ), renormalised.
struct DdmHostMap {
  glm::dmat3 linear{1.0};
  glm::dvec3 shift{0.0};
  bool operator==(const DdmHostMap&) const = default;
};

class DdmLayerDeformation {
 public:
  // What `object`'s deformation does to `layer` at scene time `time_s` (seconds; the object's offset_at(t), its clip
  // at clip_time(t), the layer's texture offset at t for the roots). For a still (scene_at_time) any time gives the
  // same. Throws std::invalid_argument: non-finite time, a layer without maps, a host mesh whose vertex count exceeds
  // the object's current surface, an instance tile out of range.
  DdmLayerDeformation(const SceneObject& object, const DdmLayer& layer, double time_s);

  // True when the layer is drawn with the object's transform only (nothing moves it): apply() = transformed().
  bool rigid() const { return hosts_.empty() && !lattice_; }
  // #instances host maps (object space), or empty when no instance's host triangle moved.
  const std::vector<DdmHostMap>& hosts() const { return hosts_; }
  // The lattice the tiles go through after the host maps and the transform (the object's FFD or DFFD lattice), or null.
  const TrivariateBSpline<glm::dvec3>* lattice() const { return lattice_; }
  const Embedding& embedding() const { return embedding_; }    // world → parameter domain (with a lattice)
  glm::dvec3 offset() const { return offset_; }                // parameter units added after E (with a lattice)
  bool identity_outside() const { return identity_outside_; }  // DFFD: outside [0,1]³ map by E⁻¹
  // #instances parameter boxes [lo, hi] every vertex of the instance is clamped to (DFFD breaks), or empty.
  const std::vector<glm::dvec3>& param_lo() const { return lo_; }
  const std::vector<glm::dvec3>& param_hi() const { return hi_; }
  const glm::dmat4& model() const { return model_; }  // the object's transform
  // The FfdBinding / DffdRig the lattice belongs to (null without a lattice): holding it keeps lattice() valid.
  const std::shared_ptr<const void>& lattice_owner() const { return keep_; }

  // World mesh of the layer's mesh at that time (`layer_mesh`: ddm_layer_mesh(layer, t) or layer.mesh for a still;
  // object space, instances in order, #V = Σ tile vertex counts): positions and unit normals through steps 1–3,
  // triangles, uvs and materials copied (winding flipped when det M < 0, as transformed()). Deterministic, TBB.
  // Throws std::invalid_argument: #V not the instances' vertex total, normals not #V.
  TriMesh apply(const TriMesh& layer_mesh) const;

 private:
  std::vector<std::size_t> first_vertex_;  // #instances + 1: where each instance's vertices start in the layer mesh
  std::vector<DdmHostMap> hosts_;
  const TrivariateBSpline<glm::dvec3>* lattice_ = nullptr;
  std::shared_ptr<const void> keep_;  // keeps the lattice's owner alive
  Embedding embedding_;
  glm::dvec3 offset_{0.0};
  bool identity_outside_ = false;
  std::vector<glm::dvec3> lo_, hi_;
  glm::dmat4 model_{1.0};
  bool flip_ = false;
};

// The CPU fast path of a layer carried by an FFD (placement, pressing, ring, offset animation), frame after frame: the
// tiles' parameters E(M·x) and world normals are bound once to a cpu_fast evaluator (float, vectorised; ffd_fast.h);
// each frame evaluates F at parameter offset `offset` with normals. Matches DdmLayerDeformation::apply to the
// cpu_fast tolerance (1e-5 × the lattice size). Host maps and DFFD sides are not handled (the reference path is).
// Not thread-safe: one per layer and thread.
class DdmFastFollower {
 public:
  DdmFastFollower();
  ~DdmFastFollower();
  // Binds the layer mesh (object space, ddm_layer_mesh or layer.mesh; #V × 3 positions and normals) of `object` (with
  // an FFD). Throws std::invalid_argument: no FFD, host maps or DFFD needed (use the reference), normals not #V.
  void bind(const SceneObject& object, const TriMesh& layer_mesh);
  // World positions and unit normals (#V × 3 each, float) of the bound tiles at the object's parameter offset.
  void evaluate(const glm::dvec3& offset, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);
  std::size_t vertex_count() const;

 private:
  std::unique_ptr<FfdFastEvaluator> ffd_;
};

// The layer in world units at `time_s` as everything exports and records it: DdmLayerDeformation(object, layer,
// time_s).apply(layer_mesh). Same errors.
TriMesh ddm_layer_world_mesh(const SceneObject& object, const DdmLayer& layer, const TriMesh& layer_mesh,
                             double time_s);

// The object-space positions of the object's surface at `time_s` whose first #host vertices the layers' host maps
// follow: the clip's pose (a glTF clip), the rest mesh morphed by its opening (SceneObject::morph), else the rest mesh.
std::vector<glm::dvec3> object_surface_positions(const SceneObject& object, double time_s);

}  // namespace trispline::core
