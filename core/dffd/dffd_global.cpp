// Global DFFD construction around obstacles. See dffd_global.h. Sources: seed §6.3.1 (Eq. 6.1, Def. 6, Fig. 6.1,
// Theorem 6, Fig. 6.4), §6.3.2 (stitching level w_s).
#include "core/dffd/dffd_global.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/base/text.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {
namespace {

std::string num6(double x) { return printf_string("%.6g", x); }

std::string vec(const glm::dvec3& p) { return "(" + num6(p.x) + ", " + num6(p.y) + ", " + num6(p.z) + ")"; }

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

// Centre of mass of a closed triangle mesh (divergence theorem); the bounding-box centre if its volume vanishes.
glm::dvec3 centre_of_mass(const TriMesh& m) {
  double volume = 0.0;
  glm::dvec3 moment(0.0);
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const double v = glm::dot(a, glm::cross(b, c)) / 6.0;  // signed volume of the tetrahedron (0, a, b, c)
    volume += v;
    moment += v * (a + b + c) / 4.0;
  }
  const Aabb box = mesh_bounds(m);
  if (!(std::abs(volume) > 1e-12 * std::pow(std::max(box.diagonal(), 1e-300), 3.0))) return box.center();
  return moment / volume;
}

// A parameter within 1e-9 of an existing knot is that knot: otherwise a near-duplicate knot would make two control
// points (almost) coincide and the fold-over check (or the basis) would see a degenerate span.
double snap_to_knot(const KnotVector& kv, double t) {
  for (double k : kv.knots())
    if (std::abs(k - t) <= 1e-9) return k;
  return t;
}

}  // namespace

double dffd_kernel(DffdKernel kernel, double d, double width) {
  if (!(width > 0.0) || !std::isfinite(width)) throw std::invalid_argument("dffd_kernel: width must be > 0");
  const double x = std::abs(d) / width;  // 0 at the discontinuity plane, 1 at the support's end
  if (x >= 1.0) return 0.0;
  if (kernel == DffdKernel::gaussian) {
    // exp(−d²/2σ²) with σ = width/3, shifted and rescaled so κ(0) = 1 and κ(width) = 0 (continuous truncation).
    const double g = std::exp(-4.5 * x * x), g1 = std::exp(-4.5);
    return (g - g1) / (1.0 - g1);
  }
  // Uniform quadratic B-spline N₂ centred at 0 (support [−1.5, 1.5], N₂(0) = 0.75), scaled to [−width, width].
  const double t = 1.5 * x;
  const double n = t <= 0.5 ? 0.75 - t * t : 0.5 * (1.5 - t) * (1.5 - t);
  return n / 0.75;
}

Discontinuity find_discontinuity(const TrivariateBSpline<glm::dvec3>& F, int axis, double u0) {
  const KnotVector& kv = F.knots(axis);
  const std::vector<double>& U = kv.knots();
  const auto it = std::find(U.begin(), U.end(), u0);
  if (it == U.end() || kv.multiplicity(u0) < kv.order())
    throw std::invalid_argument("find_discontinuity: u0 = " + num6(u0) + " is not a C^-1 break of axis " +
                                std::to_string(axis));
  const int r = static_cast<int>(it - U.begin());
  return {axis, u0, r - 1, r};
}

namespace {

// The lattice's axes as world axes: u = the travel direction, w = orthogonal to the slicing planes, v = the third.
struct LatticeAxes {
  int u, v, w;
};

// A C⁻¹ break: obstacle index and its parameter u0 along the lattice's u.
struct PlacedBreak {
  std::size_t obstacle;
  double u0;
};

void validate(const TriMesh& object_world, const std::vector<DffdObstacle>& obstacles, const GlobalDffdParams& p) {
  // --- validation -------------------------------------------------------------------------------------------
  if (p.axis < 0 || p.axis > 2) throw DffdBuildError("axis must be x, y or z", "axis");
  if (p.w_axis < 0 || p.w_axis > 2) throw DffdBuildError("w_axis must be x, y or z", "w_axis");
  if (p.axis == p.w_axis)
    throw DffdBuildError(std::string("w_axis must differ from axis (both ") + axis_name(p.axis) + ")", "w_axis");
  for (int a = 0; a < 3; ++a) {
    if (p.order[a] < 2 || p.order[a] > 6)
      throw DffdBuildError("order must be 2..6 per axis, got " + std::to_string(p.order[a]), "order");
    if (p.controls[a] < p.order[a] || p.controls[a] > 64)
      throw DffdBuildError("controls must be between the order (" + std::to_string(p.order[a]) + ") and 64, got " +
                               std::to_string(p.controls[a]),
                           "controls");
  }
  if (!(p.kernel_width > 0.0) || !std::isfinite(p.kernel_width))
    throw DffdBuildError("kernel_width must be > 0 (world units), got " + num6(p.kernel_width), "kernel_width");
  if (!std::isfinite(p.margin)) throw DffdBuildError("margin must be finite", "margin");
  if (!(p.clearance >= 0.0) || !std::isfinite(p.clearance))
    throw DffdBuildError("clearance must be ≥ 0 (world units)", "clearance");
  if (obstacles.empty()) throw DffdBuildError("at least one obstacle is needed", "obstacles");
  if (object_world.positions.empty()) throw DffdBuildError("the object has no vertices", "object");
}

// The obstacles' bounding boxes (#O) and their union.
std::vector<Aabb> obstacle_boxes(const std::vector<DffdObstacle>& obstacles, Aabb& all) {
  std::vector<Aabb> obox(obstacles.size());
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    if (obstacles[i].world_mesh.empty())
      throw DffdBuildError("obstacle '" + obstacles[i].name + "' has no triangles", "obstacles");
    obox[i] = mesh_bounds(obstacles[i].world_mesh);
    all.extend(obox[i].lo);
    all.extend(obox[i].hi);
  }
  return obox;
}

// Step 1: the lattice box B, given (p.box, every obstacle inside it) or grown from the obstacles and the object.
Aabb lattice_box(const TriMesh& object_world, const std::vector<DffdObstacle>& obstacles, const std::vector<Aabb>& obox,
                 const Aabb& all, const GlobalDffdParams& p, const LatticeAxes& ax) {
  const int u_ax = ax.u, v_ax = ax.v, w_ax = ax.w;
  // --- 1. the lattice box B ------------------------------------------------------------------------------------
  Aabb box;
  if (p.box) {
    box = *p.box;
    if (!box.valid() || box.size()[0] <= 0 || box.size()[1] <= 0 || box.size()[2] <= 0)
      throw DffdBuildError("box must have lo < hi on every axis", "box");
    for (std::size_t i = 0; i < obstacles.size(); ++i)
      for (int a = 0; a < 3; ++a)
        if (obox[i].lo[a] < box.lo[a] || obox[i].hi[a] > box.hi[a])
          throw DffdBuildError("obstacle '" + obstacles[i].name + "' " + vec(obox[i].lo) + "–" + vec(obox[i].hi) +
                                   " is larger than the lattice box " + vec(box.lo) + "–" + vec(box.hi) + " (along " +
                                   axis_name(a) + "): grow the box or drop the obstacle",
                               "box");
  } else {
    const Aabb ob = mesh_bounds(object_world);
    const double margin = p.margin >= 0.0 ? p.margin : 1.05 * p.kernel_width;
    box.lo[u_ax] = all.lo[u_ax] - margin;
    box.hi[u_ax] = all.hi[u_ax] + margin;
    for (int a : {v_ax, w_ax}) {
      const double lo = std::min(all.lo[a], ob.lo[a]), hi = std::max(all.hi[a], ob.hi[a]);
      const double grow = std::max(0.02 * (hi - lo), 1e-6);
      box.lo[a] = lo - grow;
      box.hi[a] = hi + grow;
    }
    if (!(box.size()[u_ax] > 0.0)) throw DffdBuildError("the obstacles have no extent along axis", "margin");
  }
  return box;
}

// Step 2: the identity lattice of B (clamped uniform knots, control points at the Greville abscissae).
GlobalDffd identity_lattice(const Aabb& box, const GlobalDffdParams& p, const LatticeAxes& ax) {
  const int u_ax = ax.u, w_ax = ax.w;
  // --- 2. the uniform (identity) lattice -----------------------------------------------------------------------
  const Embedding embedding = embed_bounding_box({box.lo, box.hi}, EmbeddingAxes{u_ax, w_ax});
  const glm::dmat3 A_inv = glm::inverse(embedding.linear);
  const auto to_world = [&](const glm::dvec3& uvw) { return A_inv * (uvw - embedding.offset); };
  const std::array<KnotVector, 3> kv = {KnotVector::clamped_uniform(p.order[0], p.controls[0]),
                                        KnotVector::clamped_uniform(p.order[1], p.controls[1]),
                                        KnotVector::clamped_uniform(p.order[2], p.controls[2])};
  const std::array<std::vector<double>, 3> g = {kv[0].greville(), kv[1].greville(), kv[2].greville()};
  std::vector<glm::dvec3> cps;
  cps.reserve(std::size_t(p.controls[0]) * p.controls[1] * p.controls[2]);
  for (int k = 0; k < p.controls[2]; ++k)
    for (int j = 0; j < p.controls[1]; ++j)
      for (int i = 0; i < p.controls[0]; ++i) cps.push_back(to_world({g[0][i], g[1][j], g[2][k]}));
  GlobalDffd out{DffdRig{TrivariateBSpline<glm::dvec3>(kv[0], kv[1], kv[2], std::move(cps)), embedding}, box};
  DffdRig& rig = out.rig;
  rig.openings = p.openings;
  rig.eps = p.eps;
  rig.identity_outside = true;
  return out;
}

// Step 3: order knots in u at each obstacle's centre of mass (C⁻¹), order − 1 in v at its v-extremes. The breaks,
// sorted by u0; out.rig.discontinuities and out.v_knots are filled.
std::vector<PlacedBreak> insert_breaks(GlobalDffd& out, const std::vector<DffdObstacle>& obstacles,
                                       const std::vector<Aabb>& obox, const LatticeAxes& ax) {
  const int u_ax = ax.u;
  DffdRig& rig = out.rig;
  TrivariateBSpline<glm::dvec3>& F = rig.lattice;
  // --- 3. knots: C⁻¹ at each obstacle's centre of mass, order − 1 in v at its v-extremes ------------------------
  std::vector<PlacedBreak> placed;
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const double u0 = rig.embedding.apply(centre_of_mass(obstacles[i].world_mesh))[0];
    if (!(u0 > 0.0 && u0 < 1.0))
      throw DffdBuildError(
          "the centre of obstacle '" + obstacles[i].name + "' lies outside the lattice's domain (u = " + num6(u0) + ")",
          "obstacles");
    for (const PlacedBreak& q : placed)
      if (std::abs(q.u0 - u0) < 1e-9)
        throw DffdBuildError("obstacles '" + obstacles[q.obstacle].name + "' and '" + obstacles[i].name +
                                 "' have the same centre along " + axis_name(u_ax) + ": merge them into one obstacle",
                             "obstacles");
    placed.push_back({i, u0});
  }
  std::sort(placed.begin(), placed.end(), [](const PlacedBreak& a, const PlacedBreak& b) { return a.u0 < b.u0; });
  for (PlacedBreak& q : placed) {
    q.u0 = snap_to_knot(F.knots(0), q.u0);
    insert_discontinuity(F, 0, q.u0);
  }
  const int ov = F.knots(1).order();
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const double va = rig.embedding.apply(obox[i].lo)[1], vb = rig.embedding.apply(obox[i].hi)[1];
    for (double v : {std::min(va, vb), std::max(va, vb)}) {
      if (!(v > 0.0 && v < 1.0)) continue;
      v = snap_to_knot(F.knots(1), v);
      const int times = (ov - 1) - F.knots(1).multiplicity(v);
      if (times <= 0) continue;
      F.insert_knot(1, v, times);
      out.v_knots += static_cast<std::size_t>(times);
    }
  }
  for (const PlacedBreak& q : placed) rig.discontinuities.push_back(find_discontinuity(F, 0, q.u0));
  return placed;
}

// Steps 4 and 5: the F⁻/F⁺ control points of every row projected along u onto the obstacle's cross-section in W_k,
// the displacement spread by κ. Returns, per break, the rows (j) the obstacle opened.
std::vector<std::vector<char>> open_around_obstacles(GlobalDffd& out, const std::vector<PlacedBreak>& placed,
                                                     const std::vector<DffdObstacle>& obstacles,
                                                     const std::vector<Aabb>& obox, const GlobalDffdParams& p,
                                                     const LatticeAxes& ax) {
  const int u_ax = ax.u, v_ax = ax.v;
  const Aabb& box = out.box;
  DffdRig& rig = out.rig;
  TrivariateBSpline<glm::dvec3>& F = rig.lattice;
  // --- 4./5. projection onto C±(v) at every W_k, propagation by κ ----------------------------------------------
  const glm::ivec3 n = F.control_counts();
  const std::vector<glm::dvec3> original = F.control_points();
  std::vector<double> shift(original.size(), 0.0);  // world units along +axis, summed over obstacles
  std::vector<std::vector<char>> opened(placed.size(), std::vector<char>(std::size_t(n.y), 0));  // rows j with hits
  const double reach = box.size()[u_ax] + 1.0;
  for (std::size_t di = 0; di < placed.size(); ++di) {
    const std::size_t oi = placed[di].obstacle;
    const Discontinuity& d = rig.discontinuities[di];
    RayCaster caster(BuildQuality::high);
    caster.add_mesh(obstacles[oi].world_mesh);
    caster.commit();
    const double vlo = obox[oi].lo[v_ax], vhi = obox[oi].hi[v_ax];
    const double nudge = 1e-4 * std::max(vhi - vlo, 1e-9);
    for (int k = 0; k < n.z; ++k)
      for (int j = 0; j < n.y; ++j) {
        const glm::dvec3 pm = original[F.index(d.minus_plane, j, k)];
        glm::dvec3 ray_at = pm;
        // Rows exactly on the obstacle's v-extremes (the order − 1 knots) sample just inside, where C± is defined.
        if (ray_at[v_ax] < vlo - nudge || ray_at[v_ax] > vhi + nudge) continue;
        ray_at[v_ax] = std::clamp(ray_at[v_ax], vlo + nudge, vhi - nudge);
        glm::dvec3 dir(0.0);
        dir[u_ax] = 1.0;
        glm::dvec3 from_minus = ray_at, from_plus = ray_at;
        from_minus[u_ax] = box.lo[u_ax] - reach;
        from_plus[u_ax] = box.hi[u_ax] + reach;
        const auto hm = caster.intersect(from_minus, dir);
        const auto hp = caster.intersect(from_plus, -dir);
        if (!hm || !hp) continue;
        const double cm = hm->position[u_ax] - p.clearance, cp = hp->position[u_ax] + p.clearance;
        const double vm = cm - pm[u_ax];                                     // V⁻ (F⁻ moves back)
        const double vp = cp - original[F.index(d.plus_plane, j, k)][u_ax];  // V⁺ (F⁺ moves ahead)
        out.projected_points += 2;
        opened[di][std::size_t(j)] = 1;
        out.max_displacement = std::max({out.max_displacement, std::abs(vm), std::abs(vp)});
        for (int i = 0; i < n.x; ++i) {
          if (i == 0 || i == n.x - 1) continue;  // the box's faces stay put: F = E⁻¹ there
          const std::size_t idx = F.index(i, j, k);
          if (i <= d.minus_plane) {
            const double dist = pm[u_ax] - original[idx][u_ax];
            shift[idx] += (i == d.minus_plane ? 1.0 : dffd_kernel(p.kernel, dist, p.kernel_width)) * vm;
          } else {
            const double dist = original[idx][u_ax] - original[F.index(d.plus_plane, j, k)][u_ax];
            shift[idx] += (i == d.plus_plane ? 1.0 : dffd_kernel(p.kernel, dist, p.kernel_width)) * vp;
          }
        }
      }
  }
  for (std::size_t idx = 0; idx < shift.size(); ++idx) F.control_points()[idx][u_ax] += shift[idx];
  return opened;
}

// Step 6 (seed Theorem 6): the u-components must increase along every row (j, k); folds are listed in out.folds and
// out.rig.fold_points, and refused (DffdBuildError "kernel_width") when p.reject_fold.
void check_folds(GlobalDffd& out, const GlobalDffdParams& p, const LatticeAxes& ax) {
  const int u_ax = ax.u;
  const Aabb& box = out.box;
  DffdRig& rig = out.rig;
  TrivariateBSpline<glm::dvec3>& F = rig.lattice;
  const glm::ivec3 n = F.control_counts();
  // --- 6. fold-over check (Theorem 6): u-components increase along every (j, k) --------------------------------
  const double tol = 1e-9 * box.diagonal();
  auto is_break = [&](int i) {
    for (const Discontinuity& d : rig.discontinuities)
      if (i == d.minus_plane) return true;
    return false;
  };
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i + 1 < n.x; ++i) {
        const double du = F.control_point(i + 1, j, k)[u_ax] - F.control_point(i, j, k)[u_ax];
        if (is_break(i) ? du >= -tol : du > tol) continue;
        out.folds.push_back({{i, j, k}, F.control_point(i, j, k)});
      }
  if (!out.folds.empty() && p.reject_fold) {
    const DffdFold& f = out.folds.front();
    throw DffdBuildError("fold-over: " + std::to_string(out.folds.size()) +
                             " control point pair(s) break the u-order of the lattice (seed Theorem 6, det J ≤ 0), "
                             "first at (i,j,k) = (" +
                             std::to_string(f.index.x) + "," + std::to_string(f.index.y) + "," +
                             std::to_string(f.index.z) + "), world " + vec(f.position) +
                             ": widen kernel_width, add controls along u, or pass \"fold\":\"warn\" to keep it",
                         "kernel_width");
  }
  for (const DffdFold& f : out.folds) rig.fold_points.push_back(f.position);
}

// The object's parameters and step 7: with stitched openings, both discontinuity planes of the opened rows moved to
// the level w_s (seed §6.3.2).
void embed_and_stitch(GlobalDffd& out, const TriMesh& object_world, const std::vector<std::vector<char>>& opened,
                      const GlobalDffdParams& p, const LatticeAxes& ax) {
  const int w_ax = ax.w;
  DffdRig& rig = out.rig;
  TrivariateBSpline<glm::dvec3>& F = rig.lattice;
  const glm::ivec3 n = F.control_counts();
  const glm::dmat3 A_inv = glm::inverse(rig.embedding.linear);
  const auto to_world = [&](const glm::dvec3& uvw) { return A_inv * (uvw - rig.embedding.offset); };
  // --- parameters of the object, 7. stitching -------------------------------------------------------------------
  rig.params = embed_points(rig.embedding, object_world.positions);
  // Both seam states are kept with capped or stitched openings (dffd.animate keys the seam between them); the rig's
  // lattice is the one `openings` asks for.
  if (p.openings != DffdOpenings::open) {
    auto seam = std::make_shared<DffdSeam>();
    seam->open_points = F.control_points();
    std::vector<glm::dvec3> shifted = rig.params;
    for (glm::dvec3& q : shifted) q += p.offset;
    for (const Discontinuity& d : rig.discontinuities) {
      // w_s: the mean w of the vertices the split puts on u = u0 (seed §6.3.2); if the object does not reach the
      // cut at this offset, the mean w of all its vertices inside the box's w-range.
      const MeshSplit s = split_mesh_at_parameter(object_world, shifted, 0, d.u0, 0.0);
      double sum = 0.0;
      std::size_t count = 0;
      for (std::size_t v = object_world.vertex_count(); v < s.params.size(); ++v) {
        sum += s.params[v][2];
        ++count;
      }
      if (count == 0)
        for (const glm::dvec3& q : shifted) {
          sum += std::clamp(q[2], 0.0, 1.0);
          ++count;
        }
      const double ws = std::clamp(sum / double(count), 0.0, 1.0);
      if (p.openings == DffdOpenings::stitch) out.w_s.push_back(ws);
      const double world_w = to_world({0.0, 0.0, ws})[w_ax];
      // Only the rows the obstacle opened: elsewhere F⁻ = F⁺ already closes the seam, and flattening those rows
      // too would pinch the object's whole cross-section to one curve (see docs/decisions.md).
      const std::size_t di = std::size_t(&d - rig.discontinuities.data());
      for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j) {
          if (!opened[di][std::size_t(j)]) continue;
          F.control_point(d.minus_plane, j, k)[w_ax] = world_w;
          F.control_point(d.plus_plane, j, k)[w_ax] = world_w;
        }
    }
    seam->stitched_points = F.control_points();
    if (p.openings == DffdOpenings::cap) F.control_points() = seam->open_points;
    rig.seam = std::move(seam);
  }
}

}  // namespace

GlobalDffd build_global_dffd(const TriMesh& object_world, const std::vector<DffdObstacle>& obstacles,
                             const GlobalDffdParams& p) {
  validate(object_world, obstacles, p);
  const LatticeAxes ax{p.axis, 3 - p.axis - p.w_axis, p.w_axis};
  Aabb all;
  const std::vector<Aabb> obox = obstacle_boxes(obstacles, all);
  const Aabb box = lattice_box(object_world, obstacles, obox, all, p, ax);
  GlobalDffd out = identity_lattice(box, p, ax);
  const std::vector<PlacedBreak> placed = insert_breaks(out, obstacles, obox, ax);
  const std::vector<std::vector<char>> opened = open_around_obstacles(out, placed, obstacles, obox, p, ax);
  check_folds(out, p, ax);
  embed_and_stitch(out, object_world, opened, p, ax);
  for (const DffdObstacle& o : obstacles) out.rig.obstacles.push_back(o.name);
  return out;
}

}  // namespace trispline::core
