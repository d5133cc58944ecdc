// The incision's frame (stroke → G, N) and local lattice (seed §6.4, Eq. 6.2), and point inversion.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/dffd/dffd.h"
#include "core/incision/incision_lattice.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/camera.h"
#include "core/spline/fitting.h"

namespace trispline::core {
namespace {
bool finite3(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
}  // namespace

std::optional<IncisionFrame> fit_incision_frame(const std::vector<glm::dvec2>& stroke_px, const Camera& camera,
                                                const RayCaster& surface) {
  std::vector<glm::dvec3> hits, normals;
  for (const glm::dvec2& px : stroke_px) {
    if (!std::isfinite(px.x) || !std::isfinite(px.y)) continue;
    const std::optional<RayHit> h = surface.intersect(camera.eye, camera.ray_direction(px));
    if (!h) continue;
    if (!hits.empty() && glm::length(h->position - hits.back()) <= 1e-12 * (1.0 + glm::length(h->position)))
      continue;  // the same point twice (a pause in the drag) adds nothing to the fit
    hits.push_back(h->position);
    normals.push_back(h->normal);
  }
  if (hits.size() < 2) return std::nullopt;
  double length = 0.0;
  for (std::size_t i = 1; i < hits.size(); ++i) length += glm::length(hits[i] - hits[i - 1]);
  if (!(length > 0.0)) return std::nullopt;
  const std::vector<double> t = parametrize(hits, Parametrization::ChordLength);
  const int H = static_cast<int>(hits.size());
  const int order = std::min(4, H);
  const int count = std::clamp(H / 3, order, 16);
  try {
    IncisionFrame f{hits, normals, fit_curve(hits, t, order, count), fit_curve(normals, t, order, count)};
    return f;
  } catch (const std::invalid_argument&) {  // hits the least-squares fit cannot use (e.g. all but two coincide)
    return std::nullopt;
  }
}

namespace incision_detail {
namespace {
double kernel_u(IncisionKernel k, double d) {  // d = |ū − 1/2| ∈ [0, 1/2]
  d = std::min(std::abs(d), 0.5);
  if (k == IncisionKernel::gaussian) {
    const double s2 = 2.0 * 0.2 * 0.2, floor = std::exp(-0.25 / s2);
    return std::max(0.0, (std::exp(-d * d / s2) - floor) / (1.0 - floor));
  }
  const double x = 3.0 * d;
  const double b = x <= 0.5 ? 0.75 - x * x : x <= 1.5 ? 0.5 * (1.5 - x) * (1.5 - x) : 0.0;
  return b / 0.75;
}

// Value of the scalar B-spline with knots kv and control values c at t.
double eval_scalar(const KnotVector& kv, const std::vector<double>& c, double t) {
  return BSplineCurve<double>(kv, c).eval(t);
}
// Checks p and returns the control counts (l, m, n) of Eq. 6.2 (defaults filled in from the hit count).
glm::ivec3 lattice_controls(const IncisionFrame& frame, const IncisionParams& p) {
  if (!(std::isfinite(p.width) && p.width > 0.0)) throw std::invalid_argument("width: must be a finite number > 0");
  if (!(std::isfinite(p.depth) && p.depth > 0.0))
    throw std::invalid_argument("depth: must be > 0 (zero depth: the cut must go below the surface)");
  if (!(std::isfinite(p.opening) && p.opening >= 0.0)) throw std::invalid_argument("opening: must be ≥ 0");
  if (p.order < 2 || p.order > 4) throw std::invalid_argument("order: must be in 2..4");
  if (p.wall_rows < 1 || p.wall_rows > 32) throw std::invalid_argument("wall_rows: must be in 1..32");
  if (!(p.eps > 0.0 && p.eps <= 1e-3)) throw std::invalid_argument("eps: must be in (0, 1e-3]");
  const int o = p.order;
  const int H = static_cast<int>(frame.hits.size());
  const int l = p.controls_u > 0 ? p.controls_u : std::max(7, o % 2 ? o : o + 1);
  const int m = p.controls_v > 0 ? p.controls_v : std::clamp(H / 3, o, 24);
  const int n = p.controls_w > 0 ? p.controls_w : std::max(5, o % 2 ? o : o + 1);
  if (l % 2 == 0 || l < std::max(3, o) || l > 31)
    throw std::invalid_argument("controls: l must be odd and in max(3, order)..31");
  if (m < o || m > 64) throw std::invalid_argument("controls: m must be in order..64");
  if (n % 2 == 0 || n < std::max(3, o) || n > 31)
    throw std::invalid_argument("controls: n must be odd and in max(3, order)..31");
  return {l, m, n};
}

// Frame at v: G, unit T, unit N ⊥ T, S = T × N (world units; throws on a degenerate stroke).
void frame_at(const IncisionFrame& frame, double v, glm::dvec3& g, glm::dvec3& s, glm::dvec3& nn) {
  const std::vector<glm::dvec3> d = frame.generator.derivatives(v, 1);
  g = d[0];
  const double tl = glm::length(d[1]);
  glm::dvec3 nv = frame.normal.eval(v);
  if (!(tl > 0.0) || !finite3(nv)) throw std::invalid_argument("stroke: the fitted generator curve is degenerate");
  const glm::dvec3 tt = d[1] / tl;
  nv -= glm::dot(nv, tt) * tt;
  const double nl = glm::length(nv);
  if (!(nl > 1e-9)) throw std::invalid_argument("stroke: the surface normals run along the stroke");
  nn = nv / nl;
  s = glm::cross(tt, nn);
}

// The cut's bottom: F(1/2, v, w) = Σ_j B_j(v)(G_j − (g(w) − ⌊n/2⌋)·β·N_j) with g(w) = Σ_k B_k(w)·k (monotone);
// returns w where g(w) = ⌊n/2⌋ + depth/β, by bisection on [1/2, 1].
double cut_bottom_w(const KnotVector& kw, int n, double depth, double beta) {
  std::vector<double> kidx(n);
  for (int k = 0; k < n; ++k) kidx[k] = k;
  const double target = n / 2 + depth / beta;
  double lo = 0.5, hi = 1.0;
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    (eval_scalar(kw, kidx, mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Opening: D_ijk = ±(opening/2)·c·κ(ū_i)·τ_v(v̄_j)·τ_w(k)·S_j, F⁻ side (u < 1/2, the +S side) towards +S, into
// L.offset (L.split's knots). gv: the Greville abscissae of kv (#m); Sj: unit S at them; minus_plane: the last
// control plane of F⁻; k_bottom: the w index with B_k(bottom_w) = 1. Throws when the opened lattice folds over.
void build_opening(LocalLattice& L, const IncisionParams& p, const KnotVector& kv, const std::vector<double>& gv,
                   const std::vector<glm::dvec3>& Sj, int minus_plane, int k_bottom) {
  const int m = static_cast<int>(gv.size());
  const glm::ivec3 cnt = L.split.control_counts();
  const std::vector<double> gu = L.split.knots(0).greville(), gww = L.split.knots(2).greville();
  std::vector<double> tau_v(m), tau_w(cnt.z, 0.0);
  for (int j = 0; j < m; ++j) tau_v[j] = std::sin(M_PI * std::clamp(gv[j], 0.0, 1.0));
  tau_v.front() = tau_v.back() = 0.0;
  for (int k = 0; k < std::min(k_bottom, cnt.z); ++k)
    tau_w[k] = std::clamp((L.bottom_w - gww[k]) / (L.bottom_w - 0.5), 0.0, 1.0);
  // Normalise so the gap at G(1/2) (u = 1/2∓, v = w = 1/2) is `opening`.
  const double sv = eval_scalar(kv, tau_v, 0.5), sw = eval_scalar(L.split.knots(2), tau_w, 0.5);
  const double scale = (sv > 0.0 && sw > 0.0) ? 0.5 * p.opening / (sv * sw) : 0.0;
  std::vector<glm::dvec3> dcp(L.split.control_points().size(), glm::dvec3(0.0));
  L.offset = TrivariateBSpline<glm::dvec3>(L.split.knots(0), L.split.knots(1), L.split.knots(2), dcp);
  for (int k = 0; k < cnt.z; ++k)
    for (int j = 0; j < cnt.y; ++j)
      for (int i = 0; i < cnt.x; ++i) {
        const double sign = i <= minus_plane ? 1.0 : -1.0;
        L.offset.control_point(i, j, k) = sign * scale * kernel_u(p.kernel, gu[i] - 0.5) * tau_v[j] * tau_w[k] * Sj[j];
      }
  // Fold-over check (seed Theorem 6): along u the opened control points must keep their order across S.
  for (int k = 0; k < cnt.z; ++k)
    for (int j = 0; j < cnt.y; ++j)
      for (int i = 0; i + 1 < cnt.x; ++i) {
        const glm::dvec3 a = L.split.control_point(i, j, k) + L.offset.control_point(i, j, k);
        const glm::dvec3 b = L.split.control_point(i + 1, j, k) + L.offset.control_point(i + 1, j, k);
        if (glm::dot(b - a, Sj[j]) > 1e-9 * p.width)
          throw std::invalid_argument("opening: " + std::to_string(p.opening) + " is too wide for width " +
                                      std::to_string(p.width) + " (the opened lattice folds over; seed Theorem 6)");
      }
}

// Frame samples for the inversion's initial guess: 8·m + 1 values of v, uniform in [0, 1].
void sample_frame(LocalLattice& L, const IncisionFrame& frame, int m) {
  const int K = 8 * m + 1;
  for (int s = 0; s < K; ++s) {
    const double v = double(s) / (K - 1);
    glm::dvec3 g, sv3, nn;
    frame_at(frame, v, g, sv3, nn);
    const glm::dvec3 dg = frame.generator.derivatives(v, 1)[1];
    L.sample_t.push_back(glm::normalize(dg));
    L.sample_speed.push_back(glm::length(dg));
    L.sample_v.push_back(v);
    L.sample_g.push_back(g);
    L.sample_s.push_back(sv3);
    L.sample_n.push_back(nn);
  }
}
}  // namespace

LocalLattice build_local_lattice(const IncisionFrame& frame, const IncisionParams& p) {
  const glm::ivec3 controls = lattice_controls(frame, p);
  const int o = p.order, l = controls.x, m = controls.y, n = controls.z;
  LocalLattice L{p,
                 {l, m, n},
                 0.0,
                 0.0,
                 0.0,
                 0.0,
                 TrivariateBSpline<glm::dvec3>(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                                               KnotVector::clamped_uniform(2, 2), std::vector<glm::dvec3>(8)),
                 TrivariateBSpline<glm::dvec3>(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                                               KnotVector::clamped_uniform(2, 2), std::vector<glm::dvec3>(8)),
                 TrivariateBSpline<glm::dvec3>(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                                               KnotVector::clamped_uniform(2, 2), std::vector<glm::dvec3>(8)),
                 {},
                 {},
                 {},
                 {}};
  const int hl = l / 2, hn = n / 2;
  L.alpha = p.width / hl;                                        // Eq. 6.2: ±⌊l/2⌋α = ±width across the cut
  L.half_height = std::max(4.0 / 3.0 * p.depth, 0.5 * p.width);  // reaches 1/3 below the depth, and above the sag
  L.beta = L.half_height / hn;

  const KnotVector ku = KnotVector::clamped_uniform(o, l), kv = KnotVector::clamped_uniform(o, m),
                   kw = KnotVector::clamped_uniform(o, n);
  const std::vector<double> gv = kv.greville();
  std::vector<glm::dvec3> cps(static_cast<std::size_t>(l) * m * n);
  std::vector<glm::dvec3> Sj(m), Gj(m), aS(m), bN(m);
  L.base = TrivariateBSpline<glm::dvec3>(ku, kv, kw, std::vector<glm::dvec3>(cps.size()));
  for (int j = 0; j < m; ++j) {
    glm::dvec3 g, s, nn;
    frame_at(frame, gv[j], g, s, nn);
    Sj[j] = s, Gj[j] = g, aS[j] = L.alpha * s, bN[j] = L.beta * nn;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < l; ++i)
        L.base.control_point(i, j, k) = g + double(hl - i) * L.alpha * s + double(hn - k) * L.beta * nn;
  }

  std::vector<double> au(l), cw(n);
  for (int i = 0; i < l; ++i) au[i] = hl - i;
  for (int k = 0; k < n; ++k) cw[k] = hn - k;
  L.g_hat.emplace(kv, Gj), L.s_hat.emplace(kv, aS), L.n_hat.emplace(kv, bN);
  L.a_of_u.emplace(ku, au), L.c_of_w.emplace(kw, cw);
  L.bottom_w = cut_bottom_w(kw, n, p.depth, L.beta);

  // Discontinuity at u = 1/2 (order knots) and C⁰ at the bottom (order − 1 knots) so the opening ends there exactly.
  L.split = L.base;
  const Discontinuity disc = insert_discontinuity(L.split, 0, 0.5);
  const int mult_b = L.split.knots(2).multiplicity(L.bottom_w);
  if (o - 1 - mult_b > 0) L.split.insert_knot(2, L.bottom_w, o - 1 - mult_b);
  const std::vector<double>& tw = L.split.knots(2).knots();
  int first_b = 0;
  while (first_b < static_cast<int>(tw.size()) && tw[first_b] < L.bottom_w - 1e-14) ++first_b;
  const int k_bottom = first_b - 1;  // B_{k_bottom}(bottom_w) = 1

  build_opening(L, p, kv, gv, Sj, disc.minus_plane, k_bottom);
  sample_frame(L, frame, m);
  return L;
}

glm::dvec3 eval_base(const LocalLattice& L, const glm::dvec3& q, glm::dvec3* d) {
  if (!d)
    return L.g_hat->eval(q.y) + L.a_of_u->eval(q.x) * L.s_hat->eval(q.y) + L.c_of_w->eval(q.z) * L.n_hat->eval(q.y);
  const std::vector<glm::dvec3> g = L.g_hat->derivatives(q.y, 1), s = L.s_hat->derivatives(q.y, 1),
                                n = L.n_hat->derivatives(q.y, 1);
  const std::vector<double> a = L.a_of_u->derivatives(q.x, 1), c = L.c_of_w->derivatives(q.z, 1);
  d[0] = a[1] * s[0];
  d[1] = g[1] + a[0] * s[1] + c[0] * n[1];
  d[2] = c[1] * n[0];
  return g[0] + a[0] * s[0] + c[0] * n[0];
}

Located invert_point(const LocalLattice& L, const glm::dvec3& x) {
  Located out;
  // Initial guess from the frame: nearest sample of G, then offsets along S, T and N (Eq. 6.2 read backwards).
  std::size_t best = 0;
  double bd = 1e300;
  for (std::size_t s = 0; s < L.sample_g.size(); ++s) {
    const glm::dvec3 d = x - L.sample_g[s];
    const double dd = glm::dot(d, d);
    if (dd < bd) bd = dd, best = s;
  }
  const glm::dvec3 d = x - L.sample_g[best];
  const double off_s = glm::dot(d, L.sample_s[best]), off_n = glm::dot(d, L.sample_n[best]);
  const double off_t = L.sample_speed[best] > 0.0 ? glm::dot(d, L.sample_t[best]) / L.sample_speed[best] : 0.0;
  const int l = L.controls.x, n = L.controls.z;
  out.param =
      glm::dvec3((l / 2 - off_s / L.alpha) / (l - 1), L.sample_v[best] + off_t, (n / 2 - off_n / L.beta) / (n - 1));
  const double reach = L.params.width, tall = L.half_height;
  if (std::abs(off_s) > 1.5 * reach || std::abs(off_n) > 1.5 * tall || out.param.y < -0.25 || out.param.y > 1.25)
    return out;
  const glm::dvec3 guess = glm::clamp(out.param, glm::dvec3(0.0), glm::dvec3(1.0));

  const double tol = 1e-10 * (reach + tall);
  glm::dvec3 q = guess;
  glm::dvec3 dd[3];
  glm::dvec3 r = eval_base(L, q, dd) - x;
  double rn = glm::length(r);
  for (int it = 0; it < 40 && rn > tol; ++it) {
    const glm::dmat3 J(dd[0], dd[1], dd[2]);
    const double det = glm::determinant(J);
    if (!(std::abs(det) > 1e-300)) break;
    const glm::dvec3 step = -(glm::inverse(J) * r);
    double lambda = 1.0;
    bool improved = false;
    for (int h = 0; h < 12; ++h, lambda *= 0.5) {
      const glm::dvec3 c = glm::clamp(q + lambda * step, glm::dvec3(0.0), glm::dvec3(1.0));
      glm::dvec3 dc[3];
      const glm::dvec3 rc = eval_base(L, c, dc) - x;
      const double rcn = glm::length(rc);
      if (rcn < rn) {
        q = c, r = rc, rn = rcn, improved = true;
        dd[0] = dc[0], dd[1] = dc[1], dd[2] = dc[2];
        break;
      }
    }
    if (!improved) break;
  }
  const double loose = 1e-6 * (reach + tall);
  if (rn <= loose) {  // converged (to the loose tolerance when Newton stalled in the last digits)
    out.param = q, out.inside = true;
    return out;
  }
  // Not converged. A point outside the range stalls on the domain's boundary with a large residual.
  const bool on_boundary = q.x <= 0.0 || q.x >= 1.0 || q.y <= 0.0 || q.y >= 1.0 || q.z <= 0.0 || q.z >= 1.0;
  if (on_boundary) return out;
  // Fallback (seed §6.4): the frame's guess, u from the offset across the cut, v = argmin ‖G(v) − x‖.
  out.param = guess, out.inside = true, out.fallback = true;
  return out;
}

}  // namespace incision_detail

TrivariateBSpline<glm::dvec3> incision_lattice(const IncisionFrame& frame, const IncisionParams& params) {
  return incision_detail::build_local_lattice(frame, params).base;
}

}  // namespace trispline::core
