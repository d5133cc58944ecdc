// DffdRig evaluation: split at every break, cap, deform (identity outside the lattice box). See dffd_rig.h.
// Sources: seed §6.3.1 (global DFFD over the obstacles' box), §6.3.2 (split, caps, stitching).
#include "core/deform/dffd_rig.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/deform/dffd_cap.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

bool inside_unit_box(const glm::dvec3& p) {
  return p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0 && p.z >= 0.0 && p.z <= 1.0;
}

// True when some triangle has vertices on both sides of params[·][axis] = u0 or a vertex on it (what
// split_mesh_at_parameter would change); a cheap scan that lets frames where the object is away from a break skip
// the split (and its copy of the mesh).
bool touches_plane(const TriMesh& mesh, const std::vector<glm::dvec3>& params, int axis, double u0) {
  for (const glm::uvec3& t : mesh.triangles) {
    const double a = params[t[0]][axis] - u0, b = params[t[1]][axis] - u0, c = params[t[2]][axis] - u0;
    const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
    if (lo <= 1e-12 && hi >= -1e-12) return true;
  }
  return false;
}

}  // namespace

const char* dffd_openings_name(DffdOpenings o) {
  switch (o) {
    case DffdOpenings::open: return "open";
    case DffdOpenings::stitch: return "stitch";
    case DffdOpenings::cap: return "cap";
  }
  return "open";
}

MeshSplit dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, DffdApplyStats* stats) {
  const std::size_t nv = rest_world.vertex_count();
  if (rig.params.size() != nv)
    throw std::invalid_argument("dffd_apply: the rig has " + std::to_string(rig.params.size()) +
                                " parameters for " + std::to_string(nv) + " vertices");
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z))
    throw std::invalid_argument("dffd_apply: parameter offset is not finite");
  DffdApplyStats st;
  MeshSplit split;
  split.mesh = rest_world;
  split.params = rig.params;
  for (glm::dvec3& p : split.params) p += offset;
  for (const Discontinuity& d : rig.discontinuities) {
    if (!touches_plane(split.mesh, split.params, d.axis, d.u0)) continue;  // nothing to cut at this offset
    split_mesh_at_parameter_in_place(split, d.axis, d.u0, rig.eps);
    st.cut_edges += split.cut_edges;
    if (rig.openings != DffdOpenings::open) {
      const CapStats cs = cap_split_openings(split, d.axis, d.u0, rig.eps, kMaterialInside);
      st.cap_loops += cs.loops;
      st.open_chains += cs.open_chains;
      st.cap_triangles += cs.triangles;
    }
  }
  if (stats) *stats = st;
  return split;
}

TriMesh dffd_apply(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, DffdApplyStats* stats) {
  DffdApplyStats st;
  MeshSplit split = dffd_split(rig, rest_world, offset, &st);

  // Deform: F inside the lattice box, E⁻¹ outside (or clamped F when !identity_outside).
  TriMesh out;
  out.triangles = std::move(split.mesh.triangles);
  out.face_material = std::move(split.mesh.face_material);
  out.uvs = std::move(split.mesh.uvs);
  const std::vector<glm::dvec3>& params = split.params;
  const std::vector<glm::dvec3>& rest_nrm = split.mesh.normals;
  const bool with_normals = rest_nrm.size() == params.size();
  out.positions.resize(params.size());
  if (with_normals) out.normals.resize(params.size());
  // Vertices in the box go through the reference evaluator (ffd_evaluate: exact normals via cof(J·A)); the rest
  // map by E⁻¹ (the rest position moved by the offset) and keep their normals.
  const glm::dmat3 A_inv = glm::inverse(rig.embedding.linear);
  bool all_inside = true;
  for (std::size_t i = 0; i < params.size() && all_inside; ++i)
    all_inside = !rig.identity_outside || inside_unit_box(params[i]);
  if (all_inside) {  // the common case while cutting: evaluate in place, no gather / scatter copies
    if (with_normals)
      ffd_evaluate(rig.lattice, rig.embedding, params, rest_nrm, out.positions, out.normals);
    else
      ffd_evaluate(rig.lattice, params, out.positions);
    if (!with_normals) compute_vertex_normals(out);
    if (stats) *stats = st;
    return out;
  }
  std::vector<std::size_t> inside;
  inside.reserve(params.size());
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (!rig.identity_outside || inside_unit_box(params[i])) {
      inside.push_back(i);
    } else {
      out.positions[i] = A_inv * (params[i] - rig.embedding.offset);
      if (with_normals) out.normals[i] = rest_nrm[i];
      ++st.outside_vertices;
    }
  }
  std::vector<glm::dvec3> in_params(inside.size()), in_normals, in_pos, in_out_normals;
  for (std::size_t k = 0; k < inside.size(); ++k) in_params[k] = params[inside[k]];
  if (with_normals) {
    in_normals.resize(inside.size());
    for (std::size_t k = 0; k < inside.size(); ++k) in_normals[k] = rest_nrm[inside[k]];
    ffd_evaluate(rig.lattice, rig.embedding, in_params, in_normals, in_pos, in_out_normals);
    for (std::size_t k = 0; k < inside.size(); ++k) out.normals[inside[k]] = in_out_normals[k];
  } else {
    ffd_evaluate(rig.lattice, in_params, in_pos);
  }
  for (std::size_t k = 0; k < inside.size(); ++k) out.positions[inside[k]] = in_pos[k];
  if (!with_normals) compute_vertex_normals(out);
  if (stats) *stats = st;
  return out;
}

}  // namespace trispline::core
