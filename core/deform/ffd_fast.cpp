// Fast single-precision FFD: per-span power-basis tables and order-templated kernels. See ffd_fast.h.
#include "core/deform/ffd_fast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace trispline::core {

FloatSoA3 FloatSoA3::from(const std::vector<glm::dvec3>& v) {
  FloatSoA3 s;
  s.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    s.x[i] = static_cast<float>(v[i].x);
    s.y[i] = static_cast<float>(v[i].y);
    s.z[i] = static_cast<float>(v[i].z);
  }
  return s;
}

std::vector<glm::dvec3> FloatSoA3::to_dvec3() const {
  std::vector<glm::dvec3> v(size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = glm::dvec3(x[i], y[i], z[i]);
  return v;
}

namespace {}  // namespace

// Private access for the kernels (keeps FfdFastLattice's data out of the public API).
struct FfdFastAccess {
  const FfdFastLattice& L;
  const SpanBasis<float>& axis(int i) const { return L.axes_[i]; }
  const float* inv_len(int i) const { return L.inv_len_[i].data(); }
  const float* cps() const { return L.cps_.data(); }
  glm::ivec3 counts() const { return L.counts_; }
  glm::dvec3 centre() const { return L.centre_; }
  const float* linear() const { return L.linear_.data(); }
  const std::optional<TrivariateBSpline<glm::dvec3>>& fallback() const { return L.fallback_; }
  const Embedding& embedding() const { return L.embedding_; }
};

namespace {

// Basis values (and d/dt) of order O at t from the span tables: O(1)/binary-search span lookup (SpanBasis::locate),
// then Horner with a compile-time order so the loops unroll. Returns the index of the first non-zero function.
template <int O, bool kDeriv>
inline int basis(const SpanBasis<float>& b, const float* inv_len, float t, float* N, float* dN) {
  float x;
  const int s = b.locate(t, &x);
  const float* c = b.coefficients(s);  // c[k·O + r]: coefficient of x^k of function r
  for (int r = 0; r < O; ++r) N[r] = c[(O - 1) * O + r];
  for (int k = O - 2; k >= 0; --k)
    for (int r = 0; r < O; ++r) N[r] = N[r] * x + c[k * O + r];
  if constexpr (kDeriv) {
    for (int r = 0; r < O; ++r) dN[r] = static_cast<float>(O - 1) * c[(O - 1) * O + r];
    for (int k = O - 2; k >= 1; --k)
      for (int r = 0; r < O; ++r) dN[r] = dN[r] * x + static_cast<float>(k) * c[k * O + r];
    for (int r = 0; r < O; ++r) dN[r] *= inv_len[s];
  }
  return b.first_index(s);
}

// Four floats in one SSE register (GCC/Clang vector extension): x, y, z and a zero pad of a control point.
using v4 = float __attribute__((vector_size(16)));
inline v4 load4(const float* p) {
  v4 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}

struct Arrays {
  const float *pu, *pv, *pw;  // params
  const float *nx, *ny, *nz;  // rest normals (may be null)
  float *ox, *oy, *oz;        // positions out
  float *mx, *my, *mz;        // normals out (may be null)
};

template <int OU, int OV, int OW, bool kNormals>
void kernel(const FfdFastAccess& L, const Arrays& a, std::size_t begin, std::size_t end) {
  const SpanBasis<float>&tu = L.axis(0), &tv = L.axis(1), &tw = L.axis(2);
  const float *iu = L.inv_len(0), *iv = L.inv_len(1), *iw = L.inv_len(2);
  const float* cps = L.cps();
  const std::size_t l = static_cast<std::size_t>(L.counts().x);
  const std::size_t lm = l * static_cast<std::size_t>(L.counts().y);
  const glm::dvec3 c = L.centre();
  const float cx = static_cast<float>(c.x), cy = static_cast<float>(c.y), cz = static_cast<float>(c.z);
  const float* A = L.linear();
  for (std::size_t idx = begin; idx < end; ++idx) {
    float Nu[OU], Nv[OV], Nw[OW], dNu[OU], dNv[OV], dNw[OW];
    const int fu = basis<OU, kNormals>(tu, iu, a.pu[idx], Nu, dNu);
    const int fv = basis<OV, kNormals>(tv, iv, a.pv[idx], Nv, dNv);
    const int fw = basis<OW, kNormals>(tw, iw, a.pw[idx], Nw, dNw);
    const float* base = cps + 4 * (static_cast<std::size_t>(fu) + l * fv + lm * fw);
    v4 val{}, du{}, dv{}, dw{};
    for (int k = 0; k < OW; ++k) {
      v4 vj{}, duj{}, dvj{};
      for (int j = 0; j < OV; ++j) {
        const float* row = base + 4 * (l * j + lm * k);
        v4 s{}, su{};
        for (int i = 0; i < OU; ++i) {
          const v4 P = load4(row + 4 * i);
          s += Nu[i] * P;
          if constexpr (kNormals) su += dNu[i] * P;
        }
        vj += Nv[j] * s;
        if constexpr (kNormals) {
          duj += Nv[j] * su;
          dvj += dNv[j] * s;
        }
      }
      val += Nw[k] * vj;
      if constexpr (kNormals) {
        du += Nw[k] * duj;
        dv += Nw[k] * dvj;
        dw += dNw[k] * vj;
      }
    }
    a.ox[idx] = val[0] + cx;
    a.oy[idx] = val[1] + cy;
    a.oz[idx] = val[2] + cz;
    if constexpr (kNormals) {
      // M = J_F · A (columns m0, m1, m2); n' = cof(M)·n = n.x (m1×m2) + n.y (m2×m0) + n.z (m0×m1).
      float m[3][3];
      for (int col = 0; col < 3; ++col)
        for (int r = 0; r < 3; ++r)
          m[col][r] = du[r] * A[3 * col + 0] + dv[r] * A[3 * col + 1] + dw[r] * A[3 * col + 2];
      auto cross = [](const float* p, const float* q, float* o) {
        o[0] = p[1] * q[2] - p[2] * q[1];
        o[1] = p[2] * q[0] - p[0] * q[2];
        o[2] = p[0] * q[1] - p[1] * q[0];
      };
      float c0[3], c1[3], c2[3];
      cross(m[1], m[2], c0);
      cross(m[2], m[0], c1);
      cross(m[0], m[1], c2);
      const float nx = a.nx[idx], ny = a.ny[idx], nz = a.nz[idx];
      const float x = nx * c0[0] + ny * c1[0] + nz * c2[0];
      const float y = nx * c0[1] + ny * c1[1] + nz * c2[1];
      const float z = nx * c0[2] + ny * c1[2] + nz * c2[2];
      const float len2 = x * x + y * y + z * z;
      if (len2 > 0.0f && std::isfinite(len2)) {
        const float inv = 1.0f / std::sqrt(len2);
        a.mx[idx] = x * inv;
        a.my[idx] = y * inv;
        a.mz[idx] = z * inv;
      } else {
        a.mx[idx] = nx;
        a.my[idx] = ny;
        a.mz[idx] = nz;
      }
    }
  }
}

using KernelFn = void (*)(const FfdFastAccess&, const Arrays&, std::size_t, std::size_t);

template <int OU, int OV, int OW>
KernelFn pick3(bool normals) {
  return normals ? &kernel<OU, OV, OW, true> : &kernel<OU, OV, OW, false>;
}
template <int OU, int OV>
KernelFn pick2(int ow, bool normals) {
  switch (ow) {
    case 2:
      return pick3<OU, OV, 2>(normals);
    case 3:
      return pick3<OU, OV, 3>(normals);
    case 4:
      return pick3<OU, OV, 4>(normals);
  }
  return nullptr;
}
template <int OU>
KernelFn pick1(int ov, int ow, bool normals) {
  switch (ov) {
    case 2:
      return pick2<OU, 2>(ow, normals);
    case 3:
      return pick2<OU, 3>(ow, normals);
    case 4:
      return pick2<OU, 4>(ow, normals);
  }
  return nullptr;
}
KernelFn pick(const glm::ivec3& o, bool normals) {
  switch (o.x) {
    case 2:
      return pick1<2>(o.y, o.z, normals);
    case 3:
      return pick1<3>(o.y, o.z, normals);
    case 4:
      return pick1<4>(o.y, o.z, normals);
  }
  return nullptr;
}

constexpr std::size_t kBlock = 2048;

void run(const FfdFastLattice& lattice, const FloatSoA3& params, const FloatSoA3* rest_normals,
         FloatSoA3& out_positions, FloatSoA3* out_normals) {
  const FfdFastAccess L{lattice};
  const std::size_t n = params.size();
  if (params.y.size() != n || params.z.size() != n)
    throw std::invalid_argument("ffd_evaluate_fast: params arrays differ in length");
  if (rest_normals && (rest_normals->x.size() != n || rest_normals->y.size() != n || rest_normals->z.size() != n))
    throw std::invalid_argument("ffd_evaluate_fast: " + std::to_string(rest_normals->size()) + " normals for " +
                                std::to_string(n) + " parameters");
  out_positions.resize(n);
  if (out_normals) out_normals->resize(n);
  if (!lattice.has_kernel()) {  // orders outside 2..4: round the double reference
    std::vector<glm::dvec3> pos, nrm;
    if (rest_normals) {
      ffd_evaluate(*L.fallback(), L.embedding(), params.to_dvec3(), rest_normals->to_dvec3(), pos, nrm);
      *out_normals = FloatSoA3::from(nrm);
    } else {
      ffd_evaluate(*L.fallback(), params.to_dvec3(), pos);
    }
    out_positions = FloatSoA3::from(pos);
    return;
  }
  const glm::ivec3 orders(L.axis(0).order(), L.axis(1).order(), L.axis(2).order());
  const KernelFn fn = pick(orders, rest_normals != nullptr);
  Arrays a{params.x.data(),        params.y.data(),        params.z.data(),        nullptr, nullptr, nullptr,
           out_positions.x.data(), out_positions.y.data(), out_positions.z.data(), nullptr, nullptr, nullptr};
  if (rest_normals) {
    a.nx = rest_normals->x.data();
    a.ny = rest_normals->y.data();
    a.nz = rest_normals->z.data();
    a.mx = out_normals->x.data();
    a.my = out_normals->y.data();
    a.mz = out_normals->z.data();
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kBlock),
                    [&](const tbb::blocked_range<std::size_t>& r) { fn(L, a, r.begin(), r.end()); });
}

}  // namespace

namespace {
const KnotVector& checked_knots(const KnotVector& kv) {
  if (kv.order() < 2)
    throw std::invalid_argument("ffd fast path: order must be >= 2 (got " + std::to_string(kv.order()) + ")");
  return kv;
}
}  // namespace

FfdFastLattice::FfdFastLattice(const TrivariateBSpline<glm::dvec3>& F, const Embedding& embedding)
    : axes_{SpanBasis<float>(checked_knots(F.knots(0))), SpanBasis<float>(checked_knots(F.knots(1))),
            SpanBasis<float>(checked_knots(F.knots(2)))},
      embedding_(embedding) {
  for (int i = 0; i < 3; ++i) {  // 1 / length of every non-empty span, in SpanBasis's slot order
    const KnotVector& kv = F.knots(i);
    for (int s = kv.order() - 1; s < kv.control_count(); ++s)
      if (kv[s + 1] != kv[s]) inv_len_[i].push_back(static_cast<float>(1.0 / (kv[s + 1] - kv[s])));
    if (static_cast<int>(inv_len_[i].size()) != axes_[i].span_count())
      throw std::logic_error("FfdFastLattice: span count differs from SpanBasis");
  }
  counts_ = F.control_counts();
  Aabb box;
  for (const auto& p : F.control_points()) box.extend(p);
  centre_ = box.center();
  cps_.resize(F.control_points().size() * 4);
  for (std::size_t i = 0; i < F.control_points().size(); ++i) {
    const glm::dvec3 p = F.control_points()[i] - centre_;
    cps_[4 * i + 0] = static_cast<float>(p.x);
    cps_[4 * i + 1] = static_cast<float>(p.y);
    cps_[4 * i + 2] = static_cast<float>(p.z);
    cps_[4 * i + 3] = 0.0f;
  }
  for (int col = 0; col < 3; ++col)
    for (int r = 0; r < 3; ++r) linear_[3 * col + r] = static_cast<float>(embedding.linear[col][r]);
  if (!has_kernel()) fallback_.emplace(F);
}

bool FfdFastLattice::has_kernel() const {
  for (const auto& a : axes_)
    if (a.order() < 2 || a.order() > 4) return false;
  return true;
}

void ffd_evaluate_fast(const FfdFastLattice& lattice, const FloatSoA3& params, FloatSoA3& out_positions) {
  run(lattice, params, nullptr, out_positions, nullptr);
}

void ffd_evaluate_fast(const FfdFastLattice& lattice, const FloatSoA3& params, const FloatSoA3& rest_normals,
                       FloatSoA3& out_positions, FloatSoA3& out_normals) {
  run(lattice, params, &rest_normals, out_positions, &out_normals);
}

}  // namespace trispline::core
