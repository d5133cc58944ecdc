#include "core/ffd/refine.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "core/base/enum_names.h"
#include "core/ffd/deformation_bounds.h"

namespace trispline::core {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// Inverse of the Bernstein collocation matrix at Chebyshev–Lobatto nodes s_i = (1 − cos(πi/D))/2, i = 0..D:
// control points c = Minv · samples. Gauss–Jordan with partial pivoting, once per refinement.
struct BezierInterp {
  int degree = 1;
  std::vector<double> nodes;  // #(D+1)
  std::vector<double> inv;    // (D+1) × (D+1), row-major

  explicit BezierInterp(int d) : degree(std::max(d, 1)) {
    const int n = degree + 1;
    nodes.resize(n);
    for (int i = 0; i < n; ++i) nodes[i] = 0.5 * (1.0 - std::cos(std::numbers::pi * i / degree));
    nodes[0] = 0.0;
    nodes[degree] = 1.0;
    std::vector<double> a(n * n), binom(n, 1.0);
    for (int j = 1; j < n; ++j) binom[j] = binom[j - 1] * double(degree - j + 1) / double(j);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        a[i * n + j] = binom[j] * std::pow(nodes[i], j) * std::pow(1.0 - nodes[i], degree - j);
    inv.assign(n * n, 0.0);
    for (int i = 0; i < n; ++i) inv[i * n + i] = 1.0;
    for (int c = 0; c < n; ++c) {
      int p = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(a[r * n + c]) > std::abs(a[p * n + c])) p = r;
      if (p != c)
        for (int k = 0; k < n; ++k) {
          std::swap(a[p * n + k], a[c * n + k]);
          std::swap(inv[p * n + k], inv[c * n + k]);
        }
      const double d = a[c * n + c];
      for (int k = 0; k < n; ++k) {
        a[c * n + k] /= d;
        inv[c * n + k] /= d;
      }
      for (int r = 0; r < n; ++r) {
        if (r == c) continue;
        const double f = a[r * n + c];
        if (f == 0.0) continue;
        for (int k = 0; k < n; ++k) {
          a[r * n + k] -= f * a[c * n + k];
          inv[r * n + k] -= f * inv[c * n + k];
        }
      }
    }
  }
};

int composed_degree(const TrivariateBSpline<glm::dvec3>& F) {
  const glm::ivec3 o = F.orders();
  return (o.x - 1) + (o.y - 1) + (o.z - 1);
}

// Parameters t in (0,1) where the edge pa→pb crosses a knot plane (or starts clamping / wraps) of any axis:
// between two consecutive ones E_p is one polynomial. Sorted, with 0 and 1 at the ends.
std::vector<double> edge_breaks(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb) {
  std::vector<double> t{0.0, 1.0};
  for (int a = 0; a < 3; ++a) {
    const double d = pb[a] - pa[a];
    if (d == 0.0) continue;
    const KnotVector& kv = F.knots(a);
    const double lo = std::min(pa[a], pb[a]), hi = std::max(pa[a], pb[a]);
    auto add = [&](double k) {
      const double s = (k - pa[a]) / d;
      if (s > 0.0 && s < 1.0) t.push_back(s);
    };
    if (kv.is_periodic()) {
      if (hi - lo > 1e4) throw std::invalid_argument("refine: edge spans more than 10^4 turns of a periodic axis");
      const double n0 = std::floor(lo), n1 = std::floor(hi);
      for (double k : kv.knots())
        if (k >= 0.0 && k < 1.0)
          for (double n = n0; n <= n1; n += 1.0) add(k + n);
    } else {
      for (double k : kv.knots())
        if (k >= kv.domain_min() && k <= kv.domain_max() && k > lo && k < hi) add(k);
    }
  }
  std::sort(t.begin(), t.end());
  std::vector<double> out;
  for (double s : t)
    if (out.empty() || s - out.back() > 1e-12) out.push_back(s);
  if (out.back() != 1.0) out.back() = 1.0;  // a break within 1e-12 of 1 merges into the end
  return out;
}

void bezier_pieces(const TrivariateBSpline<glm::dvec3>& F, const BezierInterp& bi, const glm::dvec3& pa,
                   const glm::dvec3& pb, std::vector<double>& breaks, std::vector<glm::dvec3>& ctrl) {
  breaks = edge_breaks(F, pa, pb);
  const int n = bi.degree + 1;
  ctrl.assign((breaks.size() - 1) * n, glm::dvec3(0.0));
  std::vector<glm::dvec3> y(n);
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double t0 = breaks[p], t1 = breaks[p + 1];
    for (int i = 0; i < n; ++i) {
      const double t = t0 + bi.nodes[i] * (t1 - t0);
      y[i] = F.eval(pa + t * (pb - pa));
    }
    for (int j = 0; j < n; ++j) {
      glm::dvec3 c(0.0);
      for (int i = 0; i < n; ++i) c += bi.inv[j * n + i] * y[i];
      ctrl[p * n + j] = c;
    }
  }
}

EdgeGreville greville_measure(const TrivariateBSpline<glm::dvec3>& F, const BezierInterp& bi, const glm::dvec3& pa,
                              const glm::dvec3& pb, const glm::dvec3& fa, const glm::dvec3& fb) {
  std::vector<double> breaks;
  std::vector<glm::dvec3> ctrl;
  bezier_pieces(F, bi, pa, pb, breaks, ctrl);
  const int n = bi.degree + 1;
  EdgeGreville best{0.0, 0.5};
  const glm::dvec3 chord = fb - fa;
  const double len2 = glm::dot(chord, chord);
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p)
    for (int j = 0; j < n; ++j) {
      const double xi = breaks[p] + (double(j) / bi.degree) * (breaks[p + 1] - breaks[p]);
      const glm::dvec3 q = ctrl[p * n + j] - fa;
      const double s = len2 > 0.0 ? std::clamp(glm::dot(q, chord) / len2, 0.0, 1.0) : 0.0;
      const double e = glm::length(q - s * chord);  // distance from the chord segment F(a)F(b)
      if (e > best.bound) best = {e, xi};
    }
  return best;
}

double midpoint_measure(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb,
                        const glm::dvec3& fa, const glm::dvec3& fb) {
  return glm::length(F.eval(0.5 * (pa + pb)) - 0.5 * (fa + fb));
}

template <class Fn>
void parallel_each(std::size_t n, Fn&& fn) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
  });
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}

void validate(const TriMesh& rest, const FfdBinding& binding, const RefineOptions& o) {
  const std::size_t nv = rest.positions.size();
  if (binding.params.size() != nv)
    throw std::invalid_argument("refine: binding has " + std::to_string(binding.params.size()) + " parameters for " +
                                std::to_string(nv) + " vertices");
  if (!rest.normals.empty() && rest.normals.size() != nv)
    throw std::invalid_argument("refine: normals count differs from vertex count");
  if (!rest.uvs.empty() && rest.uvs.size() != nv)
    throw std::invalid_argument("refine: uv count differs from vertex count");
  for (const glm::uvec3& t : rest.triangles)
    if (t.x >= nv || t.y >= nv || t.z >= nv) throw std::invalid_argument("refine: triangle index out of range");
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
    throw std::invalid_argument("refine: tolerance must be finite and > 0");
  if (o.max_iterations < 0) throw std::invalid_argument("refine: max_iterations must be >= 0");
  if (o.max_triangles < rest.triangles.size())
    throw std::invalid_argument("refine: max_triangles is below the mesh's triangle count");
  if (!(o.min_split > 0.0 && o.min_split <= 0.5)) throw std::invalid_argument("refine: min_split must be in (0, 0.5]");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(o.param_offset[a])) throw std::invalid_argument("refine: parameter offset is not finite");
  if (o.criterion == RefineCriterion::Best && o.error != RefineError::bound)
    throw std::invalid_argument(
        "refine: criterion 'best' chooses each triangle's split by its certified bound; use it "
        "with error 'bound'");
}

// A triangle's split in certified refinement: which of its edges (bit k: edge v_k → v_{k+1}) and at which points.
// The split of the parameter triangle p[0..2] (bound over tolerance) whose children are expected to need the fewest
// triangles in the end: a triangle with bound β needs about max(1, β/δ) triangles (bounds scale with the square of the
// size, triangle counts with its inverse), so the 1 → 4 split at the edge midpoints (the seed's RefineTriangle) and the
// bisection of the longest edge at its midpoint (Rivara: no slivers, bounds halve instead of quartering) are scored
// by the sum over their children. Returns the edges to split as bits (edge k = v_k → v_{k+1}); an edge that cannot be
// split (degenerate: splittable[k] false) rules out the candidates that need it (0: none is possible).
unsigned char choose_split(const SecondDerivativeBounds& bounds, const glm::dvec3 p[3], const bool splittable[3],
                           double tolerance) {
  auto cost = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double beta = triangle_error_bound(bounds, a, b, c);
    return std::max(1.0, std::min(beta / tolerance, 1e12));
  };
  glm::dvec3 mid[3];
  for (int k = 0; k < 3; ++k) mid[k] = 0.5 * (p[k] + p[(k + 1) % 3]);
  unsigned char best = 0;
  double best_cost = INFINITY;
  if (splittable[0] && splittable[1] && splittable[2]) {
    best_cost = cost(p[0], mid[0], mid[2]) + cost(mid[0], p[1], mid[1]) + cost(mid[2], mid[1], p[2]) +
                cost(mid[0], mid[1], mid[2]);
    best = 7;
  }
  int longest = 0;
  for (int k = 1; k < 3; ++k)
    if (glm::length(p[(k + 1) % 3] - p[k]) > glm::length(p[(longest + 1) % 3] - p[longest])) longest = k;
  if (splittable[longest]) {
    const glm::dvec3& opposite = p[(longest + 2) % 3];
    const double c2 = cost(p[longest], mid[longest], opposite) + cost(mid[longest], p[(longest + 1) % 3], opposite);
    if (c2 < best_cost) best = static_cast<unsigned char>(1u << longest);
  }
  return best;
}

}  // namespace

RefineCriterion parse_refine_criterion(const std::string& name) {
  if (name == "midpoint") return RefineCriterion::Midpoint;
  if (name == "greville") return RefineCriterion::Greville;
  if (name == "best") return RefineCriterion::Best;
  throw std::invalid_argument("unknown refinement criterion '" + name + "' (valid: midpoint, greville, best)");
}

const char* refine_criterion_name(RefineCriterion c) { return enum_name(c, {"midpoint", "greville", "best"}); }

double ffd_edge_midpoint_error(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb) {
  return midpoint_measure(F, pa, pb, F.eval(pa), F.eval(pb));
}

EdgeGreville ffd_edge_greville(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb) {
  const BezierInterp bi(composed_degree(F));
  return greville_measure(F, bi, pa, pb, F.eval(pa), F.eval(pb));
}

void ffd_edge_bezier(const TrivariateBSpline<glm::dvec3>& F, const glm::dvec3& pa, const glm::dvec3& pb,
                     std::vector<double>& breaks, std::vector<glm::dvec3>& ctrl, int& degree) {
  const BezierInterp bi(composed_degree(F));
  degree = bi.degree;
  bezier_pieces(F, bi, pa, pb, breaks, ctrl);
}

namespace {

// Position ids: vertices at bit-identical positions share an id (creases stored twice are one edge). `count` gets
// the number of ids.
std::vector<std::uint32_t> position_ids(const std::vector<glm::dvec3>& positions, std::uint32_t& count) {
  std::vector<std::uint32_t> pid(positions.size());
  std::uint32_t next_pid = 0;
  std::vector<std::uint32_t> order(positions.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const glm::dvec3 &p = positions[a], &q = positions[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && positions[order[i]] != positions[order[i - 1]]) ++next_pid;
    pid[order[i]] = next_pid;
  }
  if (!order.empty()) ++next_pid;
  count = next_pid;
  return pid;
}

// Adds one vertex per marked edge (position, parameters, normal, uv interpolated at split_t from the end with the
// lower position id) and returns, per triangle corner edge (#F × 3), the vertex splitting it or kNone.
std::vector<std::uint32_t> add_split_vertices(TriMesh& m, std::vector<glm::dvec3>& params,
                                              std::vector<std::uint32_t>& pid,
                                              const std::vector<std::uint32_t>& tri_pedge,
                                              const std::vector<unsigned char>& marked,
                                              const std::vector<double>& split_t,
                                              const std::vector<std::uint32_t>& pedge_pid, bool has_n, bool has_uv) {
  std::vector<std::uint32_t> tri_split(m.triangles.size() * 3, kNone);
  std::unordered_map<std::uint64_t, std::uint32_t> split_vertex;
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t pe = tri_pedge[f * 3 + k];
      if (pe == kNone || !marked[pe]) continue;
      std::uint32_t u = m.triangles[f][k], v = m.triangles[f][(k + 1) % 3];
      if (pid[u] > pid[v]) std::swap(u, v);
      const auto [it, fresh] = split_vertex.try_emplace(edge_key(u, v), std::uint32_t(m.positions.size()));
      if (fresh) {
        const double t = split_t[pe];
        m.positions.push_back(m.positions[u] + t * (m.positions[v] - m.positions[u]));
        params.push_back(params[u] + t * (params[v] - params[u]));
        if (has_n) {
          const glm::dvec3 n = m.normals[u] + t * (m.normals[v] - m.normals[u]);
          const double len = glm::length(n);
          m.normals.push_back(len > 0.0 ? n / len : m.normals[u]);
        }
        if (has_uv) m.uvs.push_back(m.uvs[u] + t * (m.uvs[v] - m.uvs[u]));
        pid.push_back(pedge_pid[pe]);
      }
      tri_split[f * 3 + k] = it->second;
    }
  return tri_split;
}

// Replaces each triangle by its pieces (1, 2, 3 split edges → 2, 3, 4 triangles, winding kept; with two split edges
// the quad is cut along its shorter deformed diagonal). Each piece keeps its triangle's face_material slot.
void split_faces(TriMesh& m, const std::vector<std::uint32_t>& tri_split, const std::vector<glm::dvec3>& fpos,
                 std::size_t next_tris) {
  std::vector<glm::uvec3> tris;
  tris.reserve(next_tris);
  std::vector<MaterialSlot> mats;  // face_material of the pieces: each keeps its triangle's slot
  if (!m.face_material.empty()) mats.reserve(next_tris);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    if (!m.face_material.empty() && f > 0) mats.resize(tris.size(), m.face_material[f - 1]);
    const glm::uvec3 v = m.triangles[f];
    const std::uint32_t* s = &tri_split[f * 3];
    const int count = (s[0] != kNone) + (s[1] != kNone) + (s[2] != kNone);
    if (count == 0) {
      tris.push_back(v);
    } else if (count == 1) {
      const int k = s[0] != kNone ? 0 : (s[1] != kNone ? 1 : 2);
      const std::uint32_t w0 = v[k], w1 = v[(k + 1) % 3], w2 = v[(k + 2) % 3], mid = s[k];
      tris.push_back({w0, mid, w2});
      tris.push_back({mid, w1, w2});
    } else if (count == 2) {
      const int k = s[0] == kNone ? 0 : (s[1] == kNone ? 1 : 2);  // the unsplit edge
      const int r = (k + 1) % 3;
      const std::uint32_t w0 = v[r], w1 = v[(r + 1) % 3], w2 = v[(r + 2) % 3];
      const std::uint32_t m0 = s[r], m1 = s[(r + 1) % 3];
      tris.push_back({m0, w1, m1});
      const double d_a = glm::dot(fpos[w0] - fpos[m1], fpos[w0] - fpos[m1]);
      const double d_b = glm::dot(fpos[m0] - fpos[w2], fpos[m0] - fpos[w2]);
      if (d_a <= d_b) {
        tris.push_back({w0, m0, m1});
        tris.push_back({w0, m1, w2});
      } else {
        tris.push_back({w0, m0, w2});
        tris.push_back({m0, m1, w2});
      }
    } else {
      tris.push_back({v[0], s[0], s[2]});
      tris.push_back({s[0], v[1], s[1]});
      tris.push_back({s[2], s[1], v[2]});
      tris.push_back({s[0], s[1], s[2]});
    }
  }
  if (!m.face_material.empty()) {
    mats.resize(tris.size(), m.face_material.back());
    m.face_material = std::move(mats);
  }
  m.triangles = std::move(tris);
}

// One refinement in progress: the mesh and its parameters, position ids, deformed positions, and the unique
// position edges of the current round with their marks.
class Refinement {
 public:
  Refinement(const TriMesh& rest, const FfdBinding& binding, const RefineOptions& o, RefineResult& res)
      : o_(o), F_(binding.lattice), bi_(composed_degree(F_)), res_(res), m_(res.mesh), params_(res.params) {
    m_ = rest;
    params_ = binding.params;
    has_n_ = !m_.normals.empty();
    has_uv_ = !m_.uvs.empty();
    // Position ids: vertices at bit-identical positions share an id (creases stored twice are one edge).
    pid_ = position_ids(m_.positions, next_pid_);
    if (o.error == RefineError::bound) second_.emplace(F_);
    evaluate_from(0);
  }

  // One round: the edges to split marked (false: none, converged) and, unless a budget stops it (stats say which),
  // split. Returns whether another round may follow.
  bool round() {
    collect_edges();
    split_t_.assign(pedges_.size(), 0.5);
    marked_.assign(pedges_.size(), 0);
    if (second_ && o_.criterion != RefineCriterion::Best)
      mark_triangles_over_tolerance();
    else if (second_)
      mark_chosen_splits();
    measure_edges();
    std::size_t any = 0;
    for (unsigned char c : marked_) any += c;
    if (any == 0) return false;
    const std::size_t next_tris = triangles_after_split();
    RefineStats& st = res_.stats;
    if (st.iterations >= o_.max_iterations || next_tris > o_.max_triangles) {
      st.stopped_by = st.iterations >= o_.max_iterations ? "max_iterations" : "max_triangles";
      st.stopped_by_budget = true;
      return false;
    }
    split(next_tris);
    ++st.iterations;
    return true;
  }

  // Final measures on the edges as they are now (after the last applied round).
  void measure_result() {
    collect_edges();
    std::vector<double> mid_err(pedges_.size()), bound(pedges_.size());
    parallel_each(pedges_.size(), [&](std::size_t i) {
      const PEdge e = pedges_[i];
      const auto [pa, pb] = ends(e);
      mid_err[i] = midpoint_measure(F_, pa, pb, fpos_[e.a], fpos_[e.b]);
      bound[i] = greville_measure(F_, bi_, pa, pb, fpos_[e.a], fpos_[e.b]).bound;
    });
    RefineStats& st = res_.stats;
    for (std::size_t i = 0; i < pedges_.size(); ++i) {
      st.max_midpoint_error = std::max(st.max_midpoint_error, mid_err[i]);
      st.max_deviation_bound = std::max(st.max_deviation_bound, bound[i]);
    }
    if (second_) {
      bound_triangles();
      for (double b : tri_bound_) st.max_triangle_bound = std::max(st.max_triangle_bound, b);
    }
  }

 private:
  struct PEdge {
    std::uint32_t a, b;  // representative ends, ordered by position id
  };

  void evaluate_from(std::size_t first) {
    fpos_.resize(m_.positions.size());
    parallel_each(m_.positions.size() - first,
                  [&](std::size_t i) { fpos_[first + i] = F_.eval(params_[first + i] + o_.param_offset); });
  }

  // Unique position edges of the current mesh, in triangle order.
  void collect_edges() {
    pedges_.clear();
    tri_pedge_.assign(m_.triangles.size() * 3, kNone);
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(m_.triangles.size() * 2);
    for (std::size_t f = 0; f < m_.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t u = m_.triangles[f][k], v = m_.triangles[f][(k + 1) % 3];
        if (pid_[u] == pid_[v]) continue;  // degenerate edge: never split
        if (pid_[u] > pid_[v]) std::swap(u, v);
        const auto [it, fresh] = index.try_emplace(edge_key(pid_[u], pid_[v]), std::uint32_t(pedges_.size()));
        if (fresh) pedges_.push_back({u, v});
        tri_pedge_[f * 3 + k] = it->second;
      }
  }

  std::pair<glm::dvec3, glm::dvec3> ends(const PEdge& e) const {
    return {params_[e.a] + o_.param_offset, params_[e.b] + o_.param_offset};
  }

  void bound_triangles() {
    tri_bound_.resize(m_.triangles.size());
    parallel_each(m_.triangles.size(), [&](std::size_t f) {
      const glm::uvec3 t = m_.triangles[f];
      tri_bound_[f] = triangle_error_bound(*second_, params_[t.x] + o_.param_offset, params_[t.y] + o_.param_offset,
                                           params_[t.z] + o_.param_offset);
    });
  }

  // Every edge of a triangle over tolerance.
  void mark_triangles_over_tolerance() {
    bound_triangles();
    for (std::size_t f = 0; f < m_.triangles.size(); ++f)
      if (!(tri_bound_[f] <= o_.tolerance))
        for (int k = 0; k < 3; ++k)
          if (tri_pedge_[f * 3 + k] != kNone) marked_[tri_pedge_[f * 3 + k]] = 1;
  }

  // Each triangle over tolerance chooses its split (choose_split) at edge midpoints; the edges any of them wants are
  // split, the rest of the mesh follows conformingly.
  void mark_chosen_splits() {
    bound_triangles();
    std::vector<std::uint32_t> over;
    for (std::size_t f = 0; f < m_.triangles.size(); ++f)
      if (!(tri_bound_[f] <= o_.tolerance)) over.push_back(static_cast<std::uint32_t>(f));
    std::vector<unsigned char> choice(over.size());
    parallel_each(over.size(), [&](std::size_t j) {
      const std::size_t f = over[j];
      glm::dvec3 p[3];
      bool splittable[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = params_[m_.triangles[f][k]] + o_.param_offset;
        splittable[k] = tri_pedge_[f * 3 + k] != kNone;
      }
      choice[j] = choose_split(*second_, p, splittable, o_.tolerance);
    });
    for (std::size_t j = 0; j < over.size(); ++j)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t pe = tri_pedge_[over[j] * 3 + k];
        if ((choice[j] >> k & 1u) && pe != kNone) marked_[pe] = 1;
      }
  }

  // The edge measures: without certified bounds they mark the edges (midpoint or Greville criterion); with them only
  // the Greville criterion places the split parameter of the marked edges.
  void measure_edges() {
    parallel_each(pedges_.size(), [&](std::size_t i) {
      const PEdge e = pedges_[i];
      const auto [pa, pb] = ends(e);
      if (second_ && (!marked_[i] || o_.criterion != RefineCriterion::Greville)) return;
      if (o_.criterion == RefineCriterion::Midpoint) {
        marked_[i] = midpoint_measure(F_, pa, pb, fpos_[e.a], fpos_[e.b]) > o_.tolerance;
      } else {
        const EdgeGreville g = greville_measure(F_, bi_, pa, pb, fpos_[e.a], fpos_[e.b]);
        if (!second_) marked_[i] = g.bound > o_.tolerance;
        split_t_[i] = std::clamp(g.t, o_.min_split, 1.0 - o_.min_split);
      }
    });
  }

  std::size_t triangles_after_split() const {
    std::size_t next_tris = 0;
    for (std::size_t f = 0; f < m_.triangles.size(); ++f) {
      next_tris += 1;
      for (int k = 0; k < 3; ++k)
        if (tri_pedge_[f * 3 + k] != kNone && marked_[tri_pedge_[f * 3 + k]]) ++next_tris;
    }
    return next_tris;
  }

  // New vertices: one per marked (vertex, vertex) edge, interpolated from the lower position id's end; then the faces.
  void split(std::size_t next_tris) {
    std::vector<std::uint32_t> pedge_pid(pedges_.size(), kNone);
    for (std::size_t i = 0; i < pedges_.size(); ++i)
      if (marked_[i]) pedge_pid[i] = next_pid_++;
    const std::size_t first_new = m_.positions.size();
    const std::vector<std::uint32_t> tri_split =
        add_split_vertices(m_, params_, pid_, tri_pedge_, marked_, split_t_, pedge_pid, has_n_, has_uv_);
    evaluate_from(first_new);
    split_faces(m_, tri_split, fpos_, next_tris);
  }

  const RefineOptions& o_;
  const TrivariateBSpline<glm::dvec3>& F_;
  const BezierInterp bi_;
  RefineResult& res_;
  TriMesh& m_;
  std::vector<glm::dvec3>& params_;
  bool has_n_ = false, has_uv_ = false;
  std::uint32_t next_pid_ = 0;
  std::vector<std::uint32_t> pid_;
  std::vector<glm::dvec3> fpos_;
  std::vector<PEdge> pedges_;
  std::vector<std::uint32_t> tri_pedge_;
  std::optional<SecondDerivativeBounds> second_;
  std::vector<double> tri_bound_, split_t_;
  std::vector<unsigned char> marked_;
};

}  // namespace

RefineResult refine_for_ffd(const TriMesh& rest, const FfdBinding& binding, const RefineOptions& o) {
  validate(rest, binding, o);
  RefineResult res;
  res.stats.triangles_before = rest.triangles.size();
  res.stats.vertices_before = rest.positions.size();
  res.stats.stopped_by = "converged";
  Refinement refinement(rest, binding, o, res);
  while (refinement.round()) {
  }
  refinement.measure_result();
  res.stats.triangles_after = res.mesh.triangles.size();
  res.stats.vertices_after = res.mesh.positions.size();
  return res;
}

}  // namespace trispline::core
