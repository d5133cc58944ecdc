// cpu_fast block kernels, compiled once per instruction set: ffd_fast_kernel_{baseline,avx2,avx512}.cpp define
//   FFD_ISA_NS    namespace of this copy            FFD_W        floats per vector (4, 8, 16)
//   FFD_ISA_NAME  "sse" | "avx2" | "avx512" | ...   FFD_TABLE_FN the KernelTable accessor to define
// then include this file. Everything here has internal linkage (anonymous namespace) and uses GCC/Clang vector
// extensions and builtins only, so nothing compiled for a wide ISA can be picked up by baseline code.
//
// Per block of kLanes vertices of one cell: tri-variate Horner in the cell's local coordinates (w innermost, then v,
// then u) on the power-basis coefficients of the cell, W vertices per vector, coefficients broadcast from memory.
// Normals: Horner with first derivatives, then n' = cof(J_x)·(N_cell·n) (see CellTables::normal_matrix).
// No reassociation (no -ffast-math): each lane runs the same fixed operation sequence, so a vertex's result does not
// depend on its block neighbours, the block partition or the thread count. FMA contraction is on in the wide ISAs
// (-ffp-contract=fast), so results are bit-identical per ISA, not across ISAs.
#include <cstring>
#include <type_traits>

#include "core/ffd/ffd_fast_kernel.h"

#if !defined(FFD_ISA_NS) || !defined(FFD_W) || !defined(FFD_ISA_NAME) || !defined(FFD_TABLE_FN)
#error "define FFD_ISA_NS, FFD_W, FFD_ISA_NAME and FFD_TABLE_FN before including ffd_fast_kernel_impl.h"
#endif

namespace trispline::core::ffd_fast_detail {
namespace FFD_ISA_NS {
namespace {

constexpr int W = FFD_W;
constexpr int kChunks = kLanes / W;
static_assert(kLanes % W == 0, "block size must be a multiple of the vector width");

typedef float vf __attribute__((vector_size(4 * W)));
typedef std::int32_t vi __attribute__((vector_size(4 * W)));

// Two-source permute with lane indices known only at run time: r[l] = (a ++ b)[m[l] mod 2W]. GCC lowers
// __builtin_shuffle to vpermt2ps / vpermps; clang (used by the sanitizer build) has no run-time form, so it gets the
// same result lane by lane.
[[gnu::always_inline]] inline vf permute2(vf a, vf b, vi m) {
#if defined(__clang__)
  vf r;
  for (int l = 0; l < W; ++l) {
    const int i = m[l] & (2 * W - 1);
    r[l] = i < W ? a[i] : b[i - W];
  }
  return r;
#else
  return __builtin_shuffle(a, b, m);
#endif
}

inline vf load(const float* p) {
  vf v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline vi loadi(const std::int32_t* p) {
  vi v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, vf v) { std::memcpy(p, &v, sizeof v); }
inline vf splat(float s) { return s - vf{}; }  // s − 0 = s exactly, −0 included
inline vf select(vi mask, vf a, vf b) { return (vf)(((vi)a & mask) | ((vi)b & ~mask)); }
inline vi select(vi mask, vi a, vi b) { return (a & mask) | (b & ~mask); }

// Value of the cell polynomial, component by component. C: coefficients of one cell (layout in CellTables::coef).
template <int OU, int OV, int OW>
inline void eval_value(const float* C, vf x, vf y, vf z, vf P[3]) {
#pragma GCC unroll 3
  for (int d = 0; d < 3; ++d) {
    vf F{};
#pragma GCC unroll 4
    for (int a = OU - 1; a >= 0; --a) {
      vf G{};
#pragma GCC unroll 4
      for (int b = OV - 1; b >= 0; --b) {
        const float* c = C + (a * OV + b) * OW * 3 + d;
        vf H = splat(c[(OW - 1) * 3]);
#pragma GCC unroll 4
        for (int k = OW - 2; k >= 0; --k) H = H * z + c[k * 3];
        G = (b == OV - 1) ? H : G * y + H;
      }
      F = (a == OU - 1) ? G : F * x + G;
    }
    P[d] = F;
  }
}

// Value and partials in the local coordinates (∂/∂x_u, ∂/∂x_v, ∂/∂x_w): Horner carrying derivatives.
template <int OU, int OV, int OW>
inline void eval_jacobian(const float* C, vf x, vf y, vf z, vf P[3], vf Du[3], vf Dv[3], vf Dw[3]) {
#pragma GCC unroll 3
  for (int d = 0; d < 3; ++d) {
    vf F{}, Fu{}, Fv{}, Fw{};
#pragma GCC unroll 4
    for (int a = OU - 1; a >= 0; --a) {
      vf G{}, Gv{}, Gw{};
#pragma GCC unroll 4
      for (int b = OV - 1; b >= 0; --b) {
        const float* c = C + (a * OV + b) * OW * 3 + d;
        vf H = splat(c[(OW - 1) * 3]), Hw{};
#pragma GCC unroll 4
        for (int k = OW - 2; k >= 0; --k) {
          Hw = (k == OW - 2) ? H : Hw * z + H;
          H = H * z + c[k * 3];
        }
        if (b == OV - 1) {
          G = H;
          Gw = Hw;
        } else {
          Gv = (b == OV - 2) ? G : Gv * y + G;
          G = G * y + H;
          Gw = Gw * y + Hw;
        }
      }
      if (a == OU - 1) {
        F = G;
        Fv = Gv;
        Fw = Gw;
      } else {
        Fu = (a == OU - 2) ? F : Fu * x + F;
        F = F * x + G;
        Fv = Fv * x + Gv;
        Fw = Fw * x + Gw;
      }
    }
    P[d] = F;
    Du[d] = Fu;
    Dv[d] = Fv;
    Dw[d] = Fw;
  }
}

// n' = cof(J_x)·m with m = N·n (N: the cell's normal matrix, row-major), normalised; the rest normal where
// |n'| is 0 or not finite. cof(J_x) = [Dv×Dw, Dw×Du, Du×Dv] (columns).
[[gnu::always_inline]] inline void map_normal(const float* N, const vf n[3], const vf Du[3], const vf Dv[3],
                                              const vf Dw[3], vf out[3]) {
  const vf mx = N[0] * n[0] + N[1] * n[1] + N[2] * n[2];
  const vf my = N[3] * n[0] + N[4] * n[1] + N[5] * n[2];
  const vf mz = N[6] * n[0] + N[7] * n[1] + N[8] * n[2];
  vf o[3];
#pragma GCC unroll 3
  for (int r = 0; r < 3; ++r) {
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
    const vf c0 = Dv[r1] * Dw[r2] - Dv[r2] * Dw[r1];
    const vf c1 = Dw[r1] * Du[r2] - Dw[r2] * Du[r1];
    const vf c2 = Du[r1] * Dv[r2] - Du[r2] * Dv[r1];
    o[r] = mx * c0 + my * c1 + mz * c2;
  }
  const vf len2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  float l2[W], inv[W];
  store(l2, len2);
#pragma GCC unroll 16
  for (int l = 0; l < W; ++l) inv[l] = 1.0f / __builtin_sqrtf(l2[l]);
  const vf s = load(inv);
  const vi ok = (len2 > 0.0f) & (len2 < __builtin_inff());
#pragma GCC unroll 3
  for (int r = 0; r < 3; ++r) out[r] = select(ok, o[r] * s, n[r]);
}

// Shuffle masks interleaving x, y, z (W lanes each) into the AoS stream x0 y0 z0 x1 ...: output vector k holds
// stream elements kW … kW+W−1. Stage 1 picks x/y lanes (z slots: don't care), stage 2 inserts the z lanes.
struct InterleaveMasks {
  std::int32_t m[3][2][W];
};
constexpr InterleaveMasks make_interleave_masks() {
  InterleaveMasks t{};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < W; ++j) {
      const int e = k * W + j, comp = e % 3, lane = e / 3;
      t.m[k][0][j] = comp == 0 ? lane : comp == 1 ? W + lane : 0;
      t.m[k][1][j] = comp == 2 ? W + lane : j;
    }
  return t;
}
constexpr InterleaveMasks kInterleave = make_interleave_masks();

typedef double vd __attribute__((vector_size(8 * W)));

// Where one block range's results go (Outputs): float positions / normals relative to the lattice centre, or the
// double ones of Outputs::positions64 / normals64, positions with the centre added (the arithmetic of
// read_results_into: centre[r] + double(value)).
struct Writer {
  const Outputs& O;
  vd centre[3];  // stream element k·W + j of a run: centre[(k·W + j) mod 3]
  explicit Writer(const Outputs& o) : O(o) {
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < W; ++j) centre[k][j] = O.centre[(k * W + j) % 3];
  }

  // out[3·index[l] + r] = v[r][l] (+ centre[r] for double positions): W vertices written in the caller's vertex
  // order. A run of W consecutive indices (common: binning keeps vertex order inside a cell) is interleaved in
  // registers and stored as 3 full vectors (widened to double for double outputs). Block invariant (binning):
  // indices ascend within a block and only a padded tail repeats the last one, so the run is consecutive iff it spans
  // W − 1 and its last two lanes differ.
  template <class T, bool kAdd>
  [[gnu::always_inline]] void write3(T* out, const std::int32_t* index, const vf v[3]) const {
    if (index[W - 1] - index[0] == W - 1 && index[W - 1] != index[W - 2]) {
      T* o = out + 3 * static_cast<std::size_t>(index[0]);
#pragma GCC unroll 3
      for (int k = 0; k < 3; ++k) {
        const vi m1 = loadi(kInterleave.m[k][0]), m2 = loadi(kInterleave.m[k][1]);
        const vf f = permute2(permute2(v[0], v[1], m1), v[2], m2);
        if constexpr (std::is_same_v<T, float>) {
          store(o + k * W, f);
        } else {
          vd d = __builtin_convertvector(f, vd);
          if constexpr (kAdd) d = centre[k] + d;
          std::memcpy(o + k * W, &d, sizeof d);
        }
      }
      return;
    }
    float t[3][W];
    for (int r = 0; r < 3; ++r) store(t[r], v[r]);
#pragma GCC unroll 16
    for (int l = 0; l < W; ++l) {
      T* o = out + 3 * static_cast<std::size_t>(index[l]);
#pragma GCC unroll 3
      for (int r = 0; r < 3; ++r) {
        if constexpr (std::is_same_v<T, float>)
          o[r] = t[r][l];
        else
          o[r] = kAdd ? centre[0][r] + double(t[r][l]) : double(t[r][l]);
      }
    }
  }
  [[gnu::always_inline]] void positions(const std::int32_t* index, const vf P[3]) const {
    if (O.positions64)
      write3<double, true>(O.positions64, index, P);
    else
      write3<float, false>(O.positions, index, P);
  }
  [[gnu::always_inline]] void normals(const std::int32_t* index, const vf N[3]) const {
    if (O.normals64)
      write3<double, false>(O.normals64, index, N);
    else
      write3<float, false>(O.normals, index, N);
  }
};

template <int OU, int OV, int OW, bool kNormals>
void rest_blocks(const CellTables& T, const BlockArrays& B, const Outputs& O, std::size_t b0, std::size_t b1) {
  const Writer out(O);
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t cell = static_cast<std::size_t>(B.cell[b]);
    const float* C = T.coef + cell * static_cast<std::size_t>(T.stride);
    for (int ch = 0; ch < kChunks; ++ch) {
      const std::size_t base = b * kLanes + static_cast<std::size_t>(ch) * W;
      const vf x = load(B.xu + base), y = load(B.xv + base), z = load(B.xw + base);
      vf P[3];
      if constexpr (kNormals) {
        vf Du[3], Dv[3], Dw[3], N[3];
        eval_jacobian<OU, OV, OW>(C, x, y, z, P, Du, Dv, Dw);
        const vf n[3] = {load(B.nx + base), load(B.ny + base), load(B.nz + base)};
        map_normal(T.normal_matrix + 9 * cell, n, Du, Dv, Dw, N);
        out.normals(B.index + base, N);
      } else {
        eval_value<OU, OV, OW>(C, x, y, z, P);
      }
      out.positions(B.index + base, P);
    }
  }
}

// A span table (span_begin or inv_span_len) for lookups by lane: up to 2W entries live in two registers and a
// lookup is one two-source permute; longer tables fall back to a lane loop.
struct LaneTable {
  vf lo{}, hi{};
  const float* data = nullptr;
  bool in_registers = false;
  LaneTable(const float* table, int n) : data(table), in_registers(n <= 2 * W) {
    if (!in_registers) return;
    for (int i = 0; i < n; ++i) {
      if (i < W)
        lo[i] = table[i];
      else
        hi[i - W] = table[i];
    }
  }
  [[gnu::always_inline]] vf operator()(vi k) const {
    if (in_registers) return permute2(lo, hi, k);
    vf r;
#pragma GCC unroll 16
    for (int l = 0; l < W; ++l) r[l] = data[k[l]];
    return r;
  }
};

struct AxisLanes {
  const AxisTable& a;
  LaneTable begin, inv_len;
  explicit AxisLanes(const AxisTable& t)
      : a(t), begin(t.span_begin, t.span_count + 1), inv_len(t.inv_span_len, t.span_count) {}
};

// Span slots and local coordinates of W parameters t on one axis: locate_span (ffd_packed.h rules) on vectors
// (wrap/clamp, O(1) lookup with the one-span correction, or a binary search by halving steps).
[[gnu::always_inline]] inline vi locate_vec(const AxisLanes& L, vf t, vf* x) {
  const AxisTable& a = L.a;
  const int S = a.span_count;
  if (a.periodic) {  // t − ⌊t⌋; |t| ≥ 2^23 is already an integer
    const vi k = __builtin_convertvector(t, vi);
    vf fl = __builtin_convertvector(k, vf);
    fl = select(t < fl, fl - 1.0f, fl);
    t = select((t < 8388608.0f) & (t > -8388608.0f), t - fl, t - t);
  }
  t = select(t >= a.domain_min, t, splat(a.domain_min));  // also maps NaN to domain_min
  t = select(t <= a.domain_max, t, splat(a.domain_max));
  vi s;
  if (a.uniform) {
    s = __builtin_convertvector((t - a.domain_min) * a.inv_uniform_len, vi);  // ≥ 0: truncation = floor
    s = s < S - 1 ? s : S - 1;
    s += t < L.begin(s);                       // comparison lanes are −1 where true
    s -= (s + 1 < S) & (t >= L.begin(s + 1));  // span_begin has S + 1 entries
  } else {
    s = vi{};
    int step = 1;
    while (2 * step < S) step *= 2;
    for (; step > 0; step /= 2) {  // last s with span_begin[s] ≤ t
      const vi m = s + step;
      const vi mc = m < S - 1 ? m : S - 1;
      s = select((m <= S - 1) & (L.begin(mc) <= t), m, s);
    }
  }
  *x = (t - L.begin(s)) * L.inv_len(s);
  return s;
}

// Offset path: spans located per lane at params + offset; a chunk is evaluated once per distinct cell among its
// lanes (with that cell's coefficients on all lanes) and lanes take the result of their own cell.
template <int OU, int OV, int OW, bool kNormals>
void offset_blocks(const CellTables& T, const BlockArrays& B, const Outputs& O, std::size_t b0, std::size_t b1,
                   const float* off) {
  const int Su = T.axis[0].span_count, Sv = T.axis[1].span_count;
  const Writer out(O);
  const AxisLanes au(T.axis[0]), av(T.axis[1]), aw(T.axis[2]);
  for (std::size_t b = b0; b < b1; ++b) {
    for (int ch = 0; ch < kChunks; ++ch) {
      const std::size_t base = b * kLanes + static_cast<std::size_t>(ch) * W;
      vf x, y, z;
      const vi su = locate_vec(au, load(B.pu + base) + off[0], &x);
      const vi sv = locate_vec(av, load(B.pv + base) + off[1], &y);
      const vi sw = locate_vec(aw, load(B.pw + base) + off[2], &z);
      const vi cells = su + Su * (sv + Sv * sw);
      vf P[3] = {}, N[3] = {}, n[3];
      if constexpr (kNormals) {
        n[0] = load(B.nx + base);
        n[1] = load(B.ny + base);
        n[2] = load(B.nz + base);
      }
      unsigned pending = (1u << W) - 1u;
      while (pending) {
        const std::int32_t c = cells[__builtin_ctz(pending)];
        const vi mask = cells == c;
#pragma GCC unroll 16
        for (int l = 0; l < W; ++l) pending &= mask[l] ? ~(1u << l) : ~0u;
        const float* C = T.coef + static_cast<std::size_t>(c) * static_cast<std::size_t>(T.stride);
        vf Pc[3];
        if constexpr (kNormals) {
          vf Du[3], Dv[3], Dw[3], Nc[3];
          eval_jacobian<OU, OV, OW>(C, x, y, z, Pc, Du, Dv, Dw);
          map_normal(T.normal_matrix + 9 * static_cast<std::size_t>(c), n, Du, Dv, Dw, Nc);
          for (int r = 0; r < 3; ++r) N[r] = select(mask, Nc[r], N[r]);
        } else {
          eval_value<OU, OV, OW>(C, x, y, z, Pc);
        }
        for (int r = 0; r < 3; ++r) P[r] = select(mask, Pc[r], P[r]);
      }
      out.positions(B.index + base, P);
      if constexpr (kNormals) out.normals(B.index + base, N);
    }
  }
}

template <int OU, int OV, int OW, bool kNormals>
void block_kernel(const CellTables& T, const BlockArrays& B, const Outputs& O, std::size_t b0, std::size_t b1,
                  const float* offset) {
  if (offset)
    offset_blocks<OU, OV, OW, kNormals>(T, B, O, b0, b1, offset);
  else
    rest_blocks<OU, OV, OW, kNormals>(T, B, O, b0, b1);
}

template <int OU, int OV, int OW>
constexpr void fill(KernelTable& t) {
  t.kernel[OU - 2][OV - 2][OW - 2][0] = &block_kernel<OU, OV, OW, false>;
  t.kernel[OU - 2][OV - 2][OW - 2][1] = &block_kernel<OU, OV, OW, true>;
}
template <int OU, int OV>
constexpr void fill_w(KernelTable& t) {
  fill<OU, OV, 2>(t);
  fill<OU, OV, 3>(t);
  fill<OU, OV, 4>(t);
}
template <int OU>
constexpr void fill_vw(KernelTable& t) {
  fill_w<OU, 2>(t);
  fill_w<OU, 3>(t);
  fill_w<OU, 4>(t);
}
constexpr KernelTable make_table() {
  KernelTable t{FFD_ISA_NAME, {}};
  fill_vw<2>(t);
  fill_vw<3>(t);
  fill_vw<4>(t);
  return t;
}

constexpr KernelTable kTable = make_table();

}  // namespace
}  // namespace FFD_ISA_NS

const KernelTable* FFD_TABLE_FN() { return &FFD_ISA_NS::kTable; }

}  // namespace trispline::core::ffd_fast_detail
