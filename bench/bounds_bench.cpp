#include "bench/bounds_bench.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <tbb/parallel_for.h>

#include "bench/ffd_bench.h"
#include "core/ffd/deformation_bounds.h"
#include "core/ffd/ffd.h"
#include "core/ffd/fold_certificate.h"
#include "core/spline/knot_vector.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::core {

namespace {

// The identity map on [0,1]³ (controls at the Greville abscissae), each control point displaced by N(0, sigma²).
TrivariateBSpline<glm::dvec3> displaced_lattice(int order, const glm::ivec3& controls, double sigma, std::mt19937& rng) {
  const KnotVector ku = KnotVector::clamped_uniform(order, controls.x), kv = KnotVector::clamped_uniform(order, controls.y),
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

}  // namespace

nlohmann::json run_bounds_benchmark(const BoundsBenchOptions& options) {
  if (options.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  if (options.lattices < 0) throw std::invalid_argument("--lattices must be at least 0");
  nlohmann::json out = {{"bench", "bounds"},
                        {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)}};
  nlohmann::json rows = nlohmann::json::array();
  for (int order : {3, 4})
    for (int n : {4, 8, 16}) {
      std::mt19937 rng(17);
      // Displacements of 2 % of a control spacing: far from folding, so every cell is judged in full.
      const auto F = displaced_lattice(order, glm::ivec3(n), 0.02 / n, rng);
      FoldCertificate c;
      double best = INFINITY;
      for (int r = 0; r < options.repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        c = certify_fold_free(F);
        best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      rows.push_back({{"order", order},
                      {"controls", n},
                      {"cells", c.cells},
                      {"boxes", c.boxes},
                      {"verdict", fold_verdict_name(c.verdict)},
                      {"ms", best}});
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
          mn = std::min(mn, jacobian_determinant(F, glm::dvec3((i + 0.5) / kGrid, (j + 0.5) / kGrid, (k + 0.5) / kGrid)));
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
  return out;
}

}  // namespace trispline::core
