// DFFD core: discontinuity insertion / opening in the lattice and mesh splitting at a parameter plane.
// See dffd.h. Sources: seed §6.3.1 Def. 6, §6.3.2; Boehm / Piegl & Tiller A5.1 (via TrivariateBSpline::insert_knot).
#include "core/dffd/dffd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace trispline::core {
namespace {

constexpr double kOnPlaneTol = 1e-12;

void require(bool ok, const std::string& msg) {
  if (!ok) throw std::invalid_argument(msg);
}

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

Discontinuity insert_discontinuity(TrivariateBSpline<glm::dvec3>& F, int axis, double u0) {
  require(axis >= 0 && axis <= 2, "insert_discontinuity: axis must be 0, 1 or 2, got " + std::to_string(axis));
  require(std::isfinite(u0), "insert_discontinuity: u0 must be finite, got " + num(u0));
  const KnotVector& kv = F.knots(axis);
  require(!kv.is_periodic(), "insert_discontinuity: axis " + std::to_string(axis) + " is periodic (not supported)");
  require(u0 > kv.domain_min() && u0 < kv.domain_max(),
          "insert_discontinuity: u0 = " + num(u0) + " must lie strictly inside the domain (" + num(kv.domain_min()) +
              ", " + num(kv.domain_max()) + ") of axis " + std::to_string(axis));
  const int order = kv.order();
  require(kv.multiplicity(u0) < order, "insert_discontinuity: u0 = " + num(u0) +
                                           " is already a discontinuity of axis " + std::to_string(axis) +
                                           " (multiplicity = order " + std::to_string(order) + ")");
  F.insert_knot(axis, u0, order);  // capped at multiplicity = order by the kernel
  const std::vector<double>& U = F.knots(axis).knots();
  const int r = static_cast<int>(std::find(U.begin(), U.end(), u0) - U.begin());  // first index of u0
  Discontinuity d;
  d.axis = axis;
  d.u0 = u0;
  d.minus_plane = r - 1;  // B_{r-1} has support [U_{r-1}, u0): F(u0⁻) = P_{r-1}
  d.plus_plane = r;       // B_r has support [u0, U_{r+order}): F(u0⁺) = P_r
  return d;
}

void open_discontinuity(TrivariateBSpline<glm::dvec3>& F, const Discontinuity& disc, const glm::dvec3& delta_minus,
                        const glm::dvec3& delta_plus) {
  require(disc.axis >= 0 && disc.axis <= 2,
          "open_discontinuity: axis must be 0, 1 or 2, got " + std::to_string(disc.axis));
  require(finite3(delta_minus) && finite3(delta_plus), "open_discontinuity: delta_minus / delta_plus must be finite");
  const KnotVector& kv = F.knots(disc.axis);
  const glm::ivec3 counts = F.control_counts();
  const int n = counts[disc.axis];
  const std::vector<double>& U = kv.knots();
  const bool planes_ok = disc.minus_plane >= 0 && disc.plus_plane == disc.minus_plane + 1 && disc.plus_plane < n &&
                         U[static_cast<std::size_t>(disc.plus_plane)] == disc.u0 &&
                         (disc.plus_plane == 0 || U[static_cast<std::size_t>(disc.plus_plane) - 1] != disc.u0);
  require(!kv.is_periodic() && std::isfinite(disc.u0) && kv.multiplicity(disc.u0) == kv.order() && planes_ok,
          "open_discontinuity: disc (axis " + std::to_string(disc.axis) + ", u0 = " + num(disc.u0) + ", planes " +
              std::to_string(disc.minus_plane) + "/" + std::to_string(disc.plus_plane) +
              ") is not a discontinuity of this lattice");
  for (int k = 0; k < counts.z; ++k)
    for (int j = 0; j < counts.y; ++j)
      for (int i = 0; i < counts.x; ++i) {
        const int a = glm::ivec3(i, j, k)[disc.axis];
        if (a == disc.minus_plane)
          F.control_point(i, j, k) += delta_minus;
        else if (a == disc.plus_plane)
          F.control_point(i, j, k) += delta_plus;
      }
}

namespace {

// Builds the split mesh; one instance per call.
class Splitter {
 public:
  // Splits `base` in place: its mesh and params are extended, its triangles rewritten where they touch the plane.
  Splitter(MeshSplit&& base, int axis, double u0, double eps)
      : out_(std::move(base)), in_(out_.mesh), axis_(axis), u0_(u0), eps_(eps) {
    const std::size_t nv = out_.mesh.vertex_count();
    // Room for the cut vertices up front: appending to vectors filled to capacity would copy them all again.
    // Callers that split at several planes reserve once for all (dffd_split); only grow when that room is short.
    if (out_.mesh.positions.capacity() < nv + nv / 16 + 64) {
      const std::size_t room = nv + nv / 8 + 64;
      out_.mesh.positions.reserve(room);
      if (!out_.mesh.normals.empty()) out_.mesh.normals.reserve(room);
      if (!out_.mesh.uvs.empty()) out_.mesh.uvs.reserve(room);
      out_.params.reserve(room);
      out_.side.reserve(room);
    }
    out_.side.resize(nv);
    out_.cut_edges = 0;
    out_.duplicated_on_plane = 0;
    out_.cut_vertices.clear();
    out_.touched.clear();
    cls_.resize(nv);
    const glm::dvec3* params = out_.params.data();
    std::int8_t* side = out_.side.data();
    for (std::size_t v = 0; v < nv; ++v) {
      const double d = params[v][axis] - u0;
      const std::int8_t c = std::abs(d) <= kOnPlaneTol ? 0 : (d < 0 ? -1 : 1);
      cls_[v] = c;
      side[v] = c == 0 ? -1 : c;
    }
  }

  // Triangles on one side keep their slot untouched; a triangle touching the plane is replaced by its first piece
  // and its other pieces are appended after all input triangles (in input order).
  MeshSplit run() {
    TriMesh& m = out_.mesh;
    const std::size_t nf = m.triangles.size();
    const bool with_materials = !m.face_material.empty();
    std::vector<glm::uvec3> extra;
    std::vector<MaterialSlot> extra_material;
    cuts_.reserve(1024);
    for (std::size_t f = 0; f < nf; ++f) {
      const glm::uvec3 t = m.triangles[f];
      const int a = cls_[t[0]], b = cls_[t[1]], c = cls_[t[2]];
      if (a != 0 && a == b && a == c) continue;  // strictly on one side: untouched
      material_ = m.material(f);
      pieces_.clear();
      split_triangle(t);
      m.triangles[f] = pieces_[0];
      out_.touched.push_back(static_cast<std::uint32_t>(f));
      for (std::size_t k = 1; k < pieces_.size(); ++k) {
        extra.push_back(pieces_[k]);
        if (with_materials) extra_material.push_back(material_);
      }
    }
    m.triangles.insert(m.triangles.end(), extra.begin(), extra.end());
    if (with_materials) m.face_material.insert(m.face_material.end(), extra_material.begin(), extra_material.end());
    for (std::size_t k = 0; k < extra.size(); ++k) out_.touched.push_back(static_cast<std::uint32_t>(nf + k));
    std::sort(out_.cut_vertices.begin(), out_.cut_vertices.end());
    out_.cut_edges = cuts_.size();
    return std::move(out_);
  }

 private:
  static int side_slot(int s) { return s < 0 ? 0 : 1; }

  // Index of vertex v as used on side s (-1/+1); on-plane vertices get their per-side copy.
  unsigned vert(unsigned v, int s) {
    if (cls_[v] != 0) return v;
    std::array<int, 2>& copies = copy_.try_emplace(v, std::array<int, 2>{-1, -1}).first->second;
    int& slot = copies[side_slot(s)];
    if (slot >= 0) return static_cast<unsigned>(slot);
    const int other = copies[1 - side_slot(s)];
    unsigned idx = v;
    if (other >= 0) {  // the input index already serves the other side: append a copy
      idx = append_copy(v);
      ++out_.duplicated_on_plane;
    }
    out_.params[idx][axis_] = u0_ + s * eps_;
    out_.side[idx] = static_cast<std::int8_t>(s);
    out_.cut_vertices.push_back(idx);
    slot = static_cast<int>(idx);
    return idx;
  }

  unsigned append_copy(unsigned v) {
    TriMesh& m = out_.mesh;
    const auto idx = static_cast<unsigned>(m.positions.size());
    m.positions.push_back(in_.positions[v]);
    if (!in_.normals.empty()) m.normals.push_back(in_.normals[v]);
    if (!in_.uvs.empty()) m.uvs.push_back(in_.uvs[v]);
    out_.params.push_back(out_.params[v]);
    out_.side.push_back(-1);
    return idx;
  }

  // Cut vertex of the edge (a, b) (strictly opposite sides) on side s.
  unsigned cut(unsigned a, unsigned b, int s) {
    const unsigned lo = std::min(a, b), hi = std::max(a, b);
    const std::uint64_t key = (std::uint64_t(lo) << 32) | hi;
    auto it = cuts_.find(key);
    if (it == cuts_.end()) {
      const glm::dvec3 pl = in_params(lo);  // copies: out_.params grows below
      const glm::dvec3 ph = in_params(hi);
      const double t = (u0_ - pl[axis_]) / (ph[axis_] - pl[axis_]);
      TriMesh& m = out_.mesh;
      std::array<unsigned, 2> ids{};
      for (int slot = 0; slot < 2; ++slot) {
        const int s2 = slot == 0 ? -1 : 1;
        const auto idx = static_cast<unsigned>(m.positions.size());
        m.positions.push_back(glm::mix(in_.positions[lo], in_.positions[hi], t));
        if (!in_.normals.empty()) {
          const glm::dvec3 n = glm::mix(in_.normals[lo], in_.normals[hi], t);
          const double len = glm::length(n);
          m.normals.push_back(len > 0.0 ? n / len : in_.normals[lo]);
        }
        if (!in_.uvs.empty()) m.uvs.push_back(glm::mix(in_.uvs[lo], in_.uvs[hi], t));
        glm::dvec3 p = glm::mix(pl, ph, t);
        p[axis_] = u0_ + s2 * eps_;
        out_.params.push_back(p);
        out_.side.push_back(static_cast<std::int8_t>(s2));
        out_.cut_vertices.push_back(idx);
        ids[slot] = idx;
      }
      it = cuts_.emplace(key, ids).first;
    }
    return it->second[side_slot(s)];
  }

  const glm::dvec3& in_params(unsigned v) const { return out_.params[v]; }  // off-plane vertices keep their params

  void emit(unsigned a, unsigned b, unsigned c) { pieces_.push_back({a, b, c}); }  // pieces keep the material

  double len2(unsigned a, unsigned b) const {
    const glm::dvec3 d = out_.mesh.positions[a] - out_.mesh.positions[b];
    return glm::dot(d, d);
  }

  void split_triangle(const glm::uvec3& t) {
    const int s[3] = {cls_[t[0]], cls_[t[1]], cls_[t[2]]};
    const bool has_minus = s[0] < 0 || s[1] < 0 || s[2] < 0;
    const bool has_plus = s[0] > 0 || s[1] > 0 || s[2] > 0;
    if (!(has_minus && has_plus)) {  // one side (minus when all three are on the plane)
      const int side = has_plus ? 1 : -1;
      emit(vert(t[0], side), vert(t[1], side), vert(t[2], side));
      return;
    }
    const int zeros = (s[0] == 0) + (s[1] == 0) + (s[2] == 0);
    if (zeros == 1) {  // rotate so the on-plane vertex is first: (a, b, c), b and c opposite
      int r = 0;
      while (s[r] != 0) ++r;
      const unsigned a = t[r], b = t[(r + 1) % 3], c = t[(r + 2) % 3];
      const int sb = s[(r + 1) % 3], sc = s[(r + 2) % 3];
      emit(vert(a, sb), b, cut(b, c, sb));
      emit(vert(a, sc), cut(b, c, sc), c);
      return;
    }
    // No on-plane vertex: rotate so the lone vertex is first: (a, b, c) with s(a) != s(b) == s(c).
    int r = 0;
    while (s[r] == s[(r + 1) % 3] || s[r] == s[(r + 2) % 3]) ++r;
    const unsigned a = t[r], b = t[(r + 1) % 3], c = t[(r + 2) % 3];
    const int sa = s[r], sb = -sa;
    emit(a, cut(a, b, sa), cut(c, a, sa));
    const unsigned mab = cut(a, b, sb), mca = cut(c, a, sb);
    // Quad (mab, b, c, mca): split along the shorter diagonal (mab–c on ties).
    if (len2(b, mca) < len2(mab, c)) {
      emit(mab, b, mca);
      emit(b, c, mca);
    } else {
      emit(mab, b, c);
      emit(mab, c, mca);
    }
  }

  MeshSplit out_;
  const TriMesh& in_;  // = out_.mesh: input vertices keep their indices and values while cut vertices are appended
  int axis_;
  double u0_, eps_;
  MaterialSlot material_ = kMaterialSurface;               // material of the input triangle being split
  std::vector<std::int8_t> cls_;                           // -1 / 0 (on plane) / +1 per input vertex
  std::unordered_map<unsigned, std::array<int, 2>> copy_;  // on-plane vertex → index used on the minus / plus side
  std::vector<glm::uvec3> pieces_;                         // the pieces of the triangle being split
  std::unordered_map<std::uint64_t, std::array<unsigned, 2>> cuts_;  // edge (lo << 32 | hi) → (minus, plus) vertex
};

}  // namespace

namespace {

void check_split_input(const TriMesh& mesh, const std::vector<glm::dvec3>& params, int axis, double u0, double eps) {
  const std::size_t nv = mesh.vertex_count();
  require(axis >= 0 && axis <= 2, "split_mesh_at_parameter: axis must be 0, 1 or 2, got " + std::to_string(axis));
  require(std::isfinite(u0), "split_mesh_at_parameter: u0 must be finite, got " + num(u0));
  require(std::isfinite(eps) && eps >= 0.0, "split_mesh_at_parameter: eps must be finite and >= 0, got " + num(eps));
  require(params.size() == nv, "split_mesh_at_parameter: params has " + std::to_string(params.size()) +
                                   " entries, the mesh has " + std::to_string(nv) + " vertices");
  require(mesh.normals.empty() || mesh.normals.size() == nv, "split_mesh_at_parameter: normals must be empty or #V");
  require(mesh.uvs.empty() || mesh.uvs.size() == nv, "split_mesh_at_parameter: uvs must be empty or #V");
  require(mesh.face_material.empty() || mesh.face_material.size() == mesh.triangles.size(),
          "split_mesh_at_parameter: face_material must be empty or #F");
  for (const glm::uvec3& t : mesh.triangles)
    require(t[0] < nv && t[1] < nv && t[2] < nv, "split_mesh_at_parameter: triangle index out of range");
  for (std::size_t v = 0; v < nv; ++v)
    require(std::isfinite(params[v][axis]), "split_mesh_at_parameter: params[" + std::to_string(v) + "] is not finite");
}

}  // namespace

MeshSplit split_mesh_at_parameter(const TriMesh& mesh, const std::vector<glm::dvec3>& params, int axis, double u0,
                                  double eps) {
  check_split_input(mesh, params, axis, u0, eps);
  MeshSplit base;
  base.mesh = mesh;
  base.params = params;
  return Splitter(std::move(base), axis, u0, eps).run();
}

void split_mesh_at_parameter_in_place(MeshSplit& split, int axis, double u0, double eps) {
  check_split_input(split.mesh, split.params, axis, u0, eps);
  split = Splitter(std::move(split), axis, u0, eps).run();
}

void detail::split_in_place_unchecked(MeshSplit& split, int axis, double u0, double eps) {
  split = Splitter(std::move(split), axis, u0, eps).run();
}

}  // namespace trispline::core
