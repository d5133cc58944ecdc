// incise(): embedding, mesh split along the cut sheet u = 1/2 and the cut-depth walls (seed §6.4).
#include "core/incision/incision.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "core/incision/incision_lattice.h"

namespace trispline::core {
namespace {
using incision_detail::LocalLattice;

// One input edge cut by the sheet: a vertex per side (minus = u < 1/2) at the crossing.
struct Crossing {
  glm::dvec3 param;     // (1/2, v, w) of the crossing
  glm::dvec3 position;  // input surface position (before the opening)
  int minus = -1, plus = -1;
  int column[2] = {-1, -1};  // wall column (index into columns) per side; bottom shared
};
// A wall column: vertex indices from the rim (row 0) down to the bottom (row wall_rows).
using Column = std::vector<int>;

struct RimEdge {
  int from_col, to_col;  // directed as in the surface piece
};

// Where a cut ends inside a face (a tip face).
struct Tip {
  int vertex;
  glm::dvec3 param, position;
};

// Column handles (index into colrefs): a crossing and a side, or a tip; columns are built after all faces.
struct ColRef {
  bool tip;
  int index, side;
};

glm::dvec3 lerp(const glm::dvec3& a, const glm::dvec3& b, double t) { return a + t * (b - a); }
glm::dvec2 lerp(const glm::dvec2& a, const glm::dvec2& b, double t) { return a + t * (b - a); }

glm::dvec3 unit(const glm::dvec3& d) { return glm::length(d) > 0.0 ? glm::normalize(d) : glm::dvec3(0.0); }

// The steps of incise(), numbered as in its comments; the state one step leaves for the next.
struct Incisor {
  const TriMesh& surface;
  const IncisionParams& params;
  const LocalLattice& L;
  const std::size_t V;
  const bool has_n, has_uv;
  IncisionResult res;
  TriMesh& out;  // res.mesh

  // Step 1: vertices near the lattice (has), their parameters (prm), embedded (emb) and fallback (fb) flags.
  std::vector<std::uint8_t> has;
  std::vector<std::uint32_t> cand;
  std::vector<glm::dvec3> prm;
  std::vector<std::uint8_t> emb, fb;
  // Steps 2-3: crossings, the output faces and their materials, tips, rim edges per side, column handles.
  std::unordered_map<std::uint64_t, int> edge_id;  // (lo << 32 | hi) → index into crossings, −1 = not cut
  std::vector<Crossing> crossings;
  std::vector<glm::uvec3> tris;
  std::vector<MaterialSlot> mats;
  std::vector<Tip> tips;
  std::vector<RimEdge> rim[2];
  std::vector<ColRef> colrefs;
  std::vector<std::uint32_t> near_faces;  // input faces with a located vertex (the only ones a moved vertex can be in)
  // Step 5: wall columns per side of a crossing, the shared bottom vertex per crossing, tip columns.
  std::vector<Column> cross_col[2];
  std::vector<int> bottom;
  std::vector<Column> tip_col;

  Incisor(const TriMesh& surface_, const IncisionParams& params_, const LocalLattice& lattice)
      : surface(surface_),
        params(params_),
        L(lattice),
        V(surface.positions.size()),
        has_n(surface.normals.size() == V && V > 0),
        has_uv(surface.uvs.size() == V && V > 0),
        res{TriMesh{}, L.split, 0, 0, 0, 0, 0, 0, L.bottom_w, L.controls, {}},
        out(res.mesh) {
    // The output mesh: the input's vertex attributes copied, its triangles built in step 3 from one copy.
    out.positions = surface.positions;
    out.normals = surface.normals;
    out.uvs = surface.uvs;
    for (std::size_t c = 0; c < res.lattice.control_points().size(); ++c)
      res.lattice.control_points()[c] += L.offset.control_points()[c];
  }

  int side(std::uint32_t v) const { return prm[v].x < 0.5 ? 0 : 1; }          // 0 = minus, 1 = plus
  glm::dvec3 opening(const glm::dvec3& q) const { return L.offset.eval(q); }  // D(q) = F_open − F

  void cull_and_invert();
  int crossing_of(std::uint32_t a, std::uint32_t b, glm::dvec3* param_out);
  bool crosses(std::uint32_t a, std::uint32_t b) const { return has[a] && has[b] && side(a) != side(b); }
  int col_of_crossing(int c, int s) {
    colrefs.push_back({false, c, s});
    return static_cast<int>(colrefs.size()) - 1;
  }
  int col_of_tip(int t) {
    colrefs.push_back({true, t, 0});
    return static_cast<int>(colrefs.size()) - 1;
  }
  void split_faces();
  void split_face(std::size_t f);
  void open();
  // `closed`: where the vertex is without the opening (IncisionResult::closed).
  int add_wall_vertex(const glm::dvec3& p, const glm::dvec2& uv, const glm::dvec3& n, const glm::dvec3& closed);
  const Column& column(int ref);
  void build_walls();
  void store_faces();
  void recompute_normals();
};

// 1. Cull: the vertices of every triangle whose bounding box meets the lattice's (the range lies in the convex hull
// of the control points), so both ends of every edge that can cross the cut sheet get parameters; then invert.
void Incisor::cull_and_invert() {
  Aabb box;
  for (const glm::dvec3& c : L.base.control_points()) box.extend(c);
  const glm::dvec3 pad(1e-9 * (params.width + L.half_height));
  box.lo -= pad;
  box.hi += pad;
  has.assign(V, 0);
  for (const glm::uvec3& t : surface.triangles) {
    const glm::dvec3 &a = surface.positions[t.x], &b = surface.positions[t.y], &c = surface.positions[t.z];
    const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    if (lo.x <= box.hi.x && hi.x >= box.lo.x && lo.y <= box.hi.y && hi.y >= box.lo.y && lo.z <= box.hi.z &&
        hi.z >= box.lo.z)
      has[t.x] = has[t.y] = has[t.z] = 1;
  }
  for (std::size_t v = 0; v < V; ++v)
    if (has[v]) cand.push_back(static_cast<std::uint32_t>(v));
  // prm: parameters (Newton inside the lattice, the frame's extended guess outside); has: prm is set.
  prm.assign(V, glm::dvec3(-1.0));
  emb.assign(V, 0);
  fb.assign(V, 0);
  tbb::parallel_for(std::size_t(0), cand.size(), [&](std::size_t c) {
    const std::uint32_t v = cand[c];
    const incision_detail::Located q = incision_detail::invert_point(L, surface.positions[v]);
    prm[v] = q.param, emb[v] = q.inside, fb[v] = q.fallback;
  });
  for (std::uint32_t v : cand) res.embedded_vertices += emb[v], res.newton_fallbacks += fb[v];
}

// 2. Cut edges: both ends with parameters, on opposite sides, crossing inside v ∈ (0,1) and above the bottom.
// Returns the crossing's index (its two vertices appended on first use), or −1; param_out: the crossing's parameters.
int Incisor::crossing_of(std::uint32_t a, std::uint32_t b, glm::dvec3* param_out) {
  const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
  const double t = (0.5 - prm[lo].x) / (prm[hi].x - prm[lo].x);
  const glm::dvec3 pc = lerp(prm[lo], prm[hi], t);
  if (param_out) *param_out = pc;
  if (!(pc.y > 0.0 && pc.y < 1.0 && pc.z < L.bottom_w)) return -1;
  const std::uint64_t key = (std::uint64_t(lo) << 32) | hi;
  auto [it, fresh] = edge_id.try_emplace(key, static_cast<int>(crossings.size()));
  if (fresh) {
    Crossing c;
    c.param = glm::dvec3(0.5, pc.y, pc.z);
    c.position = lerp(surface.positions[lo], surface.positions[hi], t);
    for (int s = 0; s < 2; ++s) {
      (s == 0 ? c.minus : c.plus) = static_cast<int>(out.positions.size());
      out.positions.push_back(c.position);
      if (has_n) {
        const glm::dvec3 nn = lerp(surface.normals[lo], surface.normals[hi], t);
        const double len = glm::length(nn);
        out.normals.push_back(len > 0 ? nn / len : surface.normals[lo]);
      }
      if (has_uv) out.uvs.push_back(lerp(surface.uvs[lo], surface.uvs[hi], t));
    }
    crossings.push_back(c);
  }
  return it->second;
}

// 3. Faces: a split face's first piece takes its place, the other pieces are appended (after all input faces,
// before the walls); rim edges per side for the walls.
void Incisor::split_faces() {
  tris = surface.triangles;
  mats = surface.face_material.empty() ? std::vector<MaterialSlot>(surface.triangles.size(), 0) : surface.face_material;
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) split_face(f);
  res.cut_edges = crossings.size();
  res.tips = tips.size();
}

void Incisor::split_face(std::size_t f) {
  const std::vector<glm::uvec3>& F = surface.triangles;
  const MaterialSlot mat = surface.material(f);
  const std::uint32_t t3[3] = {F[f].x, F[f].y, F[f].z};
  if (!(has[t3[0]] || has[t3[1]] || has[t3[2]])) return;
  near_faces.push_back(static_cast<std::uint32_t>(f));
  int cut[3] = {-1, -1, -1};  // crossing on edge (t3[e], t3[e+1])
  bool cr[3];
  glm::dvec3 pc[3];
  int ncut = 0;
  for (int e = 0; e < 3; ++e) {
    cr[e] = crosses(t3[e], t3[(e + 1) % 3]);
    if (cr[e]) cut[e] = crossing_of(t3[e], t3[(e + 1) % 3], &pc[e]);
    ncut += cut[e] >= 0;
  }
  bool first = true;
  auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (first) {
      tris[f] = glm::uvec3(a, b, c), first = false;
      return;
    }
    tris.emplace_back(a, b, c);
    mats.push_back(mat);
  };
  if (ncut == 0) return;
  ++res.split_faces;
  if (ncut == 2) {
    // Rotate so the lone vertex a = t3[r] has both cut edges: (a,b) = edge r, (c,a) = edge r+2.
    int r = 0;
    while (!(cut[r] >= 0 && cut[(r + 2) % 3] >= 0)) ++r;
    const std::uint32_t a = t3[r], b = t3[(r + 1) % 3], c = t3[(r + 2) % 3];
    const Crossing& xab = crossings[cut[r]];
    const Crossing& xca = crossings[cut[(r + 2) % 3]];
    const int sa = side(a), so = 1 - sa;
    const std::uint32_t ab_s = sa ? xab.plus : xab.minus, ca_s = sa ? xca.plus : xca.minus;
    const std::uint32_t ab_o = so ? xab.plus : xab.minus, ca_o = so ? xca.plus : xca.minus;
    emit(a, ab_s, ca_s);
    // Quad (ab_o, b, c, ca_o): the shorter diagonal.
    const double d1 = glm::length(xab.position - surface.positions[c]);
    const double d2 = glm::length(surface.positions[b] - xca.position);
    if (d1 <= d2) {
      emit(ab_o, b, c), emit(ab_o, c, ca_o);
    } else {
      emit(ab_o, b, ca_o), emit(b, c, ca_o);
    }
    rim[sa].push_back({col_of_crossing(cut[r], sa), col_of_crossing(cut[(r + 2) % 3], sa)});
    rim[so].push_back({col_of_crossing(cut[(r + 2) % 3], so), col_of_crossing(cut[r], so)});
    return;
  }
  // Tip face: the cut enters through edge r = (a, b) and ends inside at T (seed: the cut is local).
  int r = 0;
  while (cut[r] < 0) ++r;
  const std::uint32_t a = t3[r], b = t3[(r + 1) % 3], c = t3[(r + 2) % 3];
  const Crossing& x = crossings[cut[r]];
  Tip tip{static_cast<int>(out.positions.size()), x.param, {}};
  const int other = cr[(r + 1) % 3] ? (r + 1) % 3 : cr[(r + 2) % 3] ? (r + 2) % 3 : -1;
  if (other >= 0) {  // the sheet leaves through `other` outside the region: stop where the region ends
    const std::uint32_t p0 = t3[other], p1 = t3[(other + 1) % 3];
    const std::uint32_t lo = std::min(p0, p1), hi = std::max(p0, p1);
    const double t = (0.5 - prm[lo].x) / (prm[hi].x - prm[lo].x);
    const glm::dvec3 x2 = lerp(surface.positions[lo], surface.positions[hi], t);
    const glm::dvec3 q1 = x.param, q2 = pc[other];
    double s = 1.0;
    if (q2.y <= 0.0) s = std::min(s, q1.y / (q1.y - q2.y));
    if (q2.y >= 1.0) s = std::min(s, (1.0 - q1.y) / (q2.y - q1.y));
    if (q2.z >= L.bottom_w) s = std::min(s, (L.bottom_w - q1.z) / (q2.z - q1.z));
    s = std::clamp(s, 0.02, 0.98);
    tip.position = lerp(x.position, x2, s);
    tip.param = glm::dvec3(0.5, lerp(q1, q2, s).y, std::min(lerp(q1, q2, s).z, L.bottom_w));
  } else {
    tip.position = (surface.positions[a] + surface.positions[b] + surface.positions[c]) / 3.0;
  }
  out.positions.push_back(tip.position);
  if (has_n) out.normals.push_back(surface.normals[a]);  // recomputed in step 6
  if (has_uv) out.uvs.push_back((surface.uvs[a] + surface.uvs[b] + surface.uvs[c]) / 3.0);
  const int ti = static_cast<int>(tips.size());
  tips.push_back(tip);
  const int sa = side(a), sb = 1 - sa;
  const std::uint32_t xa = sa ? x.plus : x.minus, xb = sb ? x.plus : x.minus, T = tip.vertex;
  emit(a, xa, T), emit(xb, b, T), emit(b, c, T), emit(c, a, T);
  rim[sa].push_back({col_of_crossing(cut[r], sa), col_of_tip(ti)});
  rim[sb].push_back({col_of_tip(ti), col_of_crossing(cut[r], sb)});
}

// 4. Opening: surface vertices move by D(params) (F_open − F); rim copies on their side of the sheet.
void Incisor::open() {
  const std::size_t V1 = out.positions.size();
  res.moved.assign(V1, 0);
  std::vector<glm::dvec3> disp(V, glm::dvec3(0.0));
  tbb::parallel_for(std::size_t(0), cand.size(), [&](std::size_t c) {
    const std::uint32_t v = cand[c];
    if (emb[v]) disp[v] = opening(prm[v]);
  });
  res.closed = out.positions;  // input vertices at their input positions, cut vertices at their crossings
  for (std::uint32_t v : cand)
    if (disp[v] != glm::dvec3(0.0)) out.positions[v] += disp[v], res.moved[v] = 1;
  const double eps = params.eps;
  for (Crossing& c : crossings) {
    out.positions[c.minus] = c.position + opening(glm::dvec3(0.5 - eps, c.param.y, c.param.z));
    out.positions[c.plus] = c.position + opening(glm::dvec3(0.5 + eps, c.param.y, c.param.z));
  }
  for (std::size_t v = V; v < V1; ++v) res.moved[v] = 1;
}

int Incisor::add_wall_vertex(const glm::dvec3& p, const glm::dvec2& uv, const glm::dvec3& n, const glm::dvec3& closed) {
  out.positions.push_back(p);
  res.closed.push_back(closed);
  if (has_n) out.normals.push_back(n);
  if (has_uv) out.uvs.push_back(uv);
  res.moved.push_back(1);
  return static_cast<int>(out.positions.size()) - 1;
}

// The wall column behind a column handle, built on first use. Initial normals (kept where the faces around a vertex
// cancel, e.g. where both walls meet back to back): into the gap (∓S) on the walls, out of the groove (+N) on the
// shared bottom and tip columns.
const Column& Incisor::column(int ref) {
  const int R = params.wall_rows;
  const ColRef& cr = colrefs[ref];
  if (cr.tip) {
    Column& col = tip_col[cr.index];
    if (col.empty()) {
      const Tip& t = tips[cr.index];
      const glm::dvec3 base = incision_detail::eval_base(L, t.param);
      const glm::dvec2 uv = has_uv ? out.uvs[t.vertex] : glm::dvec2(0.0);
      col.push_back(t.vertex);
      for (int r = 1; r <= R; ++r) {
        const glm::dvec3 q(0.5, t.param.y, t.param.z + (L.bottom_w - t.param.z) * r / R);
        const glm::dvec3 p = t.position + incision_detail::eval_base(L, q) - base;
        col.push_back(add_wall_vertex(p, uv, unit(L.n_hat->eval(t.param.y)), p));
      }
    }
    return col;
  }
  Column& col = cross_col[cr.side][cr.index];
  if (col.empty()) {
    const Crossing& c = crossings[cr.index];
    const double u = cr.side ? 0.5 + params.eps : 0.5 - params.eps;
    const glm::dvec3 base = incision_detail::eval_base(L, c.param);
    const int top = cr.side ? c.plus : c.minus;
    const glm::dvec2 uv = has_uv ? out.uvs[top] : glm::dvec2(0.0);
    col.push_back(top);
    for (int r = 1; r < R; ++r) {
      const glm::dvec3 q(u, c.param.y, c.param.z + (L.bottom_w - c.param.z) * r / R);
      const glm::dvec3 closed = c.position + incision_detail::eval_base(L, q) - base;
      col.push_back(
          add_wall_vertex(closed + opening(q), uv, (cr.side ? 1.0 : -1.0) * unit(L.s_hat->eval(c.param.y)), closed));
    }
    if (bottom[cr.index] < 0) {  // D = 0 at the bottom: one vertex for both sides
      const glm::dvec3 q(0.5, c.param.y, L.bottom_w);
      const glm::dvec3 p = c.position + incision_detail::eval_base(L, q) - base;
      bottom[cr.index] = add_wall_vertex(p, uv, unit(L.n_hat->eval(c.param.y)), p);
    }
    col.push_back(bottom[cr.index]);
  }
  return col;
}

// 5. Walls: a column per rim vertex from the rim (row 0) to the bottom curve at w = bottom_w (row R, shared by
// both sides); rows at w linear from the rim's w, through F on the u = 1/2 ∓ eps planes. Tip columns are shared
// by both sides (the opening is zero there).
void Incisor::build_walls() {
  const int R = params.wall_rows;
  cross_col[0].assign(crossings.size(), {});
  cross_col[1].assign(crossings.size(), {});
  bottom.assign(crossings.size(), -1);
  tip_col.assign(tips.size(), {});
  for (int s = 0; s < 2; ++s)
    for (const RimEdge& e : rim[s]) {
      const Column A = column(e.from_col), B = column(e.to_col);
      for (int r = 0; r < R; ++r) {
        tris.emplace_back(B[r], A[r], A[r + 1]);
        tris.emplace_back(B[r], A[r + 1], B[r + 1]);
        mats.push_back(kMaterialInside), mats.push_back(kMaterialInside);
        res.wall_faces += 2;
      }
    }
}

void Incisor::store_faces() {
  out.triangles = std::move(tris);
  if (!surface.face_material.empty() || res.wall_faces > 0)
    out.face_material = std::move(mats);
  else
    out.face_material.clear();
}

// 6. Normals of moved and new vertices: area-weighted face normals, surface faces first (rims stay smooth); where
// they cancel (< 1e-6 of the summed face areas) the vertex keeps its interpolated / initial normal. Only faces
// near the cut (near_faces, then every appended face) can hold a moved vertex; sums are kept per moved vertex.
void Incisor::recompute_normals() {
  const std::size_t n_input_faces = surface.triangles.size();
  const std::size_t NV = out.positions.size();
  std::vector<std::int32_t> slot(NV, -1);
  std::vector<std::uint32_t> moved_list;
  for (std::size_t v = 0; v < NV; ++v)
    if (res.moved[v]) slot[v] = static_cast<std::int32_t>(moved_list.size()), moved_list.push_back(v);
  const std::size_t M = moved_list.size();
  std::vector<glm::dvec3> ns(M, glm::dvec3(0.0)), ni(M, glm::dvec3(0.0));
  std::vector<double> as(M, 0.0), ai(M, 0.0);
  auto accumulate = [&](std::size_t f) {
    const glm::uvec3 t = out.triangles[f];
    if (!(res.moved[t.x] || res.moved[t.y] || res.moved[t.z])) return;
    const glm::dvec3 fn = glm::cross(out.positions[t.y] - out.positions[t.x], out.positions[t.z] - out.positions[t.x]);
    const bool surf = out.material(f) != kMaterialInside;
    std::vector<glm::dvec3>& acc = surf ? ns : ni;
    std::vector<double>& area = surf ? as : ai;
    const double a = glm::length(fn);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t m = slot[t[k]];
      if (m >= 0) acc[m] += fn, area[m] += a;
    }
  };
  for (std::uint32_t f : near_faces) accumulate(f);  // ascending, then the appended faces: the input face order
  for (std::size_t f = n_input_faces; f < out.triangles.size(); ++f) accumulate(f);
  for (std::size_t m = 0; m < M; ++m) {
    const std::uint32_t v = moved_list[m];
    const bool surf = as[m] > 0.0;
    const glm::dvec3 sum = surf ? ns[m] : ni[m];
    const double len = glm::length(sum);
    if (len > 1e-6 * (surf ? as[m] : ai[m])) out.normals[v] = sum / len;
  }
}
}  // namespace

IncisionResult incise(const TriMesh& surface, const IncisionFrame& frame, const IncisionParams& params) {
  const LocalLattice L = incision_detail::build_local_lattice(frame, params);
  Incisor k(surface, params, L);
  k.cull_and_invert();
  k.split_faces();
  if (k.crossings.empty()) {  // nothing to cut: the surface unchanged
    k.res.mesh = surface;
    k.res.split_faces = 0;
    k.res.moved.assign(k.V, 0);
    k.res.closed = surface.positions;
    return std::move(k.res);
  }
  k.open();
  if (params.walls) k.build_walls();
  k.store_faces();
  if (k.has_n) k.recompute_normals();
  return std::move(k.res);
}

}  // namespace trispline::core
