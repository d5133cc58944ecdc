// The one OpenVDB translation unit of trispline_volume: its headers are heavy, so nothing else includes them.
#include "core/volume/iso_mesh.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/gltf_io.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

using Leaf = openvdb::FloatTree::LeafNodeType;
constexpr int kBlock = static_cast<int>(Leaf::DIM);  // 8 grid voxels per leaf axis
// φ of the space outside the domain and of the background: far outside, so a crossing between a grid sample and it
// lies on the sample itself (the caps), to float precision.
constexpr float kOutside = 1e30f;
constexpr float kInside = -1e30f;  // φ of tiles wholly inside the material (never met by a crossing edge)

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The grid: voxel v (integer, per axis) samples D at index-space t = v / s, v = 0 … count − 1 with
// count = s·(n − 1) + 1. φ = σ·(D − iso) with σ = −1 when the material is above iso, so φ < 0 inside (OpenVDB's
// inside), and the grid is a level set (volumeToMesh then orients polygons towards φ > 0, out of the material).
struct Sampling {
  const VolumeSpline& spline;
  double iso;
  double sigma;
  int s;
  std::array<int, 3> count;
  std::array<int, 3> blocks;
};

enum class BlockKind : unsigned char { outside, inside, sampled };

// Conservative class of block (bx, by, bz): the convex hull of the control points weighting the index-space box of
// every cell whose corners read the block's voxels ([8b − 1, 8b + 8] per axis, clamped to the domain). A block whose
// box reaches past the domain reads the background (outside) there: it is sampled whenever it may hold material.
BlockKind classify(const Sampling& g, int bx, int by, int bz) {
  const VolumeSpline& sp = g.spline;
  const int b[3] = {bx, by, bz};
  int c0[3], c1[3];
  bool touches_outside = false;
  for (int a = 0; a < 3; ++a) {
    const int lo = kBlock * b[a] - 1, hi = kBlock * b[a] + kBlock;
    touches_outside = touches_outside || lo < 0 || hi > g.count[a] - 1;
    const double t0 = std::max(lo, 0) / double(g.s), t1 = std::min(hi, g.count[a] - 1) / double(g.s);
    c0[a] = std::max(sp.first_control(sp.span_of(a, t0)), 0);
    c1[a] = std::min(sp.first_control(sp.span_of(a, t1)) + sp.order() - 1, sp.dims()[a] - 1);
  }
  const auto& cp = sp.control_points();
  const std::size_t nx = sp.dims()[0], nxy = nx * sp.dims()[1];
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (int l = c0[2]; l <= c1[2]; ++l)
    for (int j = c0[1]; j <= c1[1]; ++j) {
      const float* row = &cp[l * nxy + j * nx];
      for (int i = c0[0]; i <= c1[0]; ++i) lo = std::min(lo, row[i]), hi = std::max(hi, row[i]);
    }
  const double p0 = g.sigma * (lo - g.iso), p1 = g.sigma * (hi - g.iso);
  const double phi_min = std::min(p0, p1), phi_max = std::max(p0, p1);
  if (phi_min >= 0.0) return BlockKind::outside;
  if (phi_max < 0.0 && !touches_outside) return BlockKind::inside;
  return BlockKind::sampled;
}

// Basis of one axis at the block's kBlock sample positions: control indices (clamped) and weights.
struct AxisSamples {
  int idx[kBlock][4];
  double w[kBlock][4];
  int first = 0, last = 0;  // range of idx
};

void axis_samples(const Sampling& g, int axis, int block, AxisSamples& out) {
  const VolumeSpline& sp = g.spline;
  const int k = sp.order(), n = sp.dims()[axis];
  out.first = std::numeric_limits<int>::max();
  out.last = std::numeric_limits<int>::lowest();
  for (int v = 0; v < kBlock; ++v) {
    const double t = std::min(kBlock * block + v, g.count[axis] - 1) / double(g.s);
    const int span = sp.span_of(axis, t);
    uniform_bspline_weights(k, t - sp.span_begin(span), out.w[v], nullptr, nullptr);
    for (int r = 0; r < k; ++r) {
      out.idx[v][r] = std::clamp(sp.first_control(span) + r, 0, n - 1);
      out.first = std::min(out.first, out.idx[v][r]);
      out.last = std::max(out.last, out.idx[v][r]);
    }
  }
}

// A leaf of φ for a sampled block: D evaluated at its voxels by separable contraction (z, then y, then x) of the
// control points it reads — the sum VolumeSpline::value forms, in another order. Voxels past the domain stay
// inactive background.
std::unique_ptr<Leaf> sample_block(const Sampling& g, int bx, int by, int bz) {
  const VolumeSpline& sp = g.spline;
  const int k = sp.order();
  AxisSamples ax, ay, az;
  axis_samples(g, 0, bx, ax);
  axis_samples(g, 1, by, ay);
  axis_samples(g, 2, bz, az);
  const int rx = ax.last - ax.first + 1, ry = ay.last - ay.first + 1;
  const auto& cp = sp.control_points();
  const std::size_t nx = sp.dims()[0], nxy = nx * sp.dims()[1];
  std::vector<double> t1(static_cast<std::size_t>(kBlock) * ry * rx),
      t2(static_cast<std::size_t>(kBlock) * kBlock * rx);
  for (int z = 0; z < kBlock; ++z)
    for (int y = 0; y < ry; ++y)
      for (int x = 0; x < rx; ++x) {
        double sum = 0.0;
        for (int c = 0; c < k; ++c) sum += az.w[z][c] * cp[az.idx[z][c] * nxy + (ay.first + y) * nx + ax.first + x];
        t1[(z * ry + y) * rx + x] = sum;
      }
  for (int z = 0; z < kBlock; ++z)
    for (int y = 0; y < kBlock; ++y)
      for (int x = 0; x < rx; ++x) {
        double sum = 0.0;
        for (int b = 0; b < k; ++b) sum += ay.w[y][b] * t1[(z * ry + ay.idx[y][b] - ay.first) * rx + x];
        t2[(z * kBlock + y) * rx + x] = sum;
      }
  const openvdb::Coord origin(kBlock * bx, kBlock * by, kBlock * bz);
  auto leaf = std::make_unique<Leaf>(origin, kOutside, false);
  for (int z = 0; z < kBlock; ++z)
    for (int y = 0; y < kBlock; ++y)
      for (int x = 0; x < kBlock; ++x) {
        if (origin.x() + x >= g.count[0] || origin.y() + y >= g.count[1] || origin.z() + z >= g.count[2]) continue;
        double d = 0.0;
        for (int a = 0; a < k; ++a) d += ax.w[x][a] * t2[(z * kBlock + y) * rx + ax.idx[x][a] - ax.first];
        leaf->setValueOn(openvdb::Coord(x, y, z), static_cast<float>(g.sigma * (d - g.iso)));
      }
  return leaf;
}

// Builds the sparse grid of φ: sampled leaves, inside tiles, background elsewhere.
openvdb::FloatGrid::Ptr sample_grid(const Sampling& g, const IsoMeshOptions& opt, const ProgressSink* progress,
                                    IsoMeshStats& st) {
  const std::size_t nblocks = static_cast<std::size_t>(g.blocks[0]) * g.blocks[1] * g.blocks[2];
  std::vector<BlockKind> kind(nblocks);
  auto block_of = [&](std::size_t i, int& bx, int& by, int& bz) {
    bx = static_cast<int>(i % g.blocks[0]);
    by = static_cast<int>(i / g.blocks[0] % g.blocks[1]);
    bz = static_cast<int>(i / (static_cast<std::size_t>(g.blocks[0]) * g.blocks[1]));
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      int bx, by, bz;
      block_of(i, bx, by, bz);
      kind[i] = classify(g, bx, by, bz);
    }
  });
  std::vector<std::size_t> sampled;
  for (std::size_t i = 0; i < nblocks; ++i)
    if (kind[i] == BlockKind::sampled) sampled.push_back(i);
  const std::size_t leaf_voxels = Leaf::SIZE;
  if (sampled.size() > opt.max_sampled_voxels / leaf_voxels)
    throw std::invalid_argument("iso mesh: the iso-level needs " + std::to_string(sampled.size() * leaf_voxels) +
                                " grid samples, more than the limit of " + std::to_string(opt.max_sampled_voxels) +
                                " (use fewer samples per voxel)");
  check_progress(progress, 0.1);

  auto grid = openvdb::FloatGrid::create(kOutside);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  auto& tree = grid->tree();
  for (std::size_t i = 0; i < nblocks; ++i)
    if (kind[i] == BlockKind::inside) {
      int bx, by, bz;
      block_of(i, bx, by, bz);
      tree.addTile(1, openvdb::Coord(kBlock * bx, kBlock * by, kBlock * bz), kInside, false);
      ++st.inside_tiles;
    }
  // Leaves in chunks: sampled in parallel, inserted serially (the tree is not thread-safe for writes).
  constexpr std::size_t kChunk = 2048;
  std::vector<std::unique_ptr<Leaf>> leaves;
  for (std::size_t c0 = 0; c0 < sampled.size(); c0 += kChunk) {
    const std::size_t c1 = std::min(sampled.size(), c0 + kChunk);
    leaves.clear();
    leaves.resize(c1 - c0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(c0, c1, 8), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        int bx, by, bz;
        block_of(sampled[i], bx, by, bz);
        leaves[i - c0] = sample_block(g, bx, by, bz);
      }
    });
    for (auto& leaf : leaves) {
      st.sampled_voxels += leaf->onVoxelCount();
      tree.addLeaf(leaf.release());
    }
    check_progress(progress, 0.1 + 0.4 * double(c1) / double(sampled.size()));
  }
  return grid;
}

// Grid edges with φ on either side of 0: one quad each at adaptivity 0. Every such edge is owned (low end) by an
// active voxel, or by a background voxel just below the domain whose neighbour in the domain is inside.
std::size_t count_crossing_edges(const openvdb::FloatGrid& grid) {
  std::vector<const Leaf*> leaves;
  leaves.reserve(grid.tree().leafCount());
  for (auto it = grid.tree().cbeginLeaf(); it; ++it) leaves.push_back(it.getLeaf());
  tbb::combinable<std::size_t> total([] { return std::size_t{0}; });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      auto acc = grid.getConstAccessor();
                      std::size_t n = 0;
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        for (auto v = leaves[i]->cbeginValueOn(); v; ++v) {
                          const openvdb::Coord c = v.getCoord();
                          const bool in = *v < 0.0f;
                          for (int a = 0; a < 3; ++a) {
                            openvdb::Coord up = c;
                            up[a] += 1;
                            if (in != (acc.getValue(up) < 0.0f)) ++n;
                            if (in && c[a] == 0) ++n;  // the edge from the background voxel below
                          }
                        }
                      total.local() += n;
                    });
  return total.combine([](std::size_t a, std::size_t b) { return a + b; });
}

// Per vertex: bit 2a set when the vertex lies on the domain's low face of axis a, bit 2a+1 on its high face.
unsigned face_mask(const glm::dvec3& x, const std::array<int, 3>& dims) {
  constexpr double kOnFace = 1e-4;  // index units: cap vertices sit on the face to float precision
  unsigned m = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(x[a]) <= kOnFace) m |= 1u << (2 * a);
    if (std::abs(x[a] - (dims[a] - 1)) <= kOnFace) m |= 1u << (2 * a + 1);
  }
  return m;
}

// Newton steps from `x` (index space) to D = iso along the gradient, each the shortest step in world millimetres
// that zeroes the linearised residual; axes of `fixed` (a face mask) do not move. Where Newton stalls (∇D small or
// turning), a bracketed root: the grid cell of `x` has corners on both sides of iso (OpenVDB puts a vertex in a cell
// its surface crosses), so regula falsi (Illinois) between the best point and the nearest corner of the other sign —
// in the face for a fixed axis — converges. `h` is the grid spacing in index units. Returns |D − iso| at the result.
double project_vertex(const VolumeSpline& sp, double iso, const glm::dmat3& metric, unsigned fixed, int max_steps,
                      double tolerance, double h, glm::dvec3& x) {
  glm::dmat3 w = metric;  // world metric AᵀA, constrained axes replaced by identity rows/columns
  for (int a = 0; a < 3; ++a)
    if (fixed & (3u << (2 * a))) {
      for (int b = 0; b < 3; ++b) w[a][b] = w[b][a] = 0.0;
      w[a][a] = 1.0;
    }
  const glm::dmat3 w_inv = glm::inverse(w);
  const glm::dvec3 hi(sp.dims()[0] - 1, sp.dims()[1] - 1, sp.dims()[2] - 1);
  const glm::dvec3 x0 = x;
  glm::dvec3 best = x;
  double best_f = sp.value(x) - iso;
  for (int step = 0; step < max_steps && std::abs(best_f) > tolerance; ++step) {
    const VolumeJet j = sp.jet(x);
    const double f = j.value - iso;
    glm::dvec3 g = j.gradient;
    for (int a = 0; a < 3; ++a)
      if (fixed & (3u << (2 * a))) g[a] = 0.0;
    const glm::dvec3 d = w_inv * g;
    const double denom = glm::dot(g, d);
    if (!(denom > 0.0)) break;
    glm::dvec3 delta = (-f / denom) * d;
    const double len = std::max({std::abs(delta.x), std::abs(delta.y), std::abs(delta.z)});
    if (len > 1.0) delta /= len;  // at most one index unit per step
    x = glm::clamp(x + delta, glm::dvec3(0.0), hi);
    const double fx = sp.value(x) - iso;
    if (std::abs(fx) < std::abs(best_f)) best_f = fx, best = x;
  }
  x = best;
  if (std::abs(best_f) <= tolerance) return std::abs(best_f);

  // The bracket: the corner of x0's cell on the other side of iso nearest to the best point.
  glm::dvec3 other(0.0);
  double other_f = 0.0, nearest = std::numeric_limits<double>::max();
  for (int c = 0; c < 8; ++c) {
    glm::dvec3 corner;
    for (int a = 0; a < 3; ++a)
      corner[a] =
          (fixed & (3u << (2 * a))) ? x0[a] : std::clamp((std::floor(x0[a] / h) + ((c >> a) & 1)) * h, 0.0, hi[a]);
    const double fc = sp.value(corner) - iso;
    if ((fc > 0.0) != (best_f > 0.0) && glm::distance(corner, best) < nearest)
      nearest = glm::distance(corner, best), other = corner, other_f = fc;
  }
  if (nearest == std::numeric_limits<double>::max()) return std::abs(best_f);
  glm::dvec3 a = best, b = other;
  double fa = best_f, fb = other_f;
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    const double t = fa / (fa - fb);
    const glm::dvec3 m = a + t * (b - a);
    const double fm = sp.value(m) - iso;
    if (std::abs(fm) <= tolerance || it == 199) {
      x = m;
      return std::abs(fm);
    }
    if ((fm > 0.0) == (fa > 0.0)) {
      a = m, fa = fm;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = m, fb = fm;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return std::abs(best_f);
}

void check_options(const VolumeSpline& spline, double iso, const IsoMeshOptions& opt) {
  const double cmin = spline.control_min(), cmax = spline.control_max();
  if (!std::isfinite(iso) || !(iso > cmin && iso < cmax))
    throw std::invalid_argument("iso mesh: the iso-level " + std::to_string(iso) + " is outside the volume's range (" +
                                std::to_string(cmin) + ", " + std::to_string(cmax) + ")");
  if (opt.samples_per_voxel < 1 || opt.samples_per_voxel > 4)
    throw std::invalid_argument("iso mesh: samples_per_voxel must be 1…4");
  if (!(opt.adaptivity >= 0.0 && opt.adaptivity <= 1.0))
    throw std::invalid_argument("iso mesh: adaptivity must be in [0, 1]");
  if (opt.max_newton_steps < 0 || opt.max_newton_steps > 100)
    throw std::invalid_argument("iso mesh: max_newton_steps must be 0…100");
}

// Stage 1: the level set φ sampled on the grid, refused when no sample crosses the iso-level or when it would make
// more triangles than the limit.
openvdb::FloatGrid::Ptr sample_level_set(const Sampling& g, const IsoMeshOptions& opt, const ProgressSink* progress,
                                         IsoMeshStats& st) {
  const auto t_sample = std::chrono::steady_clock::now();
  openvdb::FloatGrid::Ptr grid = sample_grid(g, opt, progress, st);
  st.grid_bytes = grid->memUsage();
  st.crossing_edges = count_crossing_edges(*grid);
  st.sample_ms = ms_since(t_sample);
  if (st.crossing_edges == 0)
    throw std::invalid_argument("iso mesh: no sample of the volume lies " +
                                std::string(opt.material_above ? "above" : "below") + " the iso-level " +
                                std::to_string(g.iso));
  if (st.crossing_edges > opt.max_triangles / 2)
    throw std::invalid_argument("iso mesh: the iso-level " + std::to_string(g.iso) + " would make " +
                                std::to_string(2 * st.crossing_edges) + " triangles (" +
                                std::to_string(st.sampled_voxels) + " sampled voxels), more than the limit of " +
                                std::to_string(opt.max_triangles));
  return grid;
}

constexpr unsigned kNoCorner = std::numeric_limits<unsigned>::max();
using Polygon = std::array<unsigned, 4>;  // a triangle's fourth corner is kNoCorner
int corners(const Polygon& p) { return p[3] == kNoCorner ? 3 : 4; }

// The polygons OpenVDB made, over the vertices they use: x (index space) and the box faces each lies on.
struct IsoPolygons {
  std::vector<glm::dvec3> x;   // #used vertices, index space
  std::vector<unsigned> mask;  // face_mask of each
  std::vector<unsigned char> rim;
  std::vector<Polygon> polys;  // corners index x
};

// Stage 2: OpenVDB's polygons of φ = 0 (the grid is released), caps dropped unless closed at the boundary, and the
// vertices renumbered to those used. A cap vertex (on the box) next to a vertex off the box lies on a cap's rim.
IsoPolygons mesh_level_set(openvdb::FloatGrid::Ptr grid, const Sampling& g, const IsoMeshOptions& opt) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0, opt.adaptivity);
  grid.reset();
  const std::size_t nv = points.size();
  std::vector<glm::dvec3> x(nv);
  std::vector<unsigned> mask(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    x[i] = glm::dvec3(points[i].x(), points[i].y(), points[i].z()) / double(g.s);
    mask[i] = face_mask(x[i], g.spline.dims());
  }
  std::vector<openvdb::Vec3s>().swap(points);
  IsoPolygons out;  // quads are split later, once the vertices have moved
  std::vector<Polygon>& polys = out.polys;
  polys.reserve(quads.size() + tris.size());
  for (const auto& q : quads) polys.push_back({q[0], q[1], q[2], q[3]});
  for (const auto& t : tris) polys.push_back({t[0], t[1], t[2], kNoCorner});
  std::vector<openvdb::Vec4I>().swap(quads);
  std::vector<openvdb::Vec3I>().swap(tris);

  std::vector<unsigned char> rim(nv, 0);  // cap vertices with only cap neighbours stay where they are
  for (const Polygon& p : polys) {
    bool any_free = false, any_cap = false;
    for (int c = 0; c < corners(p); ++c) (mask[p[c]] ? any_cap : any_free) = true;
    if (any_free && any_cap)
      for (int c = 0; c < corners(p); ++c)
        if (mask[p[c]]) rim[p[c]] = 1;
  }
  if (!opt.close_at_boundary) {  // drop the caps: polygons all of whose corners lie on the box
    std::erase_if(polys, [&](const Polygon& p) {
      for (int c = 0; c < corners(p); ++c)
        if (!mask[p[c]]) return false;
      return true;
    });
  }
  std::vector<unsigned> remap(nv, kNoCorner);
  for (Polygon& p : polys)
    for (int c = 0; c < corners(p); ++c) {
      if (remap[p[c]] == kNoCorner) {
        remap[p[c]] = static_cast<unsigned>(out.x.size());
        out.x.push_back(x[p[c]]);
        out.mask.push_back(mask[p[c]]);
        out.rim.push_back(rim[p[c]]);
      }
      p[c] = remap[p[c]];
    }
  return out;
}

// What placing the vertices found: per vertex, whether ∇D vanished there, whether Newton did not converge, and its
// residual |D − iso|.
struct Placement {
  std::vector<unsigned char> no_normal, unconverged;
  std::vector<double> residual;
};

// Stage 3: every vertex off the caps projected onto D = iso along ∇D (project_vertex) with the normal orient·∇D;
// cap-interior vertices keep their place and get the box face's normal. World units out.
Placement place_vertices(const VolumeSpline& spline, double iso, const IsoPolygons& poly, const IsoMeshOptions& opt,
                         int s, const ProgressSink* progress, TriMesh& mesh) {
  const std::size_t n = poly.x.size();
  mesh.positions.resize(n);
  mesh.normals.resize(n);
  const glm::dmat4& to_world = spline.index_to_world();
  const glm::dmat3 lin(to_world);
  const glm::dmat3 metric = glm::transpose(lin) * lin;
  const glm::dmat3 normal_map = glm::transpose(glm::inverse(lin));
  const double tolerance = 1e-6 * (spline.control_max() - spline.control_min());
  const double orient = opt.material_above ? -1.0 : 1.0;  // normal = orient · ∇D
  Placement out{std::vector<unsigned char>(n, 0), std::vector<unsigned char>(n, 0), std::vector<double>(n, 0.0)};
  constexpr std::size_t kChunk = 1 << 16;
  for (std::size_t c0 = 0; c0 < n; c0 += kChunk) {
    const std::size_t c1 = std::min(n, c0 + kChunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(c0, c1, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        glm::dvec3 p = poly.x[i];
        const unsigned mask = poly.mask[i];
        if (mask && !poly.rim[i]) {  // inside a cap
          glm::dvec3 nrm(0.0);
          for (int a = 0; a < 3; ++a) {
            if (mask & (1u << (2 * a))) nrm[a] -= 1.0;
            if (mask & (1u << (2 * a + 1))) nrm[a] += 1.0;
          }
          mesh.normals[i] = glm::normalize(normal_map * nrm);
        } else {
          if (opt.project_to_spline) {
            out.residual[i] = project_vertex(spline, iso, metric, mask, opt.max_newton_steps, tolerance, 1.0 / s, p);
            out.unconverged[i] = out.residual[i] > tolerance;
          }
          const glm::dvec3 gw = spline.world_gradient(spline.jet(p).gradient);
          const double len = glm::length(gw);
          if (len > 0.0 && std::isfinite(len))
            mesh.normals[i] = (orient / len) * gw;
          else
            out.no_normal[i] = 1;
        }
        mesh.positions[i] = glm::dvec3(to_world * glm::dvec4(p, 1.0));
      }
    });
    check_progress(progress, 0.7 + 0.28 * double(c1) / double(n));
  }
  return out;
}

// Stage 4: triangles, counter-clockwise seen from outside: OpenVDB's polygons of a level set wind clockwise seen from
// outside (φ > 0) in grid space, and a mirroring index_to_world reverses that once more in world space. Quads split
// along their shorter diagonal. Vertices where ∇D vanished get area-weighted face normals.
void triangulate(const std::vector<Polygon>& polys, const glm::dmat4& index_to_world,
                 const std::vector<unsigned char>& no_normal, TriMesh& mesh) {
  const bool flip = glm::determinant(glm::dmat3(index_to_world)) > 0.0;
  auto add = [&](unsigned a, unsigned b, unsigned c) {
    mesh.triangles.push_back(flip ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
  };
  mesh.triangles.reserve(2 * polys.size());
  for (const Polygon& p : polys) {
    if (corners(p) == 3) {
      add(p[0], p[1], p[2]);
      continue;
    }
    const auto& P = mesh.positions;
    if (glm::distance(P[p[0]], P[p[2]]) <= glm::distance(P[p[1]], P[p[3]])) {
      add(p[0], p[1], p[2]);
      add(p[0], p[2], p[3]);
    } else {
      add(p[0], p[1], p[3]);
      add(p[1], p[2], p[3]);
    }
  }
  if (std::find(no_normal.begin(), no_normal.end(), 1) != no_normal.end()) {
    TriMesh faces = mesh;
    compute_vertex_normals(faces);
    for (std::size_t i = 0; i < no_normal.size(); ++i)
      if (no_normal[i]) mesh.normals[i] = faces.normals[i];
  }
}

}  // namespace

TriMesh extract_iso_mesh(const VolumeSpline& spline, double iso, const IsoMeshOptions& opt,
                         const ProgressSink* progress, IsoMeshStats* stats) {
  check_options(spline, iso, opt);
  initialize_openvdb();
  IsoMeshStats st;
  Sampling g{spline, iso, opt.material_above ? -1.0 : 1.0, opt.samples_per_voxel, {}, {}};
  for (int a = 0; a < 3; ++a) {
    g.count[a] = g.s * (spline.dims()[a] - 1) + 1;
    g.blocks[a] = (g.count[a] + kBlock - 1) / kBlock;
  }
  openvdb::FloatGrid::Ptr grid = sample_level_set(g, opt, progress, st);
  check_progress(progress, 0.55);

  const auto t_mesh = std::chrono::steady_clock::now();
  const IsoPolygons poly = mesh_level_set(std::move(grid), g, opt);
  st.mesh_ms = ms_since(t_mesh);
  check_progress(progress, 0.7);

  const auto t_project = std::chrono::steady_clock::now();
  TriMesh mesh;
  const Placement placed = place_vertices(spline, iso, poly, opt, g.s, progress, mesh);
  triangulate(poly.polys, spline.index_to_world(), placed.no_normal, mesh);
  const double range = spline.control_max() - spline.control_min();
  for (std::size_t i = 0; i < poly.x.size(); ++i) {
    st.cap_vertices += poly.mask[i] != 0;
    st.unconverged += placed.unconverged[i];
    st.max_residual = std::max(st.max_residual, placed.residual[i] / range);
  }
  st.vertices = mesh.vertex_count();
  st.triangles = mesh.triangle_count();
  st.project_ms = ms_since(t_project);
  check_progress(progress, 1.0);
  if (stats) *stats = st;
  return mesh;
}

void write_iso_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  const std::string ext = lower_extension(path);
  if (ext == ".glb") {
    GltfNode node;
    node.name = path.stem().string();
    node.mesh = &mesh;
    write_glb(path, {node});
  } else if (ext == ".obj" || ext == ".ply") {
    validate_mesh(mesh, "iso mesh");
    save_mesh(path, mesh);
  } else {
    throw MeshIoError("'" + path.string() + "': unsupported extension for an iso mesh (use .glb, .obj or .ply)");
  }
}

}  // namespace trispline::core
