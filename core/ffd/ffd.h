// trispline::core FFD — free-form deformation of a mesh through a trivariate B-spline control lattice.
//
// A mesh is *embedded* by an affine map E: world rest position x ↦ parameters (u,v,w) = A·x + b in [0,1]³, then
// deformed by F: x' = F(E(x)). Normals are mapped exactly through the Jacobian of the composition,
//   n' ∝ cof(J_F · A) · n   (cofactor matrix = det(M)·M^{-T}; no finite differences),
// then normalised. Evaluation runs in parallel over vertices (oneTBB) and is deterministic: each vertex is
// computed independently with a fixed operation order, so results are bit-identical for any thread count.
// Source: Sederberg & Parry 1986 (FFD); seed Eq. 2.1 (lattice), seed §4.3 (normals through the Jacobian).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// The affine embedding E(x) = linear·x + offset (world rest space → parameter domain [0,1]³).
struct Embedding {
  glm::dmat3 linear{1.0};  // A, column-major; det(A) > 0 so the mesh keeps its orientation
  glm::dvec3 offset{0.0};  // b
  glm::dvec3 apply(const glm::dvec3& x) const { return linear * x + offset; }
};

// Which rest-space axes map to the lattice's u (length, along the stroke) and w (up, away from the contact
// surface). Axes: 0 = x, 1 = y, 2 = z; they must differ. The remaining axis maps to v, oriented so det(A) > 0.
struct EmbeddingAxes {
  int length_axis = 0;
  int up_axis = 1;
};

// Embedding that maps the bounding box of `rest_positions` (#V × 3, world units) onto [0,1]³: length_axis → u,
// up_axis → w (bottom of the box at w = 0). Degenerate (flat) box extents map to the middle of the axis (0.5).
// Throws std::invalid_argument if the axes coincide or positions are empty / non-finite.
Embedding embed_bounding_box(const std::vector<glm::dvec3>& rest_positions, const EmbeddingAxes& axes);

// Parameters (#V × 3, in [0,1]³ for points inside the embedded box) of every rest position.
std::vector<glm::dvec3> embed_points(const Embedding& embedding, const std::vector<glm::dvec3>& rest_positions);

// A mesh bound to a lattice: everything needed to re-evaluate it after the lattice changes (pressing, animation).
struct FfdBinding {
  TrivariateBSpline<glm::dvec3> lattice;  // control lattice, world units
  Embedding embedding;                    // rest world space → [0,1]³
  std::vector<glm::dvec3> params;         // #V × 3, E(rest position) per vertex
};

// Reference CPU FFD in double precision (parallel, deterministic), any order. Parameters outside the domain are
// clamped per axis, wrapped (t − ⌊t⌋) on periodic axes (KnotVector::periodic_uniform).
//   params        #V × 3   parameter-domain points
//   out_positions #V × 3   resized; world units
void ffd_evaluate(const TrivariateBSpline<glm::dvec3>& F, const std::vector<glm::dvec3>& params,
                  std::vector<glm::dvec3>& out_positions);

// Positions and exact normals. rest_normals #V × 3 (world rest space, unit); out_normals #V × 3 unit.
// Where the mapped normal is degenerate (|cof·n| = 0) the rest normal is kept.
void ffd_evaluate(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                  const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals,
                  std::vector<glm::dvec3>& out_positions, std::vector<glm::dvec3>& out_normals);

// ffd_evaluate for a lattice that spans only part of space (the global DFFD's box, seed §6.3.1): params inside
// [0,1]³ map through F (normals through cof(J·A), as above); a param outside maps by the inverse embedding
// E⁻¹(p) = A⁻¹(p − b) and keeps its rest normal, so the map is the identity there when F is the identity of the
// box on its faces. One parallel pass, no gather / scatter. rest_normals #V × 3, or empty: then only positions are
// written (out_normals left as is). Returns the number of params outside [0,1]³.
// Throws std::invalid_argument: rest_normals neither empty nor #V.
std::size_t ffd_evaluate_identity_outside(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                                          const std::vector<glm::dvec3>& params,
                                          const std::vector<glm::dvec3>& rest_normals,
                                          std::vector<glm::dvec3>& out_positions, std::vector<glm::dvec3>& out_normals);

// The same on raw arrays of `count` points (a sub-range of a mesh, arrays already sized by the caller):
// params / out_positions count × 3; rest_normals and out_normals count × 3, or both null (positions only).
void ffd_evaluate_identity_outside(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                                   std::size_t count, const glm::dvec3* params, const glm::dvec3* rest_normals,
                                   glm::dvec3* out_positions, glm::dvec3* out_normals);

// Deformed copy of `rest_world` (world rest mesh with normals) through `binding`: topology and uvs copied,
// positions and normals evaluated. Throws std::invalid_argument if binding.params.size() != #V.
TriMesh ffd_apply(const FfdBinding& binding, const TriMesh& rest_world);

}  // namespace trispline::core
