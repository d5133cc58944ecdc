// Reference FFD (double precision): embedding, evaluation with exact normals, mesh deformation. See ffd.h.
#include "core/deform/ffd.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/mesh/mesh_io.h"
#include "core/spline/bspline_basis.h"

namespace trispline::core {

namespace {

bool finite3(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Non-zero basis functions (and optionally first derivatives) of one axis at one parameter.
// Layout of `ders`: ders[0..order) values, ders[order..2·order) first derivatives; idx[r] = control index of basis r
// along the axis (wrapped mod period on a periodic axis).
struct AxisBasis {
  const KnotVector* kv = nullptr;
  int order = 0;
  int period = 0;
  std::vector<double> ders;
  std::vector<std::size_t> idx;

  explicit AxisBasis(const KnotVector& k)
      : kv(&k), order(k.order()), period(k.period()), ders(2 * static_cast<std::size_t>(k.order())), idx(k.order()) {}

  void eval(double t, bool with_derivative) {
    t = kv->wrap_or_clamp(t);  // clamped to the domain, wrapped on a periodic axis
    const int span = kv->find_span(t);
    const int first = span - order + 1;
    for (int r = 0; r < order; ++r) idx[r] = static_cast<std::size_t>(period > 0 ? (first + r) % period : first + r);
    if (with_derivative)
      basis_derivatives(*kv, span, t, 1, ders.data());
    else
      basis_functions(*kv, span, t, ders.data());
  }
  double n(int r) const { return ders[r]; }
  double dn(int r) const { return ders[order + r]; }
};

// Cofactor matrix columns of M = [m0 m1 m2]: cof(M) = det(M)·M^{-T} = [m1×m2, m2×m0, m0×m1]; defined for singular M.
glm::dmat3 cofactor(const glm::dmat3& m) {
  return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

// F and (optionally) its three partials at `uvw`, with a fixed summation order (k, j, i): deterministic.
struct Evaluator {
  const TrivariateBSpline<glm::dvec3>& F;
  AxisBasis bu, bv, bw;
  std::size_t l, lm;
  const glm::dvec3* cps;

  explicit Evaluator(const TrivariateBSpline<glm::dvec3>& f) : F(f), bu(f.knots(0)), bv(f.knots(1)), bw(f.knots(2)) {
    const glm::ivec3 c = f.control_counts();
    l = static_cast<std::size_t>(c.x);
    lm = l * static_cast<std::size_t>(c.y);
    cps = f.control_points().data();
  }

  glm::dvec3 value(const glm::dvec3& p) {
    bu.eval(p.x, false);
    bv.eval(p.y, false);
    bw.eval(p.z, false);
    glm::dvec3 acc(0.0);
    for (int k = 0; k < bw.order; ++k) {
      glm::dvec3 acc_j(0.0);
      for (int j = 0; j < bv.order; ++j) {
        const glm::dvec3* row = cps + l * bv.idx[j] + lm * bw.idx[k];
        glm::dvec3 s(0.0);
        for (int i = 0; i < bu.order; ++i) s += bu.n(i) * row[bu.idx[i]];
        acc_j += bv.n(j) * s;
      }
      acc += bw.n(k) * acc_j;
    }
    return acc;
  }

  // Value and Jacobian columns (∂F/∂u, ∂F/∂v, ∂F/∂w).
  glm::dvec3 value_jacobian(const glm::dvec3& p, glm::dmat3& J) {
    bu.eval(p.x, true);
    bv.eval(p.y, true);
    bw.eval(p.z, true);
    glm::dvec3 val(0.0), du(0.0), dv(0.0), dw(0.0);
    for (int k = 0; k < bw.order; ++k) {
      glm::dvec3 v_j(0.0), du_j(0.0), dv_j(0.0);
      for (int j = 0; j < bv.order; ++j) {
        const glm::dvec3* row = cps + l * bv.idx[j] + lm * bw.idx[k];
        glm::dvec3 s(0.0), su(0.0);
        for (int i = 0; i < bu.order; ++i) {
          s += bu.n(i) * row[bu.idx[i]];
          su += bu.dn(i) * row[bu.idx[i]];
        }
        v_j += bv.n(j) * s;
        du_j += bv.n(j) * su;
        dv_j += bv.dn(j) * s;
      }
      val += bw.n(k) * v_j;
      du += bw.n(k) * du_j;
      dv += bw.n(k) * dv_j;
      dw += bw.dn(k) * v_j;
    }
    J = glm::dmat3(du, dv, dw);
    return val;
  }
};

constexpr std::size_t kGrain = 1024;

}  // namespace

Embedding embed_bounding_box(const std::vector<glm::dvec3>& rest_positions, const EmbeddingAxes& axes) {
  const int a = axes.length_axis, c = axes.up_axis;
  if (a < 0 || a > 2 || c < 0 || c > 2 || a == c)
    throw std::invalid_argument("embed_bounding_box: length_axis (" + std::to_string(a) + ") and up_axis (" +
                                std::to_string(c) + ") must be distinct axes in {0,1,2}");
  if (rest_positions.empty()) throw std::invalid_argument("embed_bounding_box: no positions");
  Aabb box;
  for (const auto& p : rest_positions) {
    if (!finite3(p)) throw std::invalid_argument("embed_bounding_box: non-finite position");
    box.extend(p);
  }
  const int b = 3 - a - c;
  // (a, b, c) → (u, v, w) is a permutation; an odd one reverses orientation, compensated by flipping v.
  const bool even = (a == 0 && b == 1) || (a == 1 && b == 2) || (a == 2 && b == 0);
  const int src[3] = {a, b, c};
  Embedding e;
  e.linear = glm::dmat3(0.0);
  for (int row = 0; row < 3; ++row) {
    const int ax = src[row];
    const double ext = box.hi[ax] - box.lo[ax];
    if (!(ext > 0.0)) {  // flat extent: the whole axis maps to the middle
      e.offset[row] = 0.5;
      continue;
    }
    const double sign = (row == 1 && !even) ? -1.0 : 1.0;
    e.linear[ax][row] = sign / ext;  // glm: linear[column][row]
    e.offset[row] = sign > 0 ? -box.lo[ax] / ext : box.hi[ax] / ext;
  }
  return e;
}

std::vector<glm::dvec3> embed_points(const Embedding& embedding, const std::vector<glm::dvec3>& rest_positions) {
  std::vector<glm::dvec3> out(rest_positions.size());
  for (std::size_t i = 0; i < rest_positions.size(); ++i) out[i] = embedding.apply(rest_positions[i]);
  return out;
}

void ffd_evaluate(const TrivariateBSpline<glm::dvec3>& F, const std::vector<glm::dvec3>& params,
                  std::vector<glm::dvec3>& out_positions) {
  out_positions.resize(params.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, params.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      Evaluator ev(F);
                      for (std::size_t i = r.begin(); i != r.end(); ++i) out_positions[i] = ev.value(params[i]);
                    });
}

void ffd_evaluate(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                  const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals,
                  std::vector<glm::dvec3>& out_positions, std::vector<glm::dvec3>& out_normals) {
  if (rest_normals.size() != params.size())
    throw std::invalid_argument("ffd_evaluate: " + std::to_string(rest_normals.size()) + " normals for " +
                                std::to_string(params.size()) + " parameters");
  out_positions.resize(params.size());
  out_normals.resize(params.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, params.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      Evaluator ev(F);
                      glm::dmat3 J;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        out_positions[i] = ev.value_jacobian(params[i], J);
                        const glm::dvec3 n = cofactor(J * embedding.linear) * rest_normals[i];
                        const double len = glm::length(n);
                        out_normals[i] = (len > 0.0 && std::isfinite(len)) ? n / len : rest_normals[i];
                      }
                    });
}

TriMesh ffd_apply(const FfdBinding& binding, const TriMesh& rest_world) {
  if (binding.params.size() != rest_world.positions.size())
    throw std::invalid_argument("ffd_apply: binding has " + std::to_string(binding.params.size()) + " parameters for " +
                                std::to_string(rest_world.positions.size()) + " vertices");
  TriMesh out;
  out.triangles = rest_world.triangles;
  out.face_material = rest_world.face_material;
  out.uvs = rest_world.uvs;
  if (rest_world.normals.size() == rest_world.positions.size()) {
    ffd_evaluate(binding.lattice, binding.embedding, binding.params, rest_world.normals, out.positions, out.normals);
  } else {
    ffd_evaluate(binding.lattice, binding.params, out.positions);
    compute_vertex_normals(out);
  }
  return out;
}

}  // namespace trispline::core
