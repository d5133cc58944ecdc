// cpu_fast gather kernel: per vertex, basis functions per axis from the FfdPackedLattice tables and a tensor
// contraction over gathered control points (float). Used when a lattice's cell tables would be too big
// (FfdFastEvaluator::kMaxCellTableFloats). Baseline ISA, orders 2..4 as templates.
#include <cmath>

#include "core/ffd/ffd_fast_kernel.h"
#include "core/ffd/ffd_fast_locate.h"
#include "core/ffd/ffd_packed.h"

namespace trispline::core::ffd_fast_detail {

AxisTable axis_table(const FfdPackedAxis& a) {
  AxisTable t;
  t.order = a.order;
  t.span_count = a.span_count();
  t.periodic = a.periodic;
  t.uniform = a.uniform_spans;
  t.domain_min = a.domain_min;
  t.domain_max = a.domain_max;
  t.inv_uniform_len = a.inv_uniform_len;
  t.span_begin = a.span_begin.data();
  t.inv_span_len = a.inv_span_len.data();
  return t;
}

namespace {

// Basis values N[r], derivatives dN[r] (per unit parameter) and control indices idx[r] (wrapped) at t.
template <int O>
inline void axis_basis(const FfdPackedAxis& a, const AxisTable& t_, float t, float* N, float* dN, int* idx) {
  float x;
  const int s = locate_span(t_, t, &x);
  const float* c = &a.coef[static_cast<std::size_t>(s) * O * O];
  for (int r = 0; r < O; ++r) {
    float v = c[(O - 1) * O + r], d = 0.0f;
    for (int k = O - 2; k >= 0; --k) {
      d = d * x + v;
      v = v * x + c[k * O + r];
    }
    N[r] = v;
    dN[r] = d * a.inv_span_len[s];
    const int i = a.first_index[s] + r;
    idx[r] = a.periodic ? i % a.count : i;
  }
}

template <int OU, int OV, int OW, bool kNormals>
void gather(const GatherInput& in, const Outputs& out, std::size_t begin, std::size_t end) {
  const FfdPackedLattice& L = *in.lattice;
  const AxisTable tu = axis_table(L.axes[0]), tv = axis_table(L.axes[1]), tw = axis_table(L.axes[2]);
  const std::size_t l = static_cast<std::size_t>(L.axes[0].count);
  const std::size_t lm = l * static_cast<std::size_t>(L.axes[1].count);
  const float* P = L.control_points.data();
  const glm::mat3 A = L.embedding_linear;
  for (std::size_t v = begin; v < end; ++v) {
    float Nu[OU], Nv[OV], Nw[OW], dNu[OU], dNv[OV], dNw[OW];
    int iu[OU], iv[OV], iw[OW];
    axis_basis<OU>(L.axes[0], tu, in.params[3 * v + 0] + in.offset[0], Nu, dNu, iu);
    axis_basis<OV>(L.axes[1], tv, in.params[3 * v + 1] + in.offset[1], Nv, dNv, iv);
    axis_basis<OW>(L.axes[2], tw, in.params[3 * v + 2] + in.offset[2], Nw, dNw, iw);
    // Sums over P − P_ref, P_ref = the first control point of the support: identical in exact arithmetic (Σ N = 1,
    // Σ dN = 0), but float rounding then scales with the local control spacing, not with |P| — without it the
    // derivative sums cancel badly on lattices with many spans (dN ~ #spans).
    const float* ref = P + 4 * (static_cast<std::size_t>(iu[0]) + l * static_cast<std::size_t>(iv[0]) +
                                lm * static_cast<std::size_t>(iw[0]));
    const glm::vec3 pref(ref[0], ref[1], ref[2]);
    glm::vec3 val(0.0f), du(0.0f), dv(0.0f), dw(0.0f);
    for (int k = 0; k < OW; ++k) {
      glm::vec3 vj(0.0f), duj(0.0f), dvj(0.0f);
      for (int j = 0; j < OV; ++j) {
        const float* row = P + 4 * (l * static_cast<std::size_t>(iv[j]) + lm * static_cast<std::size_t>(iw[k]));
        glm::vec3 s(0.0f), su(0.0f);
        for (int i = 0; i < OU; ++i) {
          const float* q = row + 4 * iu[i];
          const glm::vec3 p = glm::vec3(q[0], q[1], q[2]) - pref;
          s += Nu[i] * p;
          if constexpr (kNormals) su += dNu[i] * p;
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
    val += pref;
    out.positions[3 * v + 0] = val.x;
    out.positions[3 * v + 1] = val.y;
    out.positions[3 * v + 2] = val.z;
    if constexpr (kNormals) {
      const glm::mat3 M = glm::mat3(du, dv, dw) * A;
      const glm::vec3 n(in.normals[3 * v], in.normals[3 * v + 1], in.normals[3 * v + 2]);
      const glm::vec3 m = n.x * glm::cross(M[1], M[2]) + n.y * glm::cross(M[2], M[0]) + n.z * glm::cross(M[0], M[1]);
      const float len2 = glm::dot(m, m);
      const glm::vec3 r = (len2 > 0.0f && std::isfinite(len2)) ? m / std::sqrt(len2) : n;
      out.normals[3 * v + 0] = r.x;
      out.normals[3 * v + 1] = r.y;
      out.normals[3 * v + 2] = r.z;
    }
  }
}

using GatherFn = void (*)(const GatherInput&, const Outputs&, std::size_t, std::size_t);

template <int OU, int OV, int OW>
GatherFn pick3(bool n) {
  return n ? &gather<OU, OV, OW, true> : &gather<OU, OV, OW, false>;
}
template <int OU, int OV>
GatherFn pick2(int ow, bool n) {
  return ow == 2 ? pick3<OU, OV, 2>(n) : ow == 3 ? pick3<OU, OV, 3>(n) : pick3<OU, OV, 4>(n);
}
template <int OU>
GatherFn pick1(int ov, int ow, bool n) {
  return ov == 2 ? pick2<OU, 2>(ow, n) : ov == 3 ? pick2<OU, 3>(ow, n) : pick2<OU, 4>(ow, n);
}

}  // namespace

void gather_evaluate(const GatherInput& in, const Outputs& out, std::size_t begin, std::size_t end) {
  const int ou = in.lattice->axes[0].order, ov = in.lattice->axes[1].order, ow = in.lattice->axes[2].order;
  const bool n = out.normals != nullptr;
  const GatherFn fn = ou == 2 ? pick1<2>(ov, ow, n) : ou == 3 ? pick1<3>(ov, ow, n) : pick1<4>(ov, ow, n);
  fn(in, out, begin, end);
}

}  // namespace trispline::core::ffd_fast_detail
