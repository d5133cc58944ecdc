// trispline::core DFFD caps — closing the openings of a mesh split at a parameter plane (seed §6.3.2, Fig. 6.2b).
//
// The seed caps the two parts of a model split at u = u_i by Boolean operations (M⁺ = F(M ∗ P⁺), M⁻ = F(M − P⁺)).
// We compute the same caps directly: after split_mesh_at_parameter, the boundary edges on the cut of each side form
// the planar cross-section loops of the (closed) mesh at u = u_i; they are triangulated, holes included, by CGAL's
// constrained Delaunay triangulation (CGAL 5.5, Debian libcgal-dev: Constrained_Delaunay_triangulation_2 with exact
// predicates, faces marked inside by nesting depth), so each side becomes a closed 2-manifold without adding
// vertices (unless the caps are textured, CapTexturing: then they get vertices of their own, at the same points).
// Because the embedding is affine with det > 0, the loops are planar in rest space too and the orientation found in
// parameter space is that of the mesh.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dffd/dffd.h"

namespace trispline::core {

// What cap_split_openings did.
struct CapStats {
  std::size_t loops = 0;        // closed cross-section loops found (both sides together)
  std::size_t open_chains = 0;  // boundary chains on the cut that do not close (mesh not closed there): not capped
  std::size_t triangles = 0;    // cap triangles appended (both sides together)
  std::size_t fan_loops = 0;    // degenerate loops (touching / crossing others in the plane) closed by a fan
};

// Texture coordinates of the caps (an object's inside texture, SceneObject::inside_texture; seed Fig. 6.9's
// wood-textured caps). A cap lies in the discontinuity plane params[axis] = u0, so its natural map is the plane's own
// two parameter coordinates: uv = (p[a]·uv_per_param[a], p[b]·uv_per_param[b]), p = params − param_offset, a = (axis+1)
// mod 3, b = (axis+2) mod 3. uv_per_param: texture repeats per parameter unit along u, v, w (the world length of a
// parameter unit ÷ the world size of one repeat; cap_texturing() in dffd_rig.h). All zero: untextured caps. max_edge >
// 0 also refines the textured caps inside: cap edges longer than max_edge parameter units (the larger of their two
// in-plane parameter differences) that are not on the section's loop are halved, level after level, so the FFD bends
// the cap with the lattice instead of spanning it with long flat triangles (cap_texturing() takes one knot span).
// plane_normals: column k is the unit rest-space normal of the planes u_k = const, towards growing u_k (the
// embedding's gradient of u_k); non-zero, the cap copies get it as their normal (minus side +, plus side −), so a
// viewer that shades by vertex normals lights the caps as flat faces. Zero: the surface's normals are copied.
// param_offset: subtracted from the parameters before the uv is taken (the rig's animated offset: the texture stays
// on the object, not on the lattice).
struct CapTexturing {
  glm::dvec3 uv_per_param{0.0};
  double max_edge = 0.0;
  glm::dmat3 plane_normals{0.0};
  glm::dvec3 param_offset{0.0};
  bool enabled() const { return uv_per_param != glm::dvec3(0.0); }
};

// Appends cap triangles to split.mesh (untextured: no vertices are added; split.params / split.side unchanged) for the
// cut params[·][axis] = u0 made by split_mesh_at_parameter(…, axis, u0, eps):
//  * cut vertices are the split's split.cut_vertices with |params[v][axis] − (u0 ∓ eps)| ≤ 1e-9 on side ∓1, and
//    only the triangles it touched (split.touched) are scanned: O(cut) work, not O(#F), however large the mesh;
//  * cut vertices of one side at the same point of the section (within 1e-9 in the two other parameter
//    coordinates: the copies a mesh carries along hard edges and UV seams) are welded, the smallest index standing
//    for its group, so a box with per-face vertices or a textured asset with seams is closed where it is cut;
//  * boundary edges (used by exactly one triangle, counted on the welded vertices) whose two ends are cut vertices
//    of the same side are chained into loops per side; each side's loops are triangulated in the two other parameter
//    coordinates (constrained Delaunay, CGAL; a face is inside when its nesting depth among the loops is odd, so holes
//    stay open);
//  * minus-side cap triangles face +axis (out of the minus part), plus-side ones face −axis;
//  * every appended triangle gets face_material = `material` (face_material is filled with kMaterialSurface for
//    the existing triangles first if it was empty).
//  * loops are chained in the direction of the mesh's boundary half-edges, deterministically (chain heads first,
//    then from the smallest vertex index; at a branching vertex the smallest successor);
//  * cap triangles are appended minus side first, each side's sorted (smallest index first in each triangle, winding
//    kept), so the order does not depend on CGAL's internal face storage.
// Chains that do not close (an open mesh) are left open and counted. Degenerate sections (two cut vertices of one
// side at the same 2D point, loops touching or crossing in the plane): every side's caps are verified to close each
// loop exactly (the reversed boundary half-edge once, every other cap half-edge paired); loops that fail are left out
// of a second triangulation and closed by a fan from their first vertex instead (counted in fan_loops), so a closed
// mesh always gets closed sides (untextured, no vertex is ever added to the mesh).
// Textured (texturing.enabled()): every vertex the caps use gets a copy appended to the mesh (ascending by the
// vertex it copies; position, normal, params and side copied, so it deforms to the same point bit for bit), with the
// uv above; the cap triangles use the copies. uvs are filled with (0, 0) for the other vertices when the mesh had none.
// Each side is then closed geometrically (its caps meet the surface at the same points) but not topologically; the
// cap copies' normals are ±plane_normals[axis] (or the surface's, see above). With max_edge > 0 the caps' inner edges
// are then split at their midpoints (red-green refinement: a triangle with 1, 2 or 3 split edges becomes 2, 3 or 4; the
// loop's edges are never split, so the caps still meet the surface at its own points), new vertices interpolating
// position, params and uv (exact: the section is planar and the embedding affine), in a fixed order (deterministic); at
// most 16 levels and 4 M cap triangles. Deterministic: the same input gives the same triangles in the same order.
// Throws std::invalid_argument: bad axis, params.size() != #V, side.size() != #V, a touched triangle ≥ #F or with an
// index ≥ #V, a cut vertex ≥ #V, face_material neither empty nor #F, uvs / normals neither empty nor #V, non-finite
// uv_per_param; `split` is then unchanged.
CapStats cap_split_openings(MeshSplit& split, int axis, double u0, double eps, MaterialSlot material = kMaterialInside,
                            const CapTexturing& texturing = {});

}  // namespace trispline::core
