#version 430 core
// Trivariate B-spline FFD evaluation shared by ffd.comp.glsl (compute path) and mesh.vert.glsl [FFD] (vertex path,
// seed §4.2.1). Included with `#include "ffd_eval.glsl"`; the tables are core::FfdPackedLattice uploaded by
// gpu/eval/ffd_gl_lattice.cpp, and the numerics follow its header comment step by step (core/ffd/ffd_packed.h):
//   wrap (periodic) or clamp t → span slot (O(1) for uniform spans, binary search otherwise) → local x → Horner in
//   the power basis → control index first + r (mod count on a periodic axis) → tensor contraction k, j, i.
// Normals: n' ∝ cof(J·A)·n with J = [∂F/∂u ∂F/∂v ∂F/∂w], A = embedding linear part (seed §4.3); the rest normal
// where cof(J·A)·n vanishes. Positions are relative to the lattice centre until the final add.
// Defines: FFD_NORMALS to evaluate the Jacobian and normals; ORDER_U, ORDER_V, ORDER_W (2..4) specialise the orders
// at compile time (fully unrolled loops: real GPUs). Without them the orders are read from the tables at run time
// (generic variant, one program for every order combination: software renderers, where llvmpipe's JIT of each
// specialised variant costs about a second).
#ifdef ORDER_U
#define FFD_ORDER_U ORDER_U
#define FFD_ORDER_V ORDER_V
#define FFD_ORDER_W ORDER_W
#else
#define FFD_ORDER_U ffd_axes[0].order
#define FFD_ORDER_V ffd_axes[1].order
#define FFD_ORDER_W ffd_axes[2].order
#endif
#define FFD_MAX_ORDER 4

// One axis of FfdPackedLattice (mirrors gpu::detail::FfdAxisHeader, 48 bytes std430). Table fields are offsets
// into ffd_tables; first_index entries are ints stored bit-for-bit (floatBitsToInt).
struct FfdAxis {
  int order, count, periodic, uniform_spans;
  float domain_min, domain_max, inv_uniform_len;
  int span_count;
  int span_begin, inv_span_len, first_index, coef;
};
// Knot tables: change rarely (re-uploaded only when the knot vectors or orders change).
layout(std430, binding = 4) readonly buffer FfdTables {
  FfdAxis ffd_axes[3];
  float ffd_tables[];
};
// Control points (#controls × vec4, u fastest, relative to ffd_centre, world units): change on every press.
layout(std430, binding = 5) readonly buffer FfdControls {
  vec4 ffd_centre;     // xyz world units
  vec4 ffd_linear[3];  // columns of the embedding's linear part A (xyz)
  vec4 ffd_cp[];
};

// Span slot of t on axis a (t is wrapped or clamped in place).
int ffd_span(int a, inout float t) {
  if (ffd_axes[a].periodic != 0) t = t - floor(t);
  t = clamp(t, ffd_axes[a].domain_min, ffd_axes[a].domain_max);
  int S = ffd_axes[a].span_count;
  int b = ffd_axes[a].span_begin;
  int s;
  if (ffd_axes[a].uniform_spans != 0) {
    s = clamp(int(floor((t - ffd_axes[a].domain_min) * ffd_axes[a].inv_uniform_len)), 0, S - 1);
    // Rounding next to a knot can land one slot off: correct against the stored span boundaries.
    if (t < ffd_tables[b + s])
      s -= 1;
    else if (s + 1 < S && t >= ffd_tables[b + s + 1])
      s += 1;
  } else {  // last s with span_begin[s] ≤ t
    int lo = 0, hi = S - 1;
    while (lo < hi) {
      int mid = (lo + hi + 1) >> 1;
      if (ffd_tables[b + mid] <= t)
        lo = mid;
      else
        hi = mid - 1;
    }
    s = lo;
  }
  return s;
}

// Basis values N[r] (and dN[r] = dN_r/dt when `deriv`) of axis a with order `order`, r < order; control indices
// idx[r] along the axis (periodic modulo applied).
void ffd_basis(int a, int order, float t, bool deriv, out float N[FFD_MAX_ORDER], out float dN[FFD_MAX_ORDER],
               out int idx[FFD_MAX_ORDER]) {
  int s = ffd_span(a, t);
  float x = (t - ffd_tables[ffd_axes[a].span_begin + s]) * ffd_tables[ffd_axes[a].inv_span_len + s];
  int c = ffd_axes[a].coef + s * order * order;  // [power k][basis r]
  for (int r = 0; r < FFD_MAX_ORDER; ++r) {
    N[r] = 0.0;
    dN[r] = 0.0;
    idx[r] = 0;
  }
  for (int r = 0; r < order; ++r) N[r] = ffd_tables[c + (order - 1) * order + r];
  for (int k = order - 2; k >= 0; --k)
    for (int r = 0; r < order; ++r) {
      if (deriv) dN[r] = dN[r] * x + N[r];
      N[r] = N[r] * x + ffd_tables[c + k * order + r];
    }
  if (deriv) {
    float inv_len = ffd_tables[ffd_axes[a].inv_span_len + s];
    for (int r = 0; r < order; ++r) dN[r] *= inv_len;
  }
  int first = floatBitsToInt(ffd_tables[ffd_axes[a].first_index + s]);
  int count = ffd_axes[a].count;
  bool periodic = ffd_axes[a].periodic != 0;
  for (int r = 0; r < order; ++r) {
    int i = first + r;
    idx[r] = periodic ? ((i % count) + count) % count : i;
  }
}

// Deformed position (world units) of parameter point p; with FFD_NORMALS also the unit normal mapped from the
// rest normal n_rest (world rest space).
void ffd_eval(vec3 p, vec3 n_rest, out vec3 position, out vec3 normal) {
#ifdef FFD_NORMALS
  const bool deriv = true;
#else
  const bool deriv = false;
#endif
  float Nu[FFD_MAX_ORDER], Nv[FFD_MAX_ORDER], Nw[FFD_MAX_ORDER];
  float dNu[FFD_MAX_ORDER], dNv[FFD_MAX_ORDER], dNw[FFD_MAX_ORDER];
  int iu[FFD_MAX_ORDER], iv[FFD_MAX_ORDER], iw[FFD_MAX_ORDER];
  ffd_basis(0, FFD_ORDER_U, p.x, deriv, Nu, dNu, iu);
  ffd_basis(1, FFD_ORDER_V, p.y, deriv, Nv, dNv, iv);
  ffd_basis(2, FFD_ORDER_W, p.z, deriv, Nw, dNw, iw);
  int l = ffd_axes[0].count;
  int lm = l * ffd_axes[1].count;
  // Sums run over P − P0, P0 = the support's first control point: the same function (the basis sums to 1 and its
  // derivatives to 0), but Σ dN·P no longer cancels large terms on lattices with many spans, where dN grows with
  // the span count (as the CPU fast path does).
  vec3 P0 = ffd_cp[l * iv[0] + lm * iw[0] + iu[0]].xyz;
  vec3 val = vec3(0.0), du = vec3(0.0), dv = vec3(0.0), dw = vec3(0.0);
  for (int k = 0; k < FFD_ORDER_W; ++k) {
    vec3 v_j = vec3(0.0), du_j = vec3(0.0), dv_j = vec3(0.0);
    for (int j = 0; j < FFD_ORDER_V; ++j) {
      int row = l * iv[j] + lm * iw[k];
      vec3 s = vec3(0.0), su = vec3(0.0);
      for (int i = 0; i < FFD_ORDER_U; ++i) {
        vec3 P = ffd_cp[row + iu[i]].xyz - P0;
        s += Nu[i] * P;
        if (deriv) su += dNu[i] * P;
      }
      v_j += Nv[j] * s;
      if (deriv) {
        du_j += Nv[j] * su;
        dv_j += dNv[j] * s;
      }
    }
    val += Nw[k] * v_j;
    if (deriv) {
      du += Nw[k] * du_j;
      dv += Nw[k] * dv_j;
      dw += dNw[k] * v_j;
    }
  }
  position = ffd_centre.xyz + (P0 + val);
  normal = n_rest;
#ifdef FFD_NORMALS
  mat3 M = mat3(du, dv, dw) * mat3(ffd_linear[0].xyz, ffd_linear[1].xyz, ffd_linear[2].xyz);
  // cof(M) = [m1×m2, m2×m0, m0×m1] (columns), defined for singular M.
  vec3 n = cross(M[1], M[2]) * n_rest.x + cross(M[2], M[0]) * n_rest.y + cross(M[0], M[1]) * n_rest.z;
  float len = length(n);
  if (len > 0.0 && !isinf(len) && !isnan(len)) normal = n / len;
#endif
}
