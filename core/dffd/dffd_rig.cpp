// DffdRig evaluation: split at every break, cap, deform (identity outside the lattice box). See dffd_rig.h.
// Sources: seed §6.3.1 (global DFFD over the obstacles' box), §6.3.2 (split, caps, stitching).
#include "core/dffd/dffd_rig.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/base/enum_names.h"
#include "core/dffd/dffd_cap.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

bool inside_unit_box(const glm::dvec3& p) {
  return p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0 && p.z >= 0.0 && p.z <= 1.0;
}

}  // namespace

const char* dffd_openings_name(DffdOpenings o) { return enum_name(o, {"open", "stitch", "cap"}, "open"); }

double dffd_stitch_at(const DffdRig& rig, double time_s) {
  if (rig.stitch_keys.empty()) return rig.openings == DffdOpenings::stitch ? 1.0 : 0.0;
  return evaluate_offset_keys(rig.stitch_keys, time_s).x;
}

void dffd_set_stitch(DffdRig& rig, double s) {
  if (!rig.seam) throw std::invalid_argument("the DFFD has no seam to stitch (its openings are open)");
  if (!std::isfinite(s)) throw std::invalid_argument("the stitch weight is not finite");
  std::vector<glm::dvec3>& cps = rig.lattice.control_points();
  const std::vector<glm::dvec3>& a = rig.seam->open_points;
  const std::vector<glm::dvec3>& b = rig.seam->stitched_points;
  if (a.size() != cps.size() || b.size() != cps.size())
    throw std::invalid_argument("the DFFD seam has " + std::to_string(a.size()) + " / " + std::to_string(b.size()) +
                                " control points for a lattice of " + std::to_string(cps.size()));
  for (std::size_t i = 0; i < cps.size(); ++i) cps[i] = (1.0 - s) * a[i] + s * b[i];
}

std::shared_ptr<const DffdRig> dffd_rig_at(const std::shared_ptr<const DffdRig>& rig, double time_s) {
  if (!rig || rig->stitch_keys.empty()) return rig;
  auto still = std::make_shared<DffdRig>(*rig);
  dffd_set_stitch(*still, dffd_stitch_at(*rig, time_s));
  still->stitch_keys.clear();
  return still;
}

void dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, MeshSplit& out,
                DffdApplyStats* stats, const CapTexturing& texturing) {
  const std::size_t nv = rest_world.vertex_count();
  if (rig.params.size() != nv)
    throw std::invalid_argument("dffd_apply: the rig has " + std::to_string(rig.params.size()) + " parameters for " +
                                std::to_string(nv) + " vertices");
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z))
    throw std::invalid_argument("dffd_apply: parameter offset is not finite");
  if (!rest_world.normals.empty() && rest_world.normals.size() != nv)
    throw std::invalid_argument("dffd_apply: normals must be empty or #V");
  if (!rest_world.uvs.empty() && rest_world.uvs.size() != nv)
    throw std::invalid_argument("dffd_apply: uvs must be empty or #V");
  if (!rest_world.face_material.empty() && rest_world.face_material.size() != rest_world.triangle_count())
    throw std::invalid_argument("dffd_apply: face_material must be empty or #F");
  for (const glm::uvec3& t : rest_world.triangles)
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) throw std::invalid_argument("dffd_apply: triangle index ≥ #V");
  for (const Discontinuity& d : rig.discontinuities)
    if (d.axis < 0 || d.axis > 2 || !std::isfinite(d.u0))
      throw std::invalid_argument("dffd_apply: the rig has a bad discontinuity (axis " + std::to_string(d.axis) + ")");

  // One copy of the rest mesh into out's buffers (their capacity is kept from frame to frame), with room for the
  // cut vertices and pieces of every break, so the splits below never reallocate.
  DffdApplyStats st;
  const std::size_t nf = rest_world.triangle_count();
  const std::size_t room_v = nv + nv / 8 + 64, room_f = nf + nf / 8 + 64;
  auto fill = [](auto& dst, const auto& src, std::size_t room) {
    if (dst.capacity() < room) {
      dst.clear();
      dst.reserve(room);
    }
    dst.assign(src.begin(), src.end());
  };
  fill(out.mesh.positions, rest_world.positions, room_v);
  fill(out.mesh.normals, rest_world.normals, room_v);
  fill(out.mesh.uvs, rest_world.uvs, room_v);
  fill(out.mesh.triangles, rest_world.triangles, room_f);
  fill(out.mesh.face_material, rest_world.face_material, room_f);
  if (out.params.capacity() < room_v) {
    out.params.clear();
    out.params.reserve(room_v);
  }
  out.params.resize(nv);
  glm::dvec3 lo(1e300), hi(-1e300);  // parameter range of the mesh: a break outside it cuts nothing
  for (std::size_t v = 0; v < nv; ++v) {
    const glm::dvec3 p = rig.params[v] + offset;
    out.params[v] = p;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  if (out.side.capacity() < room_v) {
    out.side.clear();
    out.side.reserve(room_v);
  }
  out.side.assign(nv, -1);
  out.cut_edges = out.duplicated_on_plane = 0;
  out.cut_vertices.clear();
  out.touched.clear();
  CapTexturing textured = texturing;  // the uvs are taken without the offset: the texture stays on the object
  textured.param_offset = offset;
  for (const Discontinuity& d : rig.discontinuities) {
    // Cut vertices interpolate their edge's ends, so the range stays that of the rest vertices after each split.
    if (d.u0 < lo[d.axis] - 1e-12 || d.u0 > hi[d.axis] + 1e-12) continue;  // nothing to cut at this offset
    detail::split_in_place_unchecked(out, d.axis, d.u0, rig.eps);
    st.cut_edges += out.cut_edges;
    if (rig.openings != DffdOpenings::open && !out.touched.empty()) {
      const CapStats cs = cap_split_openings(out, d.axis, d.u0, rig.eps, kMaterialInside, textured);
      st.cap_loops += cs.loops;
      st.open_chains += cs.open_chains;
      st.cap_triangles += cs.triangles;
    }
  }
  if (stats) *stats = st;
}

MeshSplit dffd_split(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, DffdApplyStats* stats,
                     const CapTexturing& texturing) {
  MeshSplit split;
  dffd_split(rig, rest_world, offset, split, stats, texturing);
  return split;
}

void dffd_deform(const DffdRig& rig, MeshSplit& split, TriMesh& out, DffdApplyStats* stats) {
  const std::size_t nv = split.params.size();
  if (split.mesh.vertex_count() != nv || (!split.mesh.normals.empty() && split.mesh.normals.size() != nv))
    throw std::invalid_argument("dffd_deform: the split has " + std::to_string(split.mesh.vertex_count()) +
                                " vertices, " + std::to_string(nv) + " parameters and " +
                                std::to_string(split.mesh.normals.size()) + " normals");
  // Topology and uvs change hands (swap: both sides keep their buffers for the next frame).
  out.triangles.swap(split.mesh.triangles);
  out.face_material.swap(split.mesh.face_material);
  out.uvs.swap(split.mesh.uvs);
  const std::vector<glm::dvec3>& rest_nrm = split.mesh.normals;
  std::size_t outside = 0;
  if (rig.identity_outside) {
    outside =
        ffd_evaluate_identity_outside(rig.lattice, rig.embedding, split.params, rest_nrm, out.positions, out.normals);
  } else if (!rest_nrm.empty()) {
    ffd_evaluate(rig.lattice, rig.embedding, split.params, rest_nrm, out.positions, out.normals);
  } else {
    ffd_evaluate(rig.lattice, split.params, out.positions);
  }
  if (rest_nrm.empty()) compute_vertex_normals(out);
  if (stats) stats->outside_vertices = outside;
}

TriMesh dffd_apply(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset, DffdApplyStats* stats,
                   const CapTexturing& texturing) {
  DffdFrameEvaluator evaluator;
  evaluator.evaluate(rig, rest_world, offset, stats, texturing);
  return evaluator.take();
}

CapTexturing cap_texturing(const DffdRig& rig, double texture_size) {
  if (!std::isfinite(texture_size) || texture_size <= 0.0)
    throw std::invalid_argument("cap_texturing: the texture size must be finite and > 0");
  const double det = glm::determinant(rig.embedding.linear);
  if (!std::isfinite(det) || det == 0.0) throw std::invalid_argument("cap_texturing: the embedding is singular");
  const glm::dmat3 inverse = glm::inverse(rig.embedding.linear);  // columns: world vectors of the parameter units
  CapTexturing t;
  for (int k = 0; k < 3; ++k) t.uv_per_param[k] = glm::length(inverse[k]) / texture_size;
  // The planes u_k = const: normals along the gradient of u_k (row k of the embedding's linear part).
  const glm::dmat3 rows = glm::transpose(rig.embedding.linear);
  for (int k = 0; k < 3; ++k) t.plane_normals[k] = glm::normalize(rows[k]);
  // The shortest uniform knot span: the cap bends with the lattice.
  const glm::ivec3 spans = rig.lattice.control_counts() - rig.lattice.orders() + 1;
  t.max_edge = 1.0 / std::max({spans.x, spans.y, spans.z, 1});
  return t;
}

const TriMesh& DffdFrameEvaluator::evaluate(const DffdRig& rig, const TriMesh& rest_world, const glm::dvec3& offset,
                                            DffdApplyStats* stats, const CapTexturing& texturing) {
  if (!rig.identity_outside) {  // the overlap below is written for the global DFFD's identity-outside map
    DffdApplyStats st;
    dffd_split(rig, rest_world, offset, split_, &st, texturing);
    dffd_deform(rig, split_, mesh_, &st);
    if (stats) *stats = st;
    return mesh_;
  }
  const std::size_t nv = rest_world.vertex_count();
  if (rig.params.size() != nv)
    throw std::invalid_argument("dffd_apply: the rig has " + std::to_string(rig.params.size()) + " parameters for " +
                                std::to_string(nv) + " vertices");
  const bool with_normals = !rest_world.normals.empty();
  if (with_normals && rest_world.normals.size() != nv)
    throw std::invalid_argument("dffd_apply: normals must be empty or #V");
  // The input vertices keep their parameters through the split (only on-plane ones move to u0 ∓ eps), so they are
  // deformed on a worker while this thread splits and caps; the split's new vertices and the few moved ones follow.
  // Each vertex's result depends only on its own parameter and rest normal: bit-identical to dffd_apply.
  base_.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) base_[v] = rig.params[v] + offset;
  const std::size_t room = nv + nv / 8 + 64;
  mesh_.positions.reserve(room);
  mesh_.positions.resize(nv);
  if (with_normals) {
    mesh_.normals.reserve(room);
    mesh_.normals.resize(nv);
  }
  tbb::task_group deform_inputs;
  deform_inputs.run([&] {
    ffd_evaluate_identity_outside(rig.lattice, rig.embedding, nv, base_.data(),
                                  with_normals ? rest_world.normals.data() : nullptr, mesh_.positions.data(),
                                  with_normals ? mesh_.normals.data() : nullptr);
  });
  DffdApplyStats st;
  try {
    dffd_split(rig, rest_world, offset, split_, &st, texturing);
  } catch (...) {
    deform_inputs.wait();
    throw;
  }
  deform_inputs.wait();
  const std::size_t n_split = split_.params.size();
  // Input vertices whose parameter the split moved (on a plane) and the split's new vertices: gathered, evaluated.
  redo_.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (split_.params[v] != base_[v]) redo_.push_back(v);
  for (std::size_t v = nv; v < n_split; ++v) redo_.push_back(v);
  const std::vector<glm::dvec3>& rest_nrm = split_.mesh.normals;
  redo_params_.resize(redo_.size());
  redo_normals_.resize(with_normals ? redo_.size() : 0);
  for (std::size_t k = 0; k < redo_.size(); ++k) {
    redo_params_[k] = split_.params[redo_[k]];
    if (with_normals) redo_normals_[k] = rest_nrm[redo_[k]];
  }
  redo_pos_.resize(redo_.size());
  redo_out_normals_.resize(redo_normals_.size());
  ffd_evaluate_identity_outside(rig.lattice, rig.embedding, redo_.size(), redo_params_.data(),
                                with_normals ? redo_normals_.data() : nullptr, redo_pos_.data(),
                                with_normals ? redo_out_normals_.data() : nullptr);
  mesh_.positions.resize(n_split);
  if (with_normals) mesh_.normals.resize(n_split);
  for (std::size_t k = 0; k < redo_.size(); ++k) {
    mesh_.positions[redo_[k]] = redo_pos_[k];
    if (with_normals) mesh_.normals[redo_[k]] = redo_out_normals_[k];
  }
  mesh_.triangles.swap(split_.mesh.triangles);
  mesh_.face_material.swap(split_.mesh.face_material);
  mesh_.uvs.swap(split_.mesh.uvs);
  if (!with_normals) compute_vertex_normals(mesh_);
  st.outside_vertices = static_cast<std::size_t>(std::count_if(
      split_.params.begin(), split_.params.end(), [](const glm::dvec3& p) { return !inside_unit_box(p); }));
  if (stats) *stats = st;
  return mesh_;
}

}  // namespace trispline::core
