// trispline::core DFFD — Discontinuous Free-Form Deformation, core foundation (seed ch. 6).
//
// A C^-1 break is made in the control lattice by raising the multiplicity of one knot u0 (on one axis) to the
// order (seed §6.3.1, Def. 6): the function is unchanged, but the lattice now has two coincident control planes
// F⁻ (last plane whose basis functions live left of u0) and F⁺ (first plane right of u0) that can be moved
// apart to open a cut. For the mesh to open along the cut it is split there first (seed §6.3.2): every edge
// crossing u0 in parameter space gets one vertex per side, triangles are re-triangulated so that no face
// straddles u0, and the new vertices' parameters are pushed to u0 − eps / u0 + eps so each side evaluates on its
// own half of the lattice.
// Sources: seed §6.3.1 Def. 6 (discontinuity by knot multiplicity = order), §6.3.2 (mesh splitting);
// knot insertion: Boehm 1980, Piegl & Tiller A5.1 (core/spline/knot_insertion.h, not re-implemented here).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

// A C^-1 discontinuity of a lattice: the knot u0 on `axis` has multiplicity = order.
struct Discontinuity {
  int axis = 0;         // 0 = u, 1 = v, 2 = w
  double u0 = 0.0;      // parameter-domain value of the break
  int minus_plane = 0;  // control index along `axis` of F⁻ (F(u0⁻) lies on this plane)
  int plus_plane = 0;   // control index along `axis` of F⁺ = minus_plane + 1 (F(u0⁺) lies on this plane)
};

// Inserts u0 into the knot vector of `axis` until its multiplicity equals the order (C^-1 there), through
// TrivariateBSpline::insert_knot (Boehm insertion). F is unchanged as a function and the planes F⁻, F⁺ coincide
// until moved (open_discontinuity). The control count along `axis` grows by order − (previous multiplicity).
//   F     lattice, world units; modified in place (only on success)
//   axis  0, 1 or 2;  u0  parameter domain, strictly inside (domain_min, domain_max) of that axis
// Throws std::invalid_argument: bad axis, non-finite u0, u0 not strictly inside the domain, u0 already a
// discontinuity (multiplicity ≥ order), periodic axis.
Discontinuity insert_discontinuity(TrivariateBSpline<glm::dvec3>& F, int axis, double u0);

// Opens a discontinuity: every control point of plane F⁻ moves by delta_minus and every control point of F⁺ by
// delta_plus (world units). Only the parameter span(s) in the support of those planes change.
// Throws std::invalid_argument if `disc` does not describe a discontinuity of F (axis, plane indices, knot
// multiplicity) or a delta is non-finite; F is then untouched.
void open_discontinuity(TrivariateBSpline<glm::dvec3>& F, const Discontinuity& disc, const glm::dvec3& delta_minus,
                        const glm::dvec3& delta_plus);

// Result of split_mesh_at_parameter.
struct MeshSplit {
  TriMesh mesh;                         // #V' vertices: the input's #V first (same indices), new ones appended
  std::vector<glm::dvec3> params;       // #V' × 3 parameter-domain points
  std::vector<std::int8_t> side;        // #V': -1 (params[v][axis] < u0) or +1 (> u0)
  std::size_t cut_edges = 0;            // distinct input edges that crossed u0 strictly
  std::size_t duplicated_on_plane = 0;  // input vertices on u0 that got a copy for the second side
  // What the last split changed, so later passes (cap_split_openings) need not scan the whole mesh:
  std::vector<std::uint32_t> cut_vertices;  // vertices it put at u0 ∓ eps (new cut vertices, on-plane ones), ascending
  std::vector<std::uint32_t> touched;       // triangles it rewrote or appended, ascending
};

// Splits `mesh` along the parameter plane params[·][axis] = u0 (seed §6.3.2).
//   mesh    #V vertices, #F triangles (normals / uvs optional, kept and interpolated when present; face_material
//           optional, every piece keeps its triangle's material)
//   params  #V × 3, parameter domain (e.g. embed_points of the rest positions)
//   eps     ≥ 0, parameter units: new/on-plane vertices get params[axis] = u0 ∓ eps on their side
// Rules:
//  * A vertex is "on the plane" when |params[v][axis] − u0| ≤ 1e-12, otherwise on side sign(params − u0).
//  * An edge whose ends lie strictly on opposite sides is cut once: one vertex per side at the exact crossing
//    t = (u0 − pa)/(pb − pa), position / uv linearly interpolated, normal interpolated and renormalised, params
//    interpolated then params[axis] set to u0 ∓ eps. Computed from the lower vertex index, so it is the same for
//    both faces of the edge.
//  * A triangle with one vertex alone on its side becomes a triangle (that side) + a quad split into two
//    triangles (other side, shorter diagonal); one on-plane vertex with the other two opposite gives two triangles.
//    Winding is preserved; the pieces tile the input triangle exactly (area preserved).
//  * Triangle order: a triangle on one side keeps its index; a triangle that touches the plane is replaced by its
//    first piece and its other pieces are appended after all input triangles, in input order.
//  * Every other triangle lies on one side: that of its off-plane vertices, or the minus side when all three are
//    on the plane. On-plane vertices are used by the side of each triangle that references them: the input index
//    serves the first side met (in triangle order), a copy is appended for the other side if it is met too; either
//    way its params[axis] becomes u0 ∓ eps. So no face has vertices on both sides and the surface opens along the
//    cut. Unreferenced on-plane vertices keep their params and get side -1.
// Deterministic (single-threaded, fixed order). An input without crossing edges or on-plane vertices is returned
// unchanged. Throws std::invalid_argument: params.size() != #V, bad axis, non-finite u0 / eps, eps < 0,
// a triangle index ≥ #V, normals / uvs sizes neither 0 nor #V.
MeshSplit split_mesh_at_parameter(const TriMesh& mesh, const std::vector<glm::dvec3>& params, int axis, double u0,
                                  double eps);

// The same split applied to split.mesh / split.params in place (no copy of the untouched part; what dffd_apply
// does every frame). split.side, cut_edges, duplicated_on_plane, cut_vertices and touched describe this split
// afterwards. Same errors; `split` is unchanged when it throws.
void split_mesh_at_parameter_in_place(MeshSplit& split, int axis, double u0, double eps);

namespace detail {
// split_mesh_at_parameter_in_place without the O(#V + #F) input checks, for callers that validated the mesh once
// and split it at several planes (dffd_split). Internal to core/dffd.
void split_in_place_unchecked(MeshSplit& split, int axis, double u0, double eps);
}  // namespace detail

}  // namespace trispline::core
