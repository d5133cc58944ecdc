#include "bench/bounds_bench.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <random>
#include <stdexcept>

#include "bench/ffd_bench.h"
#include "bench/seed_cube.h"
#include "core/ffd/deformation_bounds.h"
#include "core/ffd/ffd.h"
#include "core/ffd/fold_certificate.h"
#include "core/ffd/refine.h"
#include "core/mesh/mesh_io.h"
#include "core/spline/knot_vector.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

namespace {

// The identity map on [0,1]³ (controls at the Greville abscissae), each control point displaced by N(0, sigma²).
TrivariateBSpline<glm::dvec3> displaced_lattice(int order, const glm::ivec3& controls, double sigma,
                                                std::mt19937& rng) {
  const KnotVector ku = KnotVector::clamped_uniform(order, controls.x),
                   kv = KnotVector::clamped_uniform(order, controls.y),
                   kw = KnotVector::clamped_uniform(order, controls.z);
  const auto gu = ku.greville(), gv = kv.greville(), gw = kw.greville();
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<glm::dvec3> P;
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i)
        P.push_back(glm::dvec3(gu[i], gv[j], gw[k]) + glm::dvec3(noise(rng), noise(rng), noise(rng)));
  return TrivariateBSpline<glm::dvec3>(ku, kv, kw, std::move(P));
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Median and largest of `v` (sorted in place); zeros when empty.
nlohmann::json spread(std::vector<double>& v) {
  std::sort(v.begin(), v.end());
  return {{"count", v.size()}, {"median", v.empty() ? 0.0 : v[v.size() / 2]}, {"worst", v.empty() ? 0.0 : v.back()}};
}

// The soundness sweep of the per-triangle bounds: every triangle of `mesh` in random lattices (orders 2–4, 4–8
// controls per axis, displacements 5–30 % of a cell) until `target` triangles are checked; per triangle each
// method's bound against the measured error (grid, finer grids, Newton), and the normal bound against the measured
// error along the drawn triangle's normal. Counts the triangles whose measured error exceeds a bound (must be 0).
nlohmann::json bound_soundness(const TriMesh& mesh, std::size_t target) {
  const ErrorBound methods[] = {ErrorBound::right_triangle, ErrorBound::circumcircle, ErrorBound::enclosing_circle,
                                ErrorBound::best};
  constexpr int kMethods = 4;
  const Embedding e = embed_bounding_box(mesh.positions, EmbeddingAxes{});
  const std::vector<glm::dvec3> params = embed_points(e, mesh.positions);
  std::size_t checked = 0, unbounded = 0, lattices = 0;
  std::atomic<std::size_t> exceeded[kMethods + 1] = {};
  std::vector<double> ratios[kMethods + 1];
  const auto t0 = std::chrono::steady_clock::now();
  while (checked < target && !mesh.triangles.empty()) {
    const int order = 2 + lattices % 3, controls = std::max(order, 4 + int(lattices % 5));
    const double perturbation = 0.05 + 0.25 * double(lattices % 6) / 5.0;
    const auto F = perturbed_lattice(e, order, controls, perturbation, 100 + std::uint32_t(lattices));
    ++lattices;
    const SecondDerivativeBounds b(F);
    const std::size_t n = std::min(mesh.triangles.size(), target - checked);
    struct Row {
      double bound[kMethods + 1], truth[2];
    };
    std::vector<Row> rows(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t f = r.begin(); f != r.end(); ++f) {
        const glm::uvec3 t = mesh.triangles[f];
        const glm::dvec3 &pa = params[t.x], &pb = params[t.y], &pc = params[t.z];
        Row& row = rows[f];
        for (int m = 0; m < kMethods; ++m) row.bound[m] = triangle_error_bound(b, pa, pb, pc, methods[m]);
        row.truth[0] = triangle_error_sampled(F, pa, pb, pc, 4);
        const glm::dvec3 normal = glm::cross(F.eval(pa) - F.eval(pc), F.eval(pb) - F.eval(pc));
        row.bound[kMethods] = row.truth[1] = -1.0;
        if (glm::length(normal) > 0.0) {
          const glm::dvec3 nn = glm::normalize(normal);
          row.bound[kMethods] = triangle_normal_error_bound(b, pa, pb, pc, nn);
          row.truth[1] = triangle_normal_error_sampled(F, pa, pb, pc, nn, 4);
        }
        for (int m = 0; m <= kMethods; ++m) {
          const double truth = row.truth[m == kMethods ? 1 : 0];
          if (truth >= 0.0 && row.bound[m] * (1.0 + 1e-12) + 1e-15 < truth) ++exceeded[m];
        }
      }
    });
    for (const Row& row : rows) {
      if (std::isinf(row.bound[kMethods - 1])) ++unbounded;
      for (int m = 0; m <= kMethods; ++m) {
        const double truth = row.truth[m == kMethods ? 1 : 0];
        if (truth > 1e-12 && std::isfinite(row.bound[m])) ratios[m].push_back(row.bound[m] / truth);
      }
    }
    checked += n;
  }
  nlohmann::json per_method = nlohmann::json::object();
  for (int m = 0; m <= kMethods; ++m)
    per_method[m == kMethods ? "normal" : error_bound_name(methods[m])] = {{"exceeded", exceeded[m].load()},
                                                                           {"tightness", spread(ratios[m])}};
  return {{"triangles", checked},
          {"lattices", lattices},
          {"unbounded", unbounded},
          {"methods", per_method},
          {"ms", ms_since(t0)}};
}

// Certified refinement (mesh.refine "error":"bound") of the seed's cube under its two deformations at three
// tolerances, with the seed's split (midpoint RefineTriangle), the Greville split point and the per-triangle choice.
nlohmann::json cube_refinement() {
  const TriMesh cube = seed_cube();
  nlohmann::json rows = nlohmann::json::array();
  for (int def = 0; def < 2; ++def)
    for (double tol : {0.04, 0.02, 0.01}) {
      const FfdBinding b = def == 0 ? seed_cube_bend_twist(cube) : seed_cube_corner_pull(cube);
      nlohmann::json row = {{"deformation", def == 0 ? "bend_twist" : "corner_pull"}, {"tolerance", tol}};
      for (RefineCriterion c : {RefineCriterion::Midpoint, RefineCriterion::Greville, RefineCriterion::Best}) {
        RefineOptions o;
        o.tolerance = tol;
        o.criterion = c;
        o.error = RefineError::bound;
        o.max_iterations = 40;
        const auto t0 = std::chrono::steady_clock::now();
        const RefineResult r = refine_for_ffd(cube, b, o);
        row[refine_criterion_name(c)] = {{"triangles", r.stats.triangles_after},
                                         {"max_bound", r.stats.max_triangle_bound},
                                         {"stopped_by", r.stats.stopped_by},
                                         {"ms", ms_since(t0)}};
      }
      row["best_over_midpoint"] =
          double(row["best"]["triangles"].get<std::size_t>()) / double(row["midpoint"]["triangles"].get<std::size_t>());
      rows.push_back(row);
    }
  return rows;
}

}  // namespace

nlohmann::json run_bounds_benchmark(const BoundsBenchOptions& options) {
  if (options.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  if (options.lattices < 0) throw std::invalid_argument("--lattices must be at least 0");
  if (options.soundness_triangles < 0) throw std::invalid_argument("--soundness-triangles must be at least 0");
  nlohmann::json out = {{"bench", "bounds"},
                        {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)}};
  nlohmann::json rows = nlohmann::json::array();
  for (int order : {3, 4})
    for (int n : {4, 8, 16}) {
      std::mt19937 rng(17);
      // Displacements of 2 % of a control spacing: far from folding, so every cell is judged in full.
      const auto F = displaced_lattice(order, glm::ivec3(n), 0.02 / n, rng);
      FoldCertificate c, e;
      FoldCertificateOptions exact;
      exact.quick_test = false;  // every cell through the Bernstein form: the cost when the quick test cannot decide
      double best = INFINITY, best_exact = INFINITY;
      for (int r = 0; r < options.repeats; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        c = certify_fold_free(F);
        best = std::min(best, ms_since(t0));
        t0 = std::chrono::steady_clock::now();
        e = certify_fold_free(F, exact);
        best_exact = std::min(best_exact, ms_since(t0));
      }
      rows.push_back({{"order", order},
                      {"controls", n},
                      {"cells", c.cells},
                      {"boxes", c.boxes},
                      {"quick_cells", c.quick_cells},
                      {"verdict", fold_verdict_name(c.verdict)},
                      {"ms", best},
                      {"exact_boxes", e.boxes},
                      {"exact_verdict", fold_verdict_name(e.verdict)},
                      {"exact_ms", best_exact}});
    }
  out["certificate"] = rows;
  std::mt19937 rng(23);
  std::size_t counts[3] = {0, 0, 0}, sampled_folds = 0, unsound = 0, false_folds = 0;
  constexpr int kGrid = 12;
  for (int trial = 0; trial < options.lattices; ++trial) {
    const int order = 2 + trial % 3;
    const glm::ivec3 controls(order + (trial % 3), order + ((trial / 3) % 3), order + ((trial / 9) % 3));
    // Displacements of 5 % to 60 % of the control spacing.
    const double spacing = 1.0 / (std::max({controls.x, controls.y, controls.z}) - 1);
    const auto F = displaced_lattice(order, controls, (0.05 + 0.55 * (trial % 8) / 7.0) * spacing, rng);
    const FoldCertificate c = certify_fold_free(F);
    ++counts[static_cast<int>(c.verdict)];
    double mn = INFINITY;
    for (int k = 0; k < kGrid; ++k)
      for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i)
          mn = std::min(mn,
                        jacobian_determinant(F, glm::dvec3((i + 0.5) / kGrid, (j + 0.5) / kGrid, (k + 0.5) / kGrid)));
    if (mn <= 0.0) {
      ++sampled_folds;
      if (c.verdict == FoldVerdict::fold_free) ++unsound;
    }
    for (const glm::dvec3& t : c.fold_params)
      if (jacobian_determinant(F, t) > 1e-9) ++false_folds;
  }
  out["sweep"] = {{"lattices", options.lattices},
                  {"fold_free", counts[static_cast<int>(FoldVerdict::fold_free)]},
                  {"fold", counts[static_cast<int>(FoldVerdict::fold)]},
                  {"undecided", counts[static_cast<int>(FoldVerdict::undecided)]},
                  {"sampled_folds", sampled_folds},
                  {"certified_but_sampled_fold", unsound},
                  {"fold_reported_at_positive_det", false_folds}};
  // Per-triangle bounds on the FFD benchmark's mesh, tri-cubic 8³ lattice perturbed by 15 % of a cell.
  FfdBenchOptions mesh_options;
  mesh_options.mesh_path = options.mesh_path;
  mesh_options.subdivision_level = options.subdivision_level;
  nlohmann::json mj;
  const TriMesh mesh = benchmark_mesh(mesh_options, mj);
  const Embedding e = embed_bounding_box(mesh.positions, EmbeddingAxes{});
  const std::vector<glm::dvec3> params = embed_points(e, mesh.positions);
  const auto F = perturbed_lattice(e, 4, 8, 0.15, 1);
  std::vector<double> bound(mesh.triangles.size());
  double prepare = INFINITY, best = INFINITY;
  for (int r = 0; r < options.repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const SecondDerivativeBounds b(F);
    const auto t1 = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangles.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t f = range.begin(); f != range.end(); ++f) {
                          const glm::uvec3 t = mesh.triangles[f];
                          bound[f] = triangle_error_bound(b, params[t.x], params[t.y], params[t.z]);
                        }
                      });
    const auto t2 = std::chrono::steady_clock::now();
    prepare = std::min(prepare, std::chrono::duration<double, std::milli>(t1 - t0).count());
    best = std::min(best, std::chrono::duration<double, std::milli>(t2 - t0).count());
  }
  std::vector<double> sorted = bound;
  std::sort(sorted.begin(), sorted.end());
  out["triangles"] = {{"mesh", mj},
                      {"vertices", mesh.positions.size()},
                      {"triangles", mesh.triangles.size()},
                      {"prepare_ms", prepare},
                      {"ms", best},
                      {"per_second", best > 0.0 ? mesh.triangles.size() / (best * 1e-3) : 0.0},
                      {"max_bound", sorted.empty() ? 0.0 : sorted.back()},
                      {"median_bound", sorted.empty() ? 0.0 : sorted[sorted.size() / 2]}};
  // The soundness sweep runs on the unrefined mesh (its own triangles, many lattices).
  TriMesh sweep_mesh = std::filesystem::exists(options.mesh_path) ? load_mesh(options.mesh_path) : mesh;
  out["soundness"] = bound_soundness(sweep_mesh, static_cast<std::size_t>(options.soundness_triangles));
  out["soundness"]["mesh"] =
      std::filesystem::exists(options.mesh_path) ? nlohmann::json(options.mesh_path) : mj["source"];
  out["refinement"] = cube_refinement();
  out["refinement_seed"] = {{"midpoint", 360},
                            {"greville", 308},
                            {"note", "the seed's cube (Fig. 2.10) with its own lattice and error estimate"}};
  return out;
}

}  // namespace trispline::core
