// DDM on the CPU: spline charts, layouts, T(u,v,w) = S + n·w with exact normals, metamorphosis. See ddm_base.h.
// Sources: seed ch. 5 — Eq. 5.1–5.2 (the shell map), §5.3.1 (base surfaces), §5.3.2 (instances, normals),
// Eq. 5.3 (metamorphosis), Fig. 5.11–5.12 (hexagonal and brick layouts).
#include "core/ddm/ddm_base.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/base/enum_names.h"
#include "core/ddm/ddm_layer.h"
#include "core/mesh/osd_topology.h"

namespace trispline::core {
namespace {

double clamp01(double t) { return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t); }
double wrap01(double t) { return t - std::floor(t); }

// n = S_u × S_v / |S_u × S_v| and its partials from S's first and second derivatives (Weingarten: ∂n = (∂m − n (n·∂m))
// / |m| with m = S_u × S_v, ∂m/∂u = S_uu × S_v + S_u × S_uv, ∂m/∂v = S_uv × S_v + S_u × S_vv). False when |m| = 0.
bool set_normal(DdmSurfacePoint& q, const glm::dvec3& Su, const glm::dvec3& Sv, const glm::dvec3& Suu,
                const glm::dvec3& Suv, const glm::dvec3& Svv) {
  const glm::dvec3 m = glm::cross(Su, Sv);
  const double len = glm::length(m);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  q.n = m / len;
  const glm::dvec3 mu = glm::cross(Suu, Sv) + glm::cross(Su, Suv);
  const glm::dvec3 mv = glm::cross(Suv, Sv) + glm::cross(Su, Svv);
  q.dn_du = (mu - q.n * glm::dot(q.n, mu)) / len;
  q.dn_dv = (mv - q.n * glm::dot(q.n, mv)) / len;
  return true;
}

}  // namespace

DdmSplineBase::DdmSplineBase(std::vector<BSplineSurface<glm::dvec3>> patches, glm::ivec2 grid, glm::bvec2 periodic)
    : patches_(std::move(patches)), grid_(grid), periodic_(periodic) {
  if (patches_.empty()) throw std::invalid_argument("base: a spline base needs at least one patch");
  if (grid_ != glm::ivec2(0) &&
      (grid_.x < 1 || grid_.y < 1 || static_cast<std::size_t>(grid_.x) * grid_.y != patches_.size()))
    throw std::invalid_argument("base: a " + std::to_string(grid_.x) + " × " + std::to_string(grid_.y) +
                                " patch grid needs that many patches, got " + std::to_string(patches_.size()));
}

DdmSurfacePoint DdmSplineBase::eval(int chart, double u, double v) const {
  if (chart < 0 || chart >= chart_count())
    throw std::out_of_range("base: chart " + std::to_string(chart) + " of " + std::to_string(chart_count()));
  u = periodic_.x ? wrap01(u) : clamp01(u);
  v = periodic_.y ? wrap01(v) : clamp01(v);
  if (grid_.x == 0) return eval_patch(chart, u, v);
  // One chart over the grid: patch (i, j) covers [i/c, (i+1)/c] × [j/r, (j+1)/r]; the chain rule scales by (c, r).
  const int i = std::min(static_cast<int>(u * grid_.x), grid_.x - 1),
            j = std::min(static_cast<int>(v * grid_.y), grid_.y - 1);
  DdmSurfacePoint q = eval_patch(i + grid_.x * j, u * grid_.x - i, v * grid_.y - j);
  q.du *= grid_.x, q.dn_du *= grid_.x;
  q.dv *= grid_.y, q.dn_dv *= grid_.y;
  return q;
}

DdmSurfacePoint DdmSplineBase::eval_patch(int patch, double u, double v) const {
  const BSplineSurface<glm::dvec3>& S = patches_[static_cast<std::size_t>(patch)];
  const KnotVector &ku = S.knots(0), &kv = S.knots(1);
  const double su = ku.domain_max() - ku.domain_min(), sv = kv.domain_max() - kv.domain_min();
  u = clamp01(u), v = clamp01(v);
  auto at = [&](double a, double b) { return S.eval_second(ku.domain_min() + su * a, kv.domain_min() + sv * b); };
  DdmSurfacePoint q;
  const auto d = at(u, v);
  q.p = d.value;
  q.du = su * d.du, q.dv = sv * d.dv;  // chain rule onto [0,1]²
  const double scale = std::max(glm::length(q.du), glm::length(q.dv));
  const bool regular = glm::length(glm::cross(q.du, q.dv)) > 1e-12 * scale * scale;
  // A collapsed edge (the teapot's bottom centre): the normal and its derivatives from a point slightly inside.
  for (double step : {0.0, 1e-4, 1e-3, 1e-2}) {
    if (step > 0.0 && regular) break;
    const auto e = step > 0.0 ? at(u + (0.5 - u) * step, v + (0.5 - v) * step) : d;
    if (set_normal(q, su * e.du, sv * e.dv, su * su * e.duu, su * sv * e.duv, sv * sv * e.dvv) &&
        (regular || step > 0.0))
      break;
  }
  return q;
}

glm::dmat2 DdmTileTransform::linear() const {
  const double a = glm::radians(rotate_deg), c = std::cos(a), s = std::sin(a);
  return glm::dmat2(c * scale.x, s * scale.x, -s * scale.y, c * scale.y);  // columns: R·e_x·sx, R·e_y·sy
}

const char* ddm_base_name(DdmBaseKind k) { return enum_name(k, {"limit", "teapot_body", "uv", "auto_uv"}, "limit"); }

const char* ddm_layout_name(DdmLayout l) { return enum_name(l, {"rect", "hex", "brick"}, "rect"); }

void ddm_check_layout_counts(DdmLayout layout, glm::ivec2 counts) {
  const int n = counts.x, m = counts.y;
  const int min_n = layout == DdmLayout::rect ? 1 : 2;
  if (n < min_n || m < 1)
    throw std::invalid_argument("counts: [" + std::to_string(n) + ", " + std::to_string(m) + "] gives an empty " +
                                ddm_layout_name(layout) + " layout (need n ≥ " + std::to_string(min_n) + ", m ≥ 1)");
}

std::vector<DdmInstance> ddm_layout_cells(DdmLayout layout, glm::ivec2 counts, int chart_count) {
  ddm_check_layout_counts(layout, counts);
  const int n = counts.x, m = counts.y;
  if (chart_count < 1) throw std::invalid_argument("base: no chart to lay tiles on");
  std::vector<DdmInstance> cells;
  const double w = 1.0 / n;
  const double h = layout == DdmLayout::hex ? 1.0 / (0.75 * (m - 1) + 1.0) : 1.0 / m;
  const double pitch = layout == DdmLayout::hex ? 0.75 * h : h;
  for (int c = 0; c < chart_count; ++c)
    for (int j = 0; j < m; ++j) {
      const bool shifted = layout != DdmLayout::rect && j % 2 == 1;
      for (int i = 0; i < n - (shifted ? 1 : 0); ++i)
        cells.push_back({c, {(i + (shifted ? 0.5 : 0.0)) * w, j * pitch}, {w, h}});
    }
  return cells;
}

std::vector<DdmInstance> ddm_layout_cells(DdmLayout layout, const std::vector<glm::ivec2>& chart_counts) {
  std::vector<DdmInstance> cells;
  for (std::size_t c = 0; c < chart_counts.size(); ++c) {
    std::vector<DdmInstance> one = ddm_layout_cells(layout, chart_counts[c], 1);
    for (DdmInstance& i : one) i.chart = static_cast<int>(c);
    cells.insert(cells.end(), one.begin(), one.end());
  }
  return cells;
}

std::size_t ddm_layout_cell_count(DdmLayout layout, glm::ivec2 counts) {
  const auto n = static_cast<std::size_t>(std::max(counts.x, 0)), m = static_cast<std::size_t>(std::max(counts.y, 0));
  if (layout == DdmLayout::rect) return n * m;
  return (m + 1) / 2 * n + m / 2 * (n > 0 ? n - 1 : 0);  // even rows n cells, odd rows n − 1
}

glm::ivec2 ddm_counts_for_size(DdmLayout layout, glm::dvec2 chart_size, double tile_size) {
  if (!std::isfinite(tile_size) || !(tile_size > 0.0))
    throw std::invalid_argument("tile_size: must be finite and > 0, got " + std::to_string(tile_size));
  constexpr double kMaxPerAxis = 1 << 20;
  const auto count = [&](double x, double lowest) {
    // +inf (a tile_size far below the chart, 5e-324) is the most tiles, not the fewest: the caller's budget refuses it.
    return static_cast<int>(std::isnan(x) ? lowest : std::clamp(std::round(x), lowest, kMaxPerAxis));
  };
  const glm::dvec2 across = chart_size / tile_size;
  const double rows = layout == DdmLayout::hex ? (across.y - 1.0) / 0.75 + 1.0 : across.y;
  return {count(across.x, layout == DdmLayout::rect ? 1.0 : 2.0), count(rows, 1.0)};
}

namespace {

// One instance's uvs and face materials: the tile's own (its (x, y) and the first slot without materials).
void copy_tile_materials(const DdmTile& tile, MaterialSlot first_slot, TriMesh& out, std::size_t first_vertex,
                         std::size_t first_triangle) {
  const TriMesh& tm = tile.mesh;
  const std::size_t own = tile.materials ? tile.materials->materials.size() : 0;
  for (std::size_t v = 0; v < tm.vertex_count(); ++v)
    out.uvs[first_vertex + v] = tm.uvs.size() == tm.vertex_count() ? tm.uvs[v] : glm::dvec2(tm.positions[v]);
  for (std::size_t f = 0; f < tm.triangle_count(); ++f) {
    const MaterialSlot local = f < tm.face_material.size() ? tm.face_material[f] : kMaterialSurface;
    out.face_material[first_triangle + f] =
        local == kMaterialInside ? kMaterialInside : static_cast<MaterialSlot>(first_slot + (local < own ? local : 0));
  }
}

}  // namespace

TriMesh ddm_evaluate(const DdmBase& base, const std::vector<DdmTile>& tiles, const std::vector<DdmInstance>& instances,
                     double height, const DdmTileTransform& transform, glm::dvec2 offset,
                     const ProgressSink* progress) {
  if (!std::isfinite(height) || !(height > 0.0))
    throw std::invalid_argument("height: must be finite and > 0, got " + std::to_string(height));
  if (tiles.empty()) throw std::invalid_argument("tile: a layer needs at least one tile");
  for (const DdmTile& tile : tiles)
    if (tile.mesh.normals.size() != tile.mesh.vertex_count())
      throw std::invalid_argument("tile: '" + tile.name + "' has no per-vertex normals");
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y)) throw std::invalid_argument("offset: must be finite");
  // Vertex offset of every instance (instances one after another, each in its tile's vertex order).
  std::vector<std::size_t> first(instances.size() + 1, 0);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const DdmInstance& inst = instances[k];
    if (inst.chart < 0 || inst.chart >= base.chart_count())
      throw std::invalid_argument("base: instance on chart " + std::to_string(inst.chart) + " of " +
                                  std::to_string(base.chart_count()));
    if (inst.tile < 0 || inst.tile >= static_cast<int>(tiles.size()))
      throw std::invalid_argument("tile: instance " + std::to_string(k) + " uses tile " + std::to_string(inst.tile) +
                                  " of " + std::to_string(tiles.size()));
    first[k + 1] = first[k] + tiles[static_cast<std::size_t>(inst.tile)].mesh.vertex_count();
  }
  if (first.back() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("counts: " + std::to_string(first.back()) + " vertices exceed 32-bit indices");
  const glm::dmat2 L = transform.linear();
  TriMesh out;
  out.positions.resize(first.back());
  out.normals.resize(first.back());
  std::vector<std::size_t> first_tri(instances.size() + 1, 0);
  for (std::size_t k = 0; k < instances.size(); ++k)
    first_tri[k + 1] = first_tri[k] + tiles[static_cast<std::size_t>(instances[k].tile)].mesh.triangle_count();
  out.triangles.resize(first_tri.back());
  // Texture-mapped tiles (seed Fig. 5.12): each copy keeps its tile's uvs and materials (slots of the layer's set).
  const DdmTileMaterials materials = ddm_tile_materials(tiles);
  if (materials.set) {
    out.uvs.resize(first.back());
    out.face_material.resize(first_tri.back());
  }
  // Chunks of instances, so a cancel is seen within one chunk's time; each instance is evaluated alone, so the
  // chunking never changes a bit of the result.
  const std::size_t count = instances.size();
  const std::size_t chunk = progress ? std::max<std::size_t>(1024, count / 100 + 1) : std::max<std::size_t>(count, 1);
  for (std::size_t c0 = 0; c0 < count; c0 += chunk) {
    check_progress(progress, static_cast<double>(c0) / static_cast<double>(count));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(c0, std::min(count, c0 + chunk), 16), [&](const auto& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const DdmInstance& inst = instances[k];
        const TriMesh& tm = tiles[static_cast<std::size_t>(inst.tile)].mesh;
        const glm::dvec2 cx = inst.size.x * glm::dvec2(L[0][0], L[1][0]);  // ∂u/∂(x, y)
        const glm::dvec2 cy = inst.size.y * glm::dvec2(L[0][1], L[1][1]);  // ∂v/∂(x, y)
        std::size_t reversed = 0;  // vertices where T reverses orientation (a mirrored chart: det J < 0)
        for (std::size_t v = 0; v < tm.vertex_count(); ++v) {
          const glm::dvec3& t = tm.positions[v];
          const glm::dvec2 uv = inst.origin + inst.size * transform.apply({t.x, t.y}) + offset;
          const DdmSurfacePoint s = base.eval(inst.chart, uv.x, uv.y);
          const double wh = t.z * height;
          out.positions[first[k] + v] = s.p + wh * s.n;  // seed Eq. 5.2
          const glm::dvec3 Tu = s.du + wh * s.dn_du, Tv = s.dv + wh * s.dn_dv;
          const glm::dmat3 J(Tu * cx.x + Tv * cy.x, Tu * cx.y + Tv * cy.y, height * s.n);
          const glm::dmat3 cof(glm::cross(J[1], J[2]), glm::cross(J[2], J[0]), glm::cross(J[0], J[1]));
          // cof(J)·n = det(J)·J⁻ᵀ·n: turned back where det J < 0, so normals point out of the copy either way.
          const bool mirrored = glm::dot(J[2], cof[2]) < 0.0;
          reversed += mirrored;
          const glm::dvec3 n = (mirrored ? -1.0 : 1.0) * (cof * tm.normals[v]);
          const double len = glm::length(n);
          out.normals[first[k] + v] = len > 0.0 && std::isfinite(len) ? n / len : s.n;
        }
        // A copy mostly on a mirrored chart is wound the other way, so its faces stay counter-clockwise from outside.
        const bool flip = 2 * reversed > tm.vertex_count();
        const auto off = static_cast<unsigned>(first[k]);
        for (std::size_t f = 0; f < tm.triangle_count(); ++f) {
          const glm::uvec3 t = tm.triangles[f] + glm::uvec3(off);
          out.triangles[first_tri[k] + f] = flip ? glm::uvec3(t.x, t.z, t.y) : t;
        }
        if (materials.set)
          copy_tile_materials(tiles[std::size_t(inst.tile)], materials.first_slot[std::size_t(inst.tile)], out,
                              first[k], first_tri[k]);
      }
    });
  }
  check_progress(progress, 1.0);
  return out;
}

TriMesh ddm_evaluate(const DdmBase& base, const DdmTile& tile, const std::vector<DdmInstance>& instances,
                     double height) {
  std::vector<DdmInstance> one = instances;
  for (DdmInstance& i : one) i.tile = 0;
  return ddm_evaluate(base, std::vector<DdmTile>{tile}, one, height);
}

DdmTile ddm_morph(const DdmTile& a, const DdmTile& b, double alpha) {
  require_same_ddm_topology(a, b);
  if (!std::isfinite(alpha)) throw std::invalid_argument("alpha: must be finite");
  DdmTile out{a.name + "→" + b.name, a.mesh, a.materials};
  for (std::size_t v = 0; v < out.mesh.positions.size(); ++v)
    out.mesh.positions[v] = a.mesh.positions[v] * (1.0 - alpha) + b.mesh.positions[v] * alpha;  // seed Eq. 5.3
  if (a.mesh.normals.size() == a.mesh.positions.size() && b.mesh.normals.size() == b.mesh.positions.size())
    for (std::size_t v = 0; v < out.mesh.normals.size(); ++v) {
      const glm::dvec3 n = a.mesh.normals[v] * (1.0 - alpha) + b.mesh.normals[v] * alpha;
      const double len = glm::length(n);
      out.mesh.normals[v] = len > 0.0 ? n / len : (alpha < 0.5 ? a.mesh.normals[v] : b.mesh.normals[v]);
    }
  return out;
}

// ---- DdmSubdivBase: Loop limit surface through OpenSubdiv Bfr -------------------------------------------------

struct DdmSubdivBase::Impl {
  std::vector<OpenSubdiv::Bfr::Surface<double>> surfaces;  // per face
  std::vector<std::vector<double>> patch_points;           // per face, 3 doubles per patch point
};

DdmSubdivBase::DdmSubdivBase(const TriMesh& mesh) : impl_(std::make_unique<Impl>()) {
  namespace Far = OpenSubdiv::Far;
  namespace Sdc = OpenSubdiv::Sdc;
  namespace Bfr = OpenSubdiv::Bfr;
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  if (nf == 0) throw std::invalid_argument("base: the mesh has no triangles");
  std::vector<double> points(3 * nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const glm::dvec3& p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("base: non-finite position at vertex " + std::to_string(v));
    points[3 * v] = p.x, points[3 * v + 1] = p.y, points[3 * v + 2] = p.z;
  }
  const std::vector<int> indices = osd::checked_triangle_indices(mesh, "base");
  {  // 2-manifold edges only (OpenSubdiv would accept a fan of faces on one edge as a sharp, non-manifold edge)
    std::vector<std::uint64_t> halfedges(3 * nf);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
        halfedges[3 * f + k] = (std::min(a, b) << 32) | std::max(a, b);
      }
    std::sort(halfedges.begin(), halfedges.end());
    for (std::size_t i = 0; i + 2 < halfedges.size(); ++i)
      if (halfedges[i] == halfedges[i + 2])
        throw std::invalid_argument("base: non-manifold edge (" + std::to_string(halfedges[i] >> 32) + ", " +
                                    std::to_string(halfedges[i] & 0xffffffffu) + ") has more than two faces");
  }
  const std::unique_ptr<Far::TopologyRefiner> refiner = osd::triangle_refiner(
      static_cast<int>(nv), indices, Sdc::SCHEME_LOOP, Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  if (!refiner) throw std::invalid_argument("base: OpenSubdiv rejected the mesh topology (non-manifold?)");
  if (refiner->GetLevel(0).GetNumVertices() != static_cast<int>(nv))
    throw std::invalid_argument("base: OpenSubdiv changed the vertex count (non-manifold input)");
  Bfr::RefinerSurfaceFactory<> factory(*refiner, Bfr::RefinerSurfaceFactory<>::Options());
  const Bfr::Surface<double>::PointDescriptor pd(3);
  impl_->surfaces.resize(nf);
  impl_->patch_points.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    Bfr::Surface<double>& surface = impl_->surfaces[f];
    if (!factory.InitVertexSurface(static_cast<int>(f), &surface) || !surface.IsValid())
      throw std::invalid_argument("base: face " + std::to_string(f) + " has no limit surface (non-manifold there?)");
    impl_->patch_points[f].resize(3 * static_cast<std::size_t>(surface.GetNumPatchPoints()));
    surface.PreparePatchPoints(points.data(), pd, impl_->patch_points[f].data(), pd);
  }
}

DdmSubdivBase::~DdmSubdivBase() = default;
DdmSubdivBase::DdmSubdivBase(DdmSubdivBase&&) noexcept = default;

int DdmSubdivBase::chart_count() const { return static_cast<int>(3 * impl_->surfaces.size()); }

glm::dvec3 DdmSubdivBase::limit_point(int face, double s, double t) const {
  if (face < 0 || face >= static_cast<int>(impl_->surfaces.size()))
    throw std::out_of_range("base: face " + std::to_string(face));
  const double uv[2] = {s, t};
  double P[3];
  impl_->surfaces[face].Evaluate(uv, impl_->patch_points[face].data(),
                                 OpenSubdiv::Bfr::Surface<double>::PointDescriptor(3), P);
  return {P[0], P[1], P[2]};
}

DdmSurfacePoint DdmSubdivBase::eval(int chart, double u, double v) const {
  if (chart < 0 || chart >= chart_count())
    throw std::out_of_range("base: chart " + std::to_string(chart) + " of " + std::to_string(chart_count()));
  const int f = chart / 3, k = chart % 3;
  u = clamp01(u), v = clamp01(v);
  // The corner quad in the face's triangular parameters: A (vertex k), B (middle of edge k→k+1), C (centre),
  // D (middle of edge k+2→k); q(u,v) = A(1−u)(1−v) + B u(1−v) + C u v + D (1−u) v.
  const glm::dvec2 corner[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
  const glm::dvec2 A = corner[k], B = 0.5 * (corner[k] + corner[(k + 1) % 3]), C(1.0 / 3.0),
                   D = 0.5 * (corner[(k + 2) % 3] + corner[k]);
  const glm::dvec2 q = A * (1 - u) * (1 - v) + B * u * (1 - v) + C * u * v + D * (1 - u) * v;
  const glm::dvec2 qu = (B - A) * (1 - v) + (C - D) * v, qv = (D - A) * (1 - u) + (C - B) * u;
  const glm::dvec2 quv = A - B + C - D;  // q_uu = q_vv = 0 (bilinear)
  const double st[2] = {q.x, q.y};
  double P[3], Ds[3], Dt[3], Dss[3], Dst[3], Dtt[3];
  impl_->surfaces[f].Evaluate(st, impl_->patch_points[f].data(), OpenSubdiv::Bfr::Surface<double>::PointDescriptor(3),
                              P, Ds, Dt, Dss, Dst, Dtt);
  const glm::dvec3 Ss(Ds[0], Ds[1], Ds[2]), St(Dt[0], Dt[1], Dt[2]), Sss(Dss[0], Dss[1], Dss[2]),
      Sst(Dst[0], Dst[1], Dst[2]), Stt(Dtt[0], Dtt[1], Dtt[2]);
  DdmSurfacePoint out;
  out.p = {P[0], P[1], P[2]};
  out.du = Ss * qu.x + St * qu.y;
  out.dv = Ss * qv.x + St * qv.y;
  auto second = [&](const glm::dvec2& a, const glm::dvec2& b) {  // S along a then b (bilinear map: q_aa = 0)
    return Sss * (a.x * b.x) + Sst * (a.x * b.y + a.y * b.x) + Stt * (a.y * b.y);
  };
  const glm::dvec3 Suu = second(qu, qu), Svv = second(qv, qv), Suv = second(qu, qv) + Ss * quv.x + St * quv.y;
  set_normal(out, out.du, out.dv, Suu, Suv, Svv);
  return out;
}

}  // namespace trispline::core
