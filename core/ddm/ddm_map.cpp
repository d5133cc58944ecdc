// DDM on the CPU: spline charts, layouts, T(u,v,w) = S + n·w with exact normals, metamorphosis. See ddm_map.h.
// Sources: seed ch. 5 — Eq. 5.1–5.2 (the shell map), §5.3.1 (base surfaces), §5.3.2 (instances, normals),
// Eq. 5.3 (metamorphosis), Fig. 5.11–5.12 (hexagonal and brick layouts).
#include "core/ddm/ddm_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/scene/primitives.h"

namespace trispline::core {
namespace {

double clamp01(double t) { return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t); }

}  // namespace

DdmSplineBase::DdmSplineBase(std::vector<BSplineSurface<glm::dvec3>> patches) : patches_(std::move(patches)) {
  if (patches_.empty()) throw std::invalid_argument("base: a spline base needs at least one patch");
}

DdmSurfacePoint DdmSplineBase::eval(int chart, double u, double v) const {
  if (chart < 0 || chart >= chart_count())
    throw std::out_of_range("base: chart " + std::to_string(chart) + " of " + std::to_string(chart_count()));
  const BSplineSurface<glm::dvec3>& S = patches_[static_cast<std::size_t>(chart)];
  const KnotVector &ku = S.knots(0), &kv = S.knots(1);
  const double su = ku.domain_max() - ku.domain_min(), sv = kv.domain_max() - kv.domain_min();
  u = clamp01(u), v = clamp01(v);
  auto at = [&](double a, double b) {
    return S.eval_second(ku.domain_min() + su * a, kv.domain_min() + sv * b);
  };
  auto d = at(u, v);
  DdmSurfacePoint q;
  q.p = d.value;
  q.du = su * d.du, q.dv = sv * d.dv;  // chain rule onto [0,1]²
  glm::dvec3 m = glm::cross(q.du, q.dv);
  double len = glm::length(m);
  const double scale = std::max(glm::length(q.du), glm::length(q.dv));
  if (!(len > 1e-12 * scale * scale)) {
    // A collapsed edge: the normal (and its derivatives) from a point slightly towards the patch centre.
    for (double step : {1e-4, 1e-3, 1e-2}) {
      const auto e = at(u + (0.5 - u) * step, v + (0.5 - v) * step);
      const glm::dvec3 m2 = glm::cross(su * e.du, sv * e.dv);
      if (glm::length(m2) > 1e-12 * scale * scale || step == 1e-2) {
        d.duu = e.duu, d.duv = e.duv, d.dvv = e.dvv, d.du = e.du, d.dv = e.dv;
        m = m2, len = glm::length(m2);
        break;
      }
    }
    if (!(len > 0.0)) return q;  // flat degenerate patch: no normal
  }
  q.n = m / len;
  // ∂m/∂u = S_uu × S_v + S_u × S_uv (on [0,1]²: scaled by su²·sv and su·sv·su); ∂n = (∂m − n (n·∂m)) / |m|.
  const glm::dvec3 Su = su * d.du, Sv = sv * d.dv, Suu = su * su * d.duu, Suv = su * sv * d.duv,
                   Svv = sv * sv * d.dvv;
  const glm::dvec3 mu = glm::cross(Suu, Sv) + glm::cross(Su, Suv);
  const glm::dvec3 mv = glm::cross(Suv, Sv) + glm::cross(Su, Svv);
  q.dn_du = (mu - q.n * glm::dot(q.n, mu)) / len;
  q.dn_dv = (mv - q.n * glm::dot(q.n, mv)) / len;
  return q;
}

std::vector<BSplineSurface<glm::dvec3>> teapot_body_patches() {
  // make_teapot stands the tessellated teapot on y = 0 with height 1 (uniform scale). Its lowest and highest points
  // are patch corners (the bottom's and the lid knob's poles), which every tessellation samples, so its y range is
  // that of the patch corners; the same affine map applied to the control points moves the patches exactly.
  Aabb raw;  // Newell units, y up
  for (int p = 0; p < detail::kTeapotPatchCount; ++p)
    for (int k : {0, 3, 12, 15}) raw.extend(glm::dvec3(0.0, detail::kTeapotVertices[detail::kTeapotPatches[p][k]][2], 0.0));
  const double scale = 1.0 / raw.size().y;
  const KnotVector bezier(4, {0, 0, 0, 0, 1, 1, 1, 1});
  std::vector<BSplineSurface<glm::dvec3>> out;
  for (int p = 4; p < 12; ++p) {
    std::vector<glm::dvec3> cps(16);
    for (int k = 0; k < 16; ++k) {  // as make_teapot: u fastest, (x, y, z) ↦ (x, z, −y)
      const double* q = detail::kTeapotVertices[detail::kTeapotPatches[p][k]];
      cps[k] = (glm::dvec3(q[0], q[2], -q[1]) - glm::dvec3(0.0, raw.lo.y, 0.0)) * scale;
    }
    out.emplace_back(bezier, bezier, std::move(cps));
  }
  return out;
}

const char* ddm_layout_name(DdmLayout l) {
  switch (l) {
    case DdmLayout::rect: return "rect";
    case DdmLayout::hex: return "hex";
    case DdmLayout::brick: return "brick";
  }
  return "rect";
}

std::vector<DdmInstance> ddm_layout_cells(DdmLayout layout, glm::ivec2 counts, int chart_count) {
  const int n = counts.x, m = counts.y;
  const int min_n = layout == DdmLayout::rect ? 1 : 2;
  if (n < min_n || m < 1)
    throw std::invalid_argument("counts: [" + std::to_string(n) + ", " + std::to_string(m) + "] gives an empty " +
                                ddm_layout_name(layout) + " layout (need n ≥ " + std::to_string(min_n) + ", m ≥ 1)");
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

TriMesh ddm_evaluate(const DdmBase& base, const DdmTile& tile, const std::vector<DdmInstance>& instances,
                     double height) {
  if (!std::isfinite(height) || !(height > 0.0))
    throw std::invalid_argument("height: must be finite and > 0, got " + std::to_string(height));
  const std::size_t nv = tile.mesh.vertex_count();
  if (tile.mesh.normals.size() != nv)
    throw std::invalid_argument("tile: '" + tile.name + "' has no per-vertex normals");
  for (const DdmInstance& inst : instances)
    if (inst.chart < 0 || inst.chart >= base.chart_count())
      throw std::invalid_argument("base: instance on chart " + std::to_string(inst.chart) + " of " +
                                  std::to_string(base.chart_count()));
  TriMesh out;
  out.positions.resize(nv * instances.size());
  out.normals.resize(nv * instances.size());
  out.triangles.reserve(tile.mesh.triangles.size() * instances.size());
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const DdmInstance& inst = instances[k];
    for (std::size_t v = 0; v < nv; ++v) {
      const glm::dvec3& t = tile.mesh.positions[v];
      const DdmSurfacePoint s = base.eval(inst.chart, inst.origin.x + inst.size.x * t.x, inst.origin.y + inst.size.y * t.y);
      const double wh = t.z * height;
      out.positions[k * nv + v] = s.p + wh * s.n;  // seed Eq. 5.2
      const glm::dmat3 J(inst.size.x * (s.du + wh * s.dn_du), inst.size.y * (s.dv + wh * s.dn_dv), height * s.n);
      const glm::dmat3 cof(glm::cross(J[1], J[2]), glm::cross(J[2], J[0]), glm::cross(J[0], J[1]));
      const glm::dvec3 n = cof * tile.mesh.normals[v];
      const double len = glm::length(n);
      out.normals[k * nv + v] = len > 0.0 && std::isfinite(len) ? n / len : s.n;
    }
    const auto off = static_cast<unsigned>(k * nv);
    for (const glm::uvec3& f : tile.mesh.triangles) out.triangles.push_back(f + glm::uvec3(off));
  }
  return out;
}

DdmTile ddm_morph(const DdmTile& a, const DdmTile& b, double alpha) {
  require_same_ddm_topology(a, b);
  if (!std::isfinite(alpha)) throw std::invalid_argument("alpha: must be finite");
  DdmTile out{a.name + "→" + b.name, a.mesh};
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

}  // namespace trispline::core
