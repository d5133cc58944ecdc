// The FfdEvaluator contract on the CPU backends: names, factory, errors, thread-count determinism, parity on the
// real Stanford bunny (8×8×8 and 4×4×4 lattices).
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <filesystem>

#include "core/ffd/ffd_evaluator.h"
#include "core/ffd/ffd_fast.h"
#include "core/mesh/mesh_io.h"
#include "ffd_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

// Lattice of the benchmark: Greville abscissae mapped back to world space, perturbed by ±15 % of a cell.
TrivariateBSpline<glm::dvec3> perturbed_lattice(const Embedding& e, int order, int controls, unsigned seed) {
  const KnotVector kv = KnotVector::clamped_uniform(order, controls);
  auto F = identity_lattice(e, kv, kv, kv);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const glm::dmat3 inv = glm::inverse(e.linear);
  for (auto& p : F.control_points()) p += inv * (0.15 / (controls - 1) * glm::dvec3(uni(rng), uni(rng), uni(rng)));
  return F;
}

bool bit_equal(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::dvec3)) == 0;
}

}  // namespace

TEST(FfdEvaluator, BackendNamesRoundTrip) {
  for (FfdBackend b : {FfdBackend::cpu_ref, FfdBackend::cpu_fast, FfdBackend::glsl_compute, FfdBackend::glsl_vertex}) {
    ASSERT_TRUE(parse_ffd_backend(to_string(b)).has_value());
    EXPECT_EQ(*parse_ffd_backend(to_string(b)), b);
  }
  EXPECT_STREQ(to_string(FfdBackend::cpu_fast), "cpu_fast");
  EXPECT_FALSE(parse_ffd_backend("cpu").has_value());
  EXPECT_FALSE(parse_ffd_backend("").has_value());
  EXPECT_TRUE(is_gpu_backend(FfdBackend::glsl_vertex));
  EXPECT_FALSE(is_gpu_backend(FfdBackend::cpu_fast));
  EXPECT_EQ(make_cpu_ffd_evaluator(FfdBackend::cpu_ref)->backend(), FfdBackend::cpu_ref);
  EXPECT_EQ(make_cpu_ffd_evaluator(FfdBackend::cpu_fast)->backend(), FfdBackend::cpu_fast);
  EXPECT_THROW(make_cpu_ffd_evaluator(FfdBackend::glsl_compute), std::invalid_argument);
}

TEST(FfdEvaluator, BadInputErrors) {
  const Embedding e;
  const auto F = random_lattice(KnotKind::clamped_uniform, {3, 3, 3}, 1);
  const auto F5 = random_lattice(KnotKind::clamped_uniform, {5, 3, 2}, 2);
  const std::vector<glm::dvec3> params{{0.5, 0.5, 0.5}, {0.1, 0.2, 0.3}};
  for (FfdBackend b : {FfdBackend::cpu_ref, FfdBackend::cpu_fast}) {
    auto ev = make_cpu_ffd_evaluator(b);
    std::vector<glm::dvec3> p, n;
    EXPECT_THROW(ev->evaluate(), std::logic_error) << to_string(b);  // before bind and set_lattice
    EXPECT_THROW(ev->read_results(p, n), std::logic_error) << to_string(b);
    EXPECT_THROW(ev->bind_vertices(params, {{0, 1, 0}}), std::invalid_argument) << to_string(b);  // size mismatch
    EXPECT_THROW(ev->bind_vertices({{0.5, NAN, 0.5}}, {}), std::invalid_argument) << to_string(b);
    EXPECT_THROW(ev->bind_vertices(params, {{0, 1, 0}, {INFINITY, 0, 0}}), std::invalid_argument) << to_string(b);
    ev->bind_vertices(params, {});
    EXPECT_THROW(ev->evaluate(), std::logic_error) << to_string(b);  // bound, but no lattice yet
    if (b == FfdBackend::cpu_fast)
      EXPECT_THROW(ev->set_lattice(F5, e), std::invalid_argument);  // order 5: cpu_ref only
    else
      EXPECT_NO_THROW(ev->set_lattice(F5, e));
    ev->set_lattice(F, e);
    EXPECT_THROW(ev->read_results(p, n), std::logic_error) << to_string(b);  // not evaluated yet
    ev->evaluate();
    ev->read_results(p, n);
    EXPECT_EQ(p.size(), 2u);
    EXPECT_TRUE(n.empty());
    EXPECT_FALSE(ev->has_normals());
    EXPECT_EQ(ev->vertex_count(), 2u);
    ev->bind_vertices(params, {{0, 1, 0}, {1, 0, 0}});  // re-binding invalidates the results
    EXPECT_THROW(ev->read_results(p, n), std::logic_error) << to_string(b);
    ev->bind_vertices({}, {});  // an empty mesh is valid
    ev->evaluate(glm::dvec3(0.1, 0.0, 0.0));
    ev->read_results(p, n);
    EXPECT_TRUE(p.empty() && n.empty()) << to_string(b);
  }
}

TEST(FfdEvaluator, BitIdenticalForAnyThreadCount) {
  const Embedding e;
  const auto params = random_points(60000, glm::dvec3(-0.05), glm::dvec3(1.05), 3);
  const auto normals = random_normals(params.size(), 4);
  const KnotVector big = KnotVector::clamped_uniform(4, 60);  // gather kernel (huge lattice)
  const TrivariateBSpline<glm::dvec3> lattices[] = {random_lattice(KnotKind::nonuniform_clamped, {4, 3, 2}, 5),
                                                    random_lattice(KnotKind::periodic_u, {4, 4, 4}, 6),
                                                    bent_lattice(e, big, big, big)};
  for (const auto& F : lattices)
    for (FfdBackend b : {FfdBackend::cpu_ref, FfdBackend::cpu_fast})
      for (glm::dvec3 off : {glm::dvec3(0.0), glm::dvec3(0.21, -0.03, 0.11)}) {
        auto eval = [&](int threads, std::vector<glm::dvec3>& p, std::vector<glm::dvec3>& n) {
          tbb::task_arena arena(threads);
          arena.execute([&] {
            auto ev = make_cpu_ffd_evaluator(b);
            ev->bind_vertices(params, normals);
            ev->set_lattice(F, e);
            ev->evaluate(off);
            ev->read_results(p, n);
          });
        };
        std::vector<glm::dvec3> p1, n1, p2, n2, p8, n8;
        eval(1, p1, n1);
        eval(2, p2, n2);
        eval(8, p8, n8);
        EXPECT_TRUE(bit_equal(p1, p2) && bit_equal(p1, p8)) << to_string(b) << " offset " << off.x;
        EXPECT_TRUE(bit_equal(n1, n2) && bit_equal(n1, n8)) << to_string(b) << " offset " << off.x;
      }
}

TEST(FfdEvaluator, FastMatchesReferenceOnTheStanfordBunny) {
  const std::filesystem::path path = TRISPLINE_SOURCE_DIR "/assets/data/bunny.obj";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run scripts/fetch_assets.sh";
  const TriMesh bunny = load_mesh(path.string());
  ASSERT_GT(bunny.positions.size(), 30000u);
  ASSERT_EQ(bunny.normals.size(), bunny.positions.size());
  const Embedding e = embed_bounding_box(bunny.positions, {0, 1});
  const auto params = embed_points(e, bunny.positions);
  for (int controls : {4, 8})
    for (int order : {3, 4}) {
      const auto F = perturbed_lattice(e, order, controls, 1);
      std::vector<glm::dvec3> rp, rn, fp, fn;
      auto ref = make_cpu_ffd_evaluator(FfdBackend::cpu_ref);
      ref->bind_vertices(params, bunny.normals);
      ref->set_lattice(F, e);
      ref->evaluate();
      ref->read_results(rp, rn);
      for (const std::string& isa : ffd_fast_available_isas()) {
        ffd_fast_select_isa(isa);
        auto fast = make_cpu_ffd_evaluator(FfdBackend::cpu_fast);
        fast->bind_vertices(params, bunny.normals);
        fast->set_lattice(F, e);
        fast->evaluate();
        fast->read_results(fp, fn);
        const std::string what = std::to_string(controls) + "^3 order " + std::to_string(order) + " " + isa;
        EXPECT_LE(max_rel_error(fp, rp, F), 1e-5) << what;
        EXPECT_LE(max_angle(fn, rn), 1e-4) << what;
        for (const auto& n : fn) ASSERT_NEAR(glm::length(n), 1.0, 1e-6) << what;
      }
      ffd_fast_select_isa("auto");
    }
}
