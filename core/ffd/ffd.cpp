// Reference FFD (double precision): embedding, evaluation with exact normals, mesh deformation. See ffd.h.
#include "core/ffd/ffd.h"

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

// Non-zero basis functions (and optionally first derivatives) of one axis at one parameter. n(r) / dn(r) for
// r in [0, order); idx(r) = control index of basis r along the axis: first + r, wrapped mod period on a periodic
// axis (`contiguous` is false only there).
struct AxisBasis {
  const KnotVector* kv = nullptr;
  int order = 0;
  int period = 0;
  bool contiguous = true;
  std::size_t first = 0;
  std::vector<double> storage;  // N | dN
  std::vector<std::size_t> index;
  double* N = nullptr;
  double* dN = nullptr;
  std::size_t* idx = nullptr;

  // Span search table (non-periodic axes): bucket b of the domain → the span at its lower end; find() then walks
  // at most a few knots, instead of a binary search per point (its branches mispredict on scattered points).
  const double* U = nullptr;
  int last_span = 0;  // n − 1
  double lo = 0.0, hi = 0.0, inv_width = 0.0;
  std::vector<int> bucket_span;

  explicit AxisBasis(const KnotVector& k)
      : kv(&k),
        order(k.order()),
        period(k.period()),
        contiguous(k.period() == 0),
        storage(2 * static_cast<std::size_t>(k.order())),
        index(k.order()) {
    N = storage.data();
    dN = N + order;
    idx = index.data();
    U = k.knots().data();
    last_span = k.control_count() - 1;
    lo = k.domain_min();
    hi = k.domain_max();
    if (contiguous) {
      const int buckets = 4 * (k.control_count() - k.order() + 1);
      inv_width = buckets / (hi - lo);
      bucket_span.resize(static_cast<std::size_t>(buckets));
      for (int b = 0; b < buckets; ++b) bucket_span[b] = k.find_span(lo + (hi - lo) * b / buckets);
    }
  }
  AxisBasis(const AxisBasis&) = delete;
  AxisBasis& operator=(const AxisBasis&) = delete;

  // KnotVector::find_span(t) for t already clamped to [lo, hi] (the same span: knots[s] ≤ t < knots[s+1], the last
  // non-empty span at hi), from the table.
  int find(double t) const {
    if (!contiguous || !(t < hi)) return kv->find_span(t);
    const double x = (t - lo) * inv_width;
    int s = bucket_span[std::min(static_cast<std::size_t>(x > 0.0 ? x : 0.0), bucket_span.size() - 1)];
    while (s > order - 1 && U[s] > t) --s;  // the bucket index may round one too high
    while (s < last_span && U[s + 1] <= t) ++s;
    return s;
  }

  void eval(double t, bool with_derivative) {
    t = kv->wrap_or_clamp(t);  // clamped to the domain, wrapped on a periodic axis
    const int span = find(t);
    const int f = span - order + 1;
    first = static_cast<std::size_t>(f);
    if (!contiguous)
      for (int r = 0; r < order; ++r) idx[r] = static_cast<std::size_t>((f + r) % period);
    if (with_derivative)
      basis_first_derivatives(*kv, span, t, N, dN);  // bit-identical to basis_derivatives(…, 1, ·)
    else
      basis_functions(*kv, span, t, N);
  }
  std::size_t at(int r) const { return contiguous ? first + static_cast<std::size_t>(r) : idx[r]; }
  double n(int r) const { return N[r]; }
  double dn(int r) const { return dN[r]; }
};

bool inside_unit_cube(const glm::dvec3& p) {
  return p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0 && p.z >= 0.0 && p.z <= 1.0;
}

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
        const glm::dvec3* row = cps + l * bv.at(j) + lm * bw.at(k);
        glm::dvec3 s(0.0);
        if (bu.contiguous) {
          const glm::dvec3* r0 = row + bu.first;
          for (int i = 0; i < bu.order; ++i) s += bu.N[i] * r0[i];
        } else {
          for (int i = 0; i < bu.order; ++i) s += bu.N[i] * row[bu.idx[i]];
        }
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
    const double* Nu = bu.N;
    const double* dNu = bu.dN;
    for (int k = 0; k < bw.order; ++k) {
      glm::dvec3 v_j(0.0), du_j(0.0), dv_j(0.0);
      for (int j = 0; j < bv.order; ++j) {
        const glm::dvec3* row = cps + l * bv.at(j) + lm * bw.at(k);
        glm::dvec3 s(0.0), su(0.0);
        if (bu.contiguous) {
          const glm::dvec3* r0 = row + bu.first;
          for (int i = 0; i < bu.order; ++i) {
            s += Nu[i] * r0[i];
            su += dNu[i] * r0[i];
          }
        } else {
          for (int i = 0; i < bu.order; ++i) {
            s += Nu[i] * row[bu.idx[i]];
            su += dNu[i] * row[bu.idx[i]];
          }
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

// The same evaluation for lattices of one order O on all three axes, none periodic (the common case: quadratic or
// cubic lattices): fixed-size arrays and loops the compiler unrolls. Every operation is the one Evaluator does, in
// the same order (basis: A2.2 / A2.3 with k = 1 as in basis_functions / basis_first_derivatives; sums over k, j, i),
// so the results are bit-identical to Evaluator's; only the bookkeeping is gone.
template <int O>
struct FixedAxis {
  const AxisBasis& table;  // span search (AxisBasis::find) and domain
  double N[O], dN[O];
  std::size_t first = 0;

  explicit FixedAxis(const AxisBasis& t) : table(t) {}

  template <bool kDerivative>
  void eval(double t) {
    t = t < table.lo ? table.lo : (t > table.hi ? table.hi : t);  // KnotVector::wrap_or_clamp, non-periodic
    const int span = table.find(t);
    first = static_cast<std::size_t>(span - O + 1);
    constexpr int p = O - 1;
    const double* U = table.U;
    if constexpr (p == 0) {
      N[0] = 1.0;
      dN[0] = 0.0;
      return;
    } else {
      double left[O], right[O], prev[O], diff[O];
      N[0] = 1.0;
      for (int j = 1; j <= p; ++j) {
        left[j] = t - U[span + 1 - j];
        right[j] = U[span + j] - t;
        if (kDerivative && j == p)
          for (int r = 0; r < p; ++r) prev[r] = N[r];
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
          const double d = right[r + 1] + left[j - r];
          if (kDerivative && j == p) diff[r] = d;
          const double temp = N[r] / d;
          N[r] = saved + right[r + 1] * temp;
          saved = left[j - r] * temp;
        }
        N[j] = saved;
      }
      if constexpr (kDerivative) detail::first_derivative_row(p, prev, diff, dN);
    }
  }
};

template <int O>
struct FixedEvaluator {
  Evaluator generic;  // owns the span tables
  FixedAxis<O> bu, bv, bw;

  explicit FixedEvaluator(const TrivariateBSpline<glm::dvec3>& f)
      : generic(f), bu(generic.bu), bv(generic.bv), bw(generic.bw) {}

  glm::dvec3 value(const glm::dvec3& p) {
    bu.template eval<false>(p.x);
    bv.template eval<false>(p.y);
    bw.template eval<false>(p.z);
    const glm::dvec3* cps = generic.cps;
    const std::size_t l = generic.l, lm = generic.lm;
    glm::dvec3 acc(0.0);
    for (int k = 0; k < O; ++k) {
      glm::dvec3 acc_j(0.0);
      for (int j = 0; j < O; ++j) {
        const glm::dvec3* r0 = cps + l * (bv.first + j) + lm * (bw.first + k) + bu.first;
        glm::dvec3 s(0.0);
        for (int i = 0; i < O; ++i) s += bu.N[i] * r0[i];
        acc_j += bv.N[j] * s;
      }
      acc += bw.N[k] * acc_j;
    }
    return acc;
  }

  glm::dvec3 value_jacobian(const glm::dvec3& p, glm::dmat3& J) {
    bu.template eval<true>(p.x);
    bv.template eval<true>(p.y);
    bw.template eval<true>(p.z);
    const glm::dvec3* cps = generic.cps;
    const std::size_t l = generic.l, lm = generic.lm;
    glm::dvec3 val(0.0), du(0.0), dv(0.0), dw(0.0);
    for (int k = 0; k < O; ++k) {
      glm::dvec3 v_j(0.0), du_j(0.0), dv_j(0.0);
      for (int j = 0; j < O; ++j) {
        const glm::dvec3* r0 = cps + l * (bv.first + j) + lm * (bw.first + k) + bu.first;
        glm::dvec3 s(0.0), su(0.0);
        for (int i = 0; i < O; ++i) {
          s += bu.N[i] * r0[i];
          su += bu.dN[i] * r0[i];
        }
        v_j += bv.N[j] * s;
        du_j += bv.N[j] * su;
        dv_j += bv.dN[j] * s;
      }
      val += bw.N[k] * v_j;
      du += bw.N[k] * du_j;
      dv += bw.N[k] * dv_j;
      dw += bw.dN[k] * v_j;
    }
    J = glm::dmat3(du, dv, dw);
    return val;
  }
};

// Runs body(evaluator, range) over [0, n) in parallel chunks, with the fixed-order evaluator when the lattice has one
// order ≤ 4 on all axes and no periodic axis, the generic one otherwise (same results either way).
template <class Body>
void for_each_chunk(const TrivariateBSpline<glm::dvec3>& F, std::size_t n, const Body& body) {
  const int o = F.knots(0).order();
  const bool uniform = F.knots(1).order() == o && F.knots(2).order() == o && F.knots(0).period() == 0 &&
                       F.knots(1).period() == 0 && F.knots(2).period() == 0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    if (uniform && o == 2) {
      FixedEvaluator<2> ev(F);
      body(ev, r);
    } else if (uniform && o == 3) {
      FixedEvaluator<3> ev(F);
      body(ev, r);
    } else if (uniform && o == 4) {
      FixedEvaluator<4> ev(F);
      body(ev, r);
    } else {
      Evaluator ev(F);
      body(ev, r);
    }
  });
}

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
  for_each_chunk(F, params.size(), [&](auto& ev, const tbb::blocked_range<std::size_t>& r) {
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
  for_each_chunk(F, params.size(), [&](auto& ev, const tbb::blocked_range<std::size_t>& r) {
    glm::dmat3 J;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      out_positions[i] = ev.value_jacobian(params[i], J);
      const glm::dvec3 n = cofactor(J * embedding.linear) * rest_normals[i];
      const double len = glm::length(n);
      out_normals[i] = (len > 0.0 && std::isfinite(len)) ? n / len : rest_normals[i];
    }
  });
}

void ffd_evaluate_identity_outside(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                                   std::size_t count, const glm::dvec3* params, const glm::dvec3* rest_normals,
                                   glm::dvec3* out_positions, glm::dvec3* out_normals) {
  const glm::dmat3 A_inv = glm::inverse(embedding.linear);
  for_each_chunk(F, count, [&](auto& ev, const tbb::blocked_range<std::size_t>& r) {
    glm::dmat3 J;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const glm::dvec3& p = params[i];
      if (!inside_unit_cube(p)) {
        out_positions[i] = A_inv * (p - embedding.offset);
        if (rest_normals) out_normals[i] = rest_normals[i];
      } else if (rest_normals) {
        out_positions[i] = ev.value_jacobian(p, J);
        const glm::dvec3 n = cofactor(J * embedding.linear) * rest_normals[i];
        const double len = glm::length(n);
        out_normals[i] = (len > 0.0 && std::isfinite(len)) ? n / len : rest_normals[i];
      } else {
        out_positions[i] = ev.value(p);
      }
    }
  });
}

std::size_t ffd_evaluate_identity_outside(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding,
                                          const std::vector<glm::dvec3>& params,
                                          const std::vector<glm::dvec3>& rest_normals,
                                          std::vector<glm::dvec3>& out_positions,
                                          std::vector<glm::dvec3>& out_normals) {
  const bool with_normals = !rest_normals.empty();
  if (with_normals && rest_normals.size() != params.size())
    throw std::invalid_argument("ffd_evaluate_identity_outside: " + std::to_string(rest_normals.size()) +
                                " normals for " + std::to_string(params.size()) + " parameters");
  out_positions.resize(params.size());
  if (with_normals) out_normals.resize(params.size());
  ffd_evaluate_identity_outside(F, embedding, params.size(), params.data(),
                                with_normals ? rest_normals.data() : nullptr, out_positions.data(),
                                with_normals ? out_normals.data() : nullptr);
  return static_cast<std::size_t>(
      std::count_if(params.begin(), params.end(), [](const glm::dvec3& p) { return !inside_unit_cube(p); }));
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
