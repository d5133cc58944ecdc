// FfdFastEvaluator (cpu_fast): cell tables, binning of vertices into same-cell blocks, threaded dispatch to the
// per-ISA block kernels (ffd_fast_kernel_impl.h) or to the gather kernel. See ffd_fast.h.
#include "core/ffd/ffd_fast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/ffd/ffd_fast_kernel.h"
#include "core/ffd/ffd_packed.h"
#include "core/spline/span_basis.h"

namespace trispline::core {

namespace {

using namespace ffd_fast_detail;

// 64-byte aligned storage (whole cache lines for the vector loads of the block arrays).
template <class T>
struct Aligned64 {
  using value_type = T;
  Aligned64() = default;
  template <class U>
  Aligned64(const Aligned64<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64))); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(64)); }
  bool operator==(const Aligned64&) const { return true; }
};
template <class T>
using AVec = std::vector<T, Aligned64<T>>;

constexpr std::size_t kChunkVertices = 8192;  // vertices binned together (a task; its outputs stay in L2)
constexpr std::size_t kGatherGrain = 2048;    // vertices per task in gather mode

bool same_knots(const KnotVector& a, const KnotVector& b) {
  return a.order() == b.order() && a.period() == b.period() && a.knots() == b.knots();
}

// cof(M) = det(M)·M^{-T}, columns m1×m2, m2×m0, m0×m1.
glm::dmat3 cofactor(const glm::dmat3& m) {
  return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

}  // namespace

struct FfdFastEvaluator::Impl {
  // Bound vertices.
  bool bound = false;
  std::vector<glm::dvec3> params;  // #V × 3, for (re-)binning in double
  AVec<float> params_f;            // #V × 3 AoS float (gather mode)
  AVec<float> normals_f;           // #V × 3 AoS float or empty

  // Lattice.
  bool has_lattice = false;
  FfdPackedLattice packed;
  std::vector<KnotVector> knots;  // the three knot vectors of the lattice
  bool tables = false;            // cell-table mode (else gather)
  glm::ivec3 spans{0};
  AVec<float> coef, normal_matrix;
  CellTables ct;

  // Binning (blocks of kLanes same-cell vertices), valid for `binned_knots`.
  bool binned = false;
  std::vector<KnotVector> binned_knots;
  std::size_t blocks = 0;
  std::vector<std::size_t> chunk_first_block;  // #chunks + 1
  AVec<float> xu, xv, xw, pu, pv, pw, bnx, bny, bnz;
  AVec<std::int32_t> index, cell;

  // Results (relative to `centre`).
  bool evaluated = false;
  glm::dvec3 centre{0.0};
  AVec<float> pos, nrm;

  void bin();
  void run(const glm::dvec3& param_offset, const Outputs& out);
  void build_tables(const TrivariateBSpline<glm::dvec3>& F, const Embedding& E);
};

// Locates every vertex in double (SpanBasis<double>, the reference's span convention); then, per chunk of
// kChunkVertices consecutive vertices, a stable sort by cell into blocks of kLanes (tails repeat the cell's last
// vertex). Chunking keeps each task's output writes inside a cache-sized window of the result arrays.
void FfdFastEvaluator::Impl::bin() {
  const std::size_t V = params.size();
  const SpanBasis<double> sb[3] = {SpanBasis<double>(knots[0]), SpanBasis<double>(knots[1]),
                                   SpanBasis<double>(knots[2])};
  const std::size_t chunks = (V + kChunkVertices - 1) / kChunkVertices;
  std::vector<std::uint64_t> key(V);  // (cell << 32) | vertex index: sorting it is a stable sort by cell
  std::vector<float> local(3 * V);
  std::vector<std::size_t> chunk_blocks(chunks, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t ch = r.begin(); ch != r.end(); ++ch) {
      const std::size_t i0 = ch * kChunkVertices, i1 = std::min(V, i0 + kChunkVertices);
      for (std::size_t i = i0; i < i1; ++i) {
        int s[3];
        for (int a = 0; a < 3; ++a) {
          double x;
          s[a] = sb[a].locate(params[i][a], &x);
          local[3 * i + a] = static_cast<float>(x);
        }
        const std::uint64_t c = static_cast<std::uint64_t>(s[0] + spans.x * (s[1] + spans.y * s[2]));
        key[i] = (c << 32) | static_cast<std::uint64_t>(i);
      }
      std::sort(key.begin() + static_cast<std::ptrdiff_t>(i0), key.begin() + static_cast<std::ptrdiff_t>(i1));
      std::size_t nb = 0;
      for (std::size_t i = i0; i < i1;) {
        std::size_t j = i;
        while (j < i1 && (key[j] >> 32) == (key[i] >> 32)) ++j;
        nb += (j - i + kLanes - 1) / kLanes;
        i = j;
      }
      chunk_blocks[ch] = nb;
    }
  });
  chunk_first_block.assign(chunks + 1, 0);
  for (std::size_t ch = 0; ch < chunks; ++ch) chunk_first_block[ch + 1] = chunk_first_block[ch] + chunk_blocks[ch];
  blocks = chunk_first_block[chunks];
  const std::size_t lanes = blocks * kLanes;
  const bool with_normals = !normals_f.empty();
  for (AVec<float>* a : {&xu, &xv, &xw, &pu, &pv, &pw}) a->resize(lanes);
  for (AVec<float>* a : {&bnx, &bny, &bnz}) a->resize(with_normals ? lanes : 0);
  index.resize(lanes);
  cell.resize(blocks);
  auto put = [&](std::size_t lane, std::size_t i) {
    xu[lane] = local[3 * i];
    xv[lane] = local[3 * i + 1];
    xw[lane] = local[3 * i + 2];
    pu[lane] = params_f[3 * i];
    pv[lane] = params_f[3 * i + 1];
    pw[lane] = params_f[3 * i + 2];
    if (with_normals) {
      bnx[lane] = normals_f[3 * i];
      bny[lane] = normals_f[3 * i + 1];
      bnz[lane] = normals_f[3 * i + 2];
    }
    index[lane] = static_cast<std::int32_t>(i);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t ch = r.begin(); ch != r.end(); ++ch) {
      const std::size_t i0 = ch * kChunkVertices, i1 = std::min(V, i0 + kChunkVertices);
      std::size_t b = chunk_first_block[ch];
      for (std::size_t i = i0; i < i1;) {
        std::size_t j = i;
        const std::uint64_t c = key[i] >> 32;
        while (j < i1 && (key[j] >> 32) == c) ++j;
        const std::size_t nb = (j - i + kLanes - 1) / kLanes;
        for (std::size_t k = 0; k < nb * kLanes; ++k)
          put(b * kLanes + k, static_cast<std::size_t>(key[std::min(i + k, j - 1)] & 0xffffffffu));
        for (std::size_t k = 0; k < nb; ++k) cell[b + k] = static_cast<std::int32_t>(c);
        b += nb;
        i = j;
      }
    }
  });
  binned_knots = knots;
  binned = true;
}

// Per cell: power-basis coefficients c_abc = Σ_ijk Cu[a][i]·Cv[b][j]·Cw[c][k]·(P_ijk − centre), folded in double and
// rounded once; and the normal matrix cof(D)·cof(A), scaled so that mapped normals are O(1) before normalisation.
void FfdFastEvaluator::Impl::build_tables(const TrivariateBSpline<glm::dvec3>& F, const Embedding& E) {
  const glm::ivec3 o = F.orders();
  const glm::ivec3 cnt = F.control_counts();
  const std::size_t cells = static_cast<std::size_t>(spans.x) * spans.y * static_cast<std::size_t>(spans.z);
  const int stride = 3 * o.x * o.y * o.z;
  tables = cells * static_cast<std::size_t>(stride + 9) <= kMaxCellTableFloats;
  if (!tables) {
    coef.clear();
    coef.shrink_to_fit();
    normal_matrix.clear();
    normal_matrix.shrink_to_fit();
    return;
  }
  const SpanBasis<double> sb[3] = {SpanBasis<double>(knots[0]), SpanBasis<double>(knots[1]),
                                   SpanBasis<double>(knots[2])};
  coef.resize(cells * static_cast<std::size_t>(stride));
  normal_matrix.resize(cells * 9);
  const std::vector<glm::dvec3>& P = F.control_points();
  const glm::dvec3 centre_d = packed.centre;
  const glm::dmat3 cofA = cofactor(E.linear);
  const double h = packed.bbox_diagonal() / std::max({spans.x, spans.y, spans.z});
  const double h2 = h > 0.0 && std::isfinite(h * h) ? h * h : 1.0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 16), [&](const tbb::blocked_range<std::size_t>& r) {
    glm::dvec3 t1[4][4][4], t2[4][4][4];  // [a][j][k], then [a][b][k]
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const int s[3] = {static_cast<int>(c % spans.x), static_cast<int>((c / spans.x) % spans.y),
                        static_cast<int>(c / (static_cast<std::size_t>(spans.x) * spans.y))};
      const double* C[3];
      int idx[3][4];
      for (int a = 0; a < 3; ++a) {
        C[a] = sb[a].coefficients(s[a]);
        for (int r2 = 0; r2 < o[a]; ++r2) {
          const int i = sb[a].first_index(s[a]) + r2;
          idx[a][r2] = knots[a].is_periodic() ? i % cnt[a] : i;
        }
      }
      for (int a = 0; a < o.x; ++a)
        for (int j = 0; j < o.y; ++j)
          for (int k = 0; k < o.z; ++k) {
            glm::dvec3 sum(0.0);
            for (int i = 0; i < o.x; ++i)
              sum += C[0][a * o.x + i] * (P[F.index(idx[0][i], idx[1][j], idx[2][k])] - centre_d);
            t1[a][j][k] = sum;
          }
      for (int a = 0; a < o.x; ++a)
        for (int b = 0; b < o.y; ++b)
          for (int k = 0; k < o.z; ++k) {
            glm::dvec3 sum(0.0);
            for (int j = 0; j < o.y; ++j) sum += C[1][b * o.y + j] * t1[a][j][k];
            t2[a][b][k] = sum;
          }
      float* out = &coef[c * static_cast<std::size_t>(stride)];
      for (int a = 0; a < o.x; ++a)
        for (int b = 0; b < o.y; ++b)
          for (int cc = 0; cc < o.z; ++cc) {
            glm::dvec3 sum(0.0);
            for (int k = 0; k < o.z; ++k) sum += C[2][cc * o.z + k] * t2[a][b][k];
            for (int d = 0; d < 3; ++d) out[((a * o.y + b) * o.z + cc) * 3 + d] = static_cast<float>(sum[d]);
          }
      // cof(D)·cof(A) with D = diag(1/span length): rows of cof(A) scaled by (iv·iw, iw·iu, iu·iv).
      const double iu = static_cast<double>(sb[0].inv_span_lengths()[s[0]]);
      const double iv = static_cast<double>(sb[1].inv_span_lengths()[s[1]]);
      const double iw = static_cast<double>(sb[2].inv_span_lengths()[s[2]]);
      const double rs[3] = {iv * iw, iw * iu, iu * iv};
      double m[9], mx = 0.0;
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) {
          m[3 * row + col] = rs[row] * cofA[col][row];
          mx = std::max(mx, std::abs(m[3 * row + col]));
        }
      const double scale = mx > 0.0 ? 1.0 / (mx * h2) : 1.0;
      for (int e = 0; e < 9; ++e) normal_matrix[9 * c + e] = static_cast<float>(m[e] * scale);
    }
  });
  ct.coef = coef.data();
  ct.stride = stride;
  ct.normal_matrix = normal_matrix.data();
}

FfdFastEvaluator::FfdFastEvaluator() : impl_(std::make_unique<Impl>()) {}
FfdFastEvaluator::~FfdFastEvaluator() = default;

void FfdFastEvaluator::bind_vertices(const std::vector<glm::dvec3>& params,
                                     const std::vector<glm::dvec3>& rest_normals) {
  detail::check_ffd_vertices(params, rest_normals, "cpu_fast bind_vertices");
  if (params.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::invalid_argument("cpu_fast bind_vertices: more than 2^31 - 1 vertices");
  Impl& m = *impl_;
  m.params = params;
  m.params_f.resize(3 * params.size());
  for (std::size_t i = 0; i < params.size(); ++i)
    for (int a = 0; a < 3; ++a) m.params_f[3 * i + a] = static_cast<float>(params[i][a]);
  m.normals_f.resize(3 * rest_normals.size());
  for (std::size_t i = 0; i < rest_normals.size(); ++i)
    for (int a = 0; a < 3; ++a) m.normals_f[3 * i + a] = static_cast<float>(rest_normals[i][a]);
  m.bound = true;
  m.binned = false;
  m.blocks = 0;
  m.evaluated = false;
  if (m.has_lattice && m.tables) m.bin();
}

void FfdFastEvaluator::set_lattice(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding) {
  const glm::ivec3 o = lattice.orders();
  for (int a = 0; a < 3; ++a)
    if (o[a] < 2 || o[a] > 4)
      throw std::invalid_argument("cpu_fast set_lattice: order " + std::to_string(o[a]) + " along axis " +
                                  std::to_string(a) + " is outside 2..4 (use cpu_ref for other orders)");
  Impl& m = *impl_;
  m.packed = FfdPackedLattice::build(lattice, embedding);
  m.knots = {lattice.knots(0), lattice.knots(1), lattice.knots(2)};
  if (m.binned)
    for (int a = 0; a < 3; ++a)
      if (!same_knots(m.knots[a], m.binned_knots[a])) m.binned = false;
  for (int a = 0; a < 3; ++a) {
    const FfdPackedAxis& p = m.packed.axes[a];
    m.spans[a] = p.span_count();
    m.ct.axis[a] = axis_table(p);
  }
  m.build_tables(lattice, embedding);
  if (!m.tables) {
    m.binned = false;
    m.blocks = 0;
  }
  m.has_lattice = true;
  if (m.bound && m.tables && !m.binned) m.bin();
}

void FfdFastEvaluator::evaluate(const glm::dvec3& param_offset) {
  Impl& m = *impl_;
  if (!m.bound || !m.has_lattice)
    throw std::logic_error("cpu_fast evaluate: bind_vertices and set_lattice must be called first");
  const std::size_t V = m.params.size();
  m.pos.resize(3 * V);
  m.nrm.resize(m.normals_f.empty() ? 0 : 3 * V);
  m.run(param_offset, Outputs{m.pos.data(), m.nrm.empty() ? nullptr : m.nrm.data()});
  m.centre = m.packed.centre;
  m.evaluated = true;
}

void FfdFastEvaluator::evaluate_into(const glm::dvec3& param_offset, double* positions, double* normals) {
  Impl& m = *impl_;
  if (!m.bound || !m.has_lattice)
    throw std::logic_error("cpu_fast evaluate_into: bind_vertices and set_lattice must be called first");
  if (!m.tables) {  // the gather kernel writes floats only
    evaluate(param_offset);
    read_results_into(positions, normals);
    return;
  }
  Outputs out;
  out.positions64 = positions;
  out.normals64 = m.normals_f.empty() ? nullptr : normals;
  for (int a = 0; a < 3; ++a) out.centre[a] = m.packed.centre[a];
  std::vector<double> discard;  // normals the caller does not want still have somewhere to go
  if (!m.normals_f.empty() && !normals) {
    discard.resize(3 * m.params.size());
    out.normals64 = discard.data();
  }
  m.run(param_offset, out);
  m.evaluated = false;  // the float results are not this evaluation's
}

// Runs the kernels at params + param_offset into `out` (its float arrays, or its double ones).
void FfdFastEvaluator::Impl::run(const glm::dvec3& param_offset, const Outputs& out) {
  Impl& m = *this;
  glm::dvec3 off = param_offset;
  for (int a = 0; a < 3; ++a)
    if (m.packed.axes[a].periodic) off[a] -= std::floor(off[a]);  // whole periods change nothing
  const float off_f[3] = {static_cast<float>(off.x), static_cast<float>(off.y), static_cast<float>(off.z)};
  const bool rest = off == glm::dvec3(0.0);
  const std::size_t V = m.params.size();
  const bool normals = !m.normals_f.empty();
  if (m.tables) {
    if (!m.binned) m.bin();
    const BlockArrays ba{m.xu.data(),
                         m.xv.data(),
                         m.xw.data(),
                         m.pu.data(),
                         m.pv.data(),
                         m.pw.data(),
                         normals ? m.bnx.data() : nullptr,
                         normals ? m.bny.data() : nullptr,
                         normals ? m.bnz.data() : nullptr,
                         m.index.data(),
                         m.cell.data()};
    const glm::ivec3 o(m.packed.axes[0].order, m.packed.axes[1].order, m.packed.axes[2].order);
    const BlockKernel fn = active_kernels()->kernel[o.x - 2][o.y - 2][o.z - 2][normals ? 1 : 0];
    const CellTables& ct = m.ct;
    const std::vector<std::size_t>& cb = m.chunk_first_block;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cb.size() - 1, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        fn(ct, ba, out, cb[r.begin()], cb[r.end()], rest ? nullptr : off_f);
                      });
  } else {
    GatherInput in;
    in.lattice = &m.packed;
    in.params = m.params_f.data();
    in.normals = normals ? m.normals_f.data() : nullptr;
    for (int a = 0; a < 3; ++a) in.offset[a] = off_f[a];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, V, kGatherGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) { gather_evaluate(in, out, r.begin(), r.end()); });
  }
}

namespace {

// The evaluated positions (the centre added in double, then converted once to Vec) and normals as Vec (dvec3, vec3).
template <class Vec, class Impl>
void copy_results(const Impl& m, const char* who, std::vector<Vec>& positions, std::vector<Vec>& normals) {
  if (!m.evaluated) throw std::logic_error(std::string(who) + ": evaluate() has not run since bind_vertices");
  const std::size_t V = m.params.size();
  positions.resize(V);
  normals.resize(m.nrm.empty() ? 0 : V);
  const glm::dvec3 c = m.centre;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, V, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      positions[i] = Vec(c + glm::dvec3(m.pos[3 * i], m.pos[3 * i + 1], m.pos[3 * i + 2]));
    if (!normals.empty())
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        normals[i] = Vec(m.nrm[3 * i], m.nrm[3 * i + 1], m.nrm[3 * i + 2]);
  });
}

}  // namespace

void FfdFastEvaluator::read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) {
  copy_results(*impl_, "cpu_fast read_results", positions, normals);
}

void FfdFastEvaluator::read_results_float(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  copy_results(*impl_, "cpu_fast read_results_float", positions, normals);
}

void FfdFastEvaluator::read_results_into(double* positions, double* normals) {
  const Impl& m = *impl_;
  if (!m.evaluated) throw std::logic_error("cpu_fast read_results_into: evaluate() has not run since bind_vertices");
  const std::size_t V = m.params.size();
  const bool with_normals = normals && !m.nrm.empty();
  const glm::dvec3 c = m.centre;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, V, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      positions[3 * i] = c.x + double(m.pos[3 * i]);
      positions[3 * i + 1] = c.y + double(m.pos[3 * i + 1]);
      positions[3 * i + 2] = c.z + double(m.pos[3 * i + 2]);
    }
    if (with_normals)
      for (std::size_t i = 3 * r.begin(); i != 3 * r.end(); ++i) normals[i] = double(m.nrm[i]);
  });
}

std::size_t FfdFastEvaluator::vertex_count() const { return impl_->params.size(); }
bool FfdFastEvaluator::has_normals() const { return !impl_->normals_f.empty(); }
bool FfdFastEvaluator::uses_cell_tables() const { return impl_->tables; }
std::size_t FfdFastEvaluator::block_count() const { return impl_->binned ? impl_->blocks : 0; }

}  // namespace trispline::core
