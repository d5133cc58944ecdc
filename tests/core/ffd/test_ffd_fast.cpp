// cpu_fast (float, vectorised) against cpu_ref (double) through the FfdEvaluator contract: every order combination
// 2..4 × knot type (clamped, floating, periodic along u, non-uniform clamped) × every instruction set this machine
// runs, at rest and with parameter offsets; periodic offsets; the gather kernel of huge lattices; re-binning.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/ffd/ffd_evaluator.h"
#include "core/ffd/ffd_fast.h"
#include "ffd_test_util.h"

using namespace trispline::core;
using namespace trispline::core::test;

namespace {

constexpr double kPosTol = 1e-5;     // × lattice bounding-box diagonal (ffd_evaluator.h accuracy contract)
constexpr double kNormalTol = 1e-4;  // rad

// Parameters: random in [−0.1, 1.1]³ (some outside the domain: clamped, or wrapped along a periodic u), every knot
// of every axis exactly, and the corners.
std::vector<glm::dvec3> test_params(const TrivariateBSpline<glm::dvec3>& F, int n, unsigned seed) {
  auto p = random_points(n, glm::dvec3(-0.1), glm::dvec3(1.1), seed);
  for (int a = 0; a < 3; ++a)
    for (double k : F.knots(a).knots()) {
      glm::dvec3 q(0.37, 0.61, 0.45);
      q[a] = k;
      p.push_back(q);
    }
  for (int c = 0; c < 8; ++c) p.push_back(glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  return p;
}

struct Result {
  std::vector<glm::dvec3> positions, normals;
};

Result run(FfdBackend b, const TrivariateBSpline<glm::dvec3>& F, const Embedding& e,
           const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& normals, glm::dvec3 offset) {
  auto ev = make_cpu_ffd_evaluator(b);
  ev->bind_vertices(params, normals);
  ev->set_lattice(F, e);
  ev->evaluate(offset);
  Result r;
  ev->read_results(r.positions, r.normals);
  return r;
}

// A non-trivial embedding (axes permuted, anisotropic scales) so that A matters for the normals.
Embedding test_embedding() { return embed_bounding_box({{-1.0, 0.5, 2.0}, {3.0, 1.5, 2.5}}, {2, 0}); }

class IsaScope {  // selects an instruction set for cpu_fast and restores "auto" afterwards
 public:
  explicit IsaScope(const std::string& isa) { ffd_fast_select_isa(isa); }
  ~IsaScope() { ffd_fast_select_isa("auto"); }
};

}  // namespace

TEST(FfdFast, MatchesReferenceForEveryOrderKnotTypeAndIsa) {
  const Embedding e = test_embedding();
  const std::vector<std::string> isas = ffd_fast_available_isas();
  ASSERT_FALSE(isas.empty());
  unsigned seed = 1;
  for (KnotKind kind : kAllKnotKinds)
    for (int ou = 2; ou <= 4; ++ou)
      for (int ov = 2; ov <= 4; ++ov)
        for (int ow = 2; ow <= 4; ++ow) {
          const auto F = random_lattice(kind, {ou, ov, ow}, ++seed);
          const auto params = test_params(F, 400, seed);
          const auto normals = random_normals(params.size(), seed);
          for (glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(0.137, -0.071, 0.043)}) {
            const Result ref = run(FfdBackend::cpu_ref, F, e, params, normals, offset);
            const Result ref_p = run(FfdBackend::cpu_ref, F, e, params, {}, offset);
            for (const std::string& isa : isas) {
              IsaScope scope(isa);
              const Result fast = run(FfdBackend::cpu_fast, F, e, params, normals, offset);
              const Result fast_p = run(FfdBackend::cpu_fast, F, e, params, {}, offset);
              const std::string what = std::string(name_of(kind)) + " orders " + std::to_string(ou) +
                                       std::to_string(ov) + std::to_string(ow) + " " + isa +
                                       (offset == glm::dvec3(0.0) ? " at rest" : " with offset");
              EXPECT_LE(max_rel_error(fast.positions, ref.positions, F), kPosTol) << what;
              EXPECT_LE(max_rel_error(fast_p.positions, ref_p.positions, F), kPosTol) << what;
              EXPECT_LE(max_angle(fast.normals, ref.normals), kNormalTol) << what;
              EXPECT_TRUE(fast_p.normals.empty());
              ASSERT_EQ(fast.positions.size(), params.size());
            }
          }
        }
}

TEST(FfdFast, LargeOffsetsClampAndAnimationSweepMatches) {
  const Embedding e = test_embedding();
  for (KnotKind kind : kAllKnotKinds) {
    const auto F = random_lattice(kind, {3, 4, 2}, 77);
    const auto params = test_params(F, 500, 78);
    const auto normals = random_normals(params.size(), 79);
    auto fast = make_cpu_ffd_evaluator(FfdBackend::cpu_fast);
    fast->bind_vertices(params, normals);
    fast->set_lattice(F, e);
    for (glm::dvec3 off : {glm::dvec3(2.5, 0, 0), glm::dvec3(-0.6, 0.4, -1.2), glm::dvec3(0.0, 0.0, 0.35),
                           glm::dvec3(0.05, 0.0, 0.0), glm::dvec3(0.55, 0.0, 0.0)}) {
      fast->evaluate(off);
      Result f, r = run(FfdBackend::cpu_ref, F, e, params, normals, off);
      fast->read_results(f.positions, f.normals);
      EXPECT_LE(max_rel_error(f.positions, r.positions, F), kPosTol) << name_of(kind) << " " << off.x;
      EXPECT_LE(max_angle(f.normals, r.normals), kNormalTol) << name_of(kind) << " " << off.x;
    }
  }
}

TEST(FfdFast, PeriodicLatticeObjectReturnsAfterOneFullPeriod) {
  const Embedding e = test_embedding();
  for (int order = 2; order <= 4; ++order) {
    const auto F = random_lattice(KnotKind::periodic_u, {order, 3, 3}, 5 + order);
    const auto params = random_points(3000, glm::dvec3(0.0), glm::dvec3(1.0), 6);
    const auto normals = random_normals(params.size(), 7);
    for (FfdBackend b : {FfdBackend::cpu_ref, FfdBackend::cpu_fast}) {
      auto ev = make_cpu_ffd_evaluator(b);
      ev->bind_vertices(params, normals);
      ev->set_lattice(F, e);
      Result start, moved, back, half, half_plus;
      ev->evaluate(glm::dvec3(0.0));
      ev->read_results(start.positions, start.normals);
      ev->evaluate(glm::dvec3(0.5, 0.0, 0.0));
      ev->read_results(half.positions, half.normals);
      ev->evaluate(glm::dvec3(1.0, 0.0, 0.0));
      ev->read_results(back.positions, back.normals);
      ev->evaluate(glm::dvec3(-2.5, 0.0, 0.0));
      ev->read_results(half_plus.positions, half_plus.normals);
      // The object has moved half-way round the ring...
      double moved_by = 0.0;
      for (std::size_t i = 0; i < params.size(); ++i)
        moved_by = std::max(moved_by, glm::length(half.positions[i] - start.positions[i]));
      EXPECT_GT(moved_by, 1.0) << to_string(b);
      // ...and a whole period (or several) brings every vertex back to its start.
      EXPECT_LE(max_rel_error(back.positions, start.positions, F), 1e-12) << to_string(b);
      EXPECT_LE(max_angle(back.normals, start.normals), 1e-9) << to_string(b);
      EXPECT_LE(max_rel_error(half_plus.positions, half.positions, F), 1e-12) << to_string(b);
    }
  }
}

TEST(FfdFast, PeriodicSeamIsSmoothForTheFastPath) {
  // Points straddling u = 0 ≡ 1 of a cubic periodic ring: no seam in positions or normals.
  const Embedding e = test_embedding();
  const auto F = random_lattice(KnotKind::periodic_u, {4, 3, 3}, 12);
  std::vector<glm::dvec3> params;
  for (int i = 0; i < 50; ++i) {
    const double v = 0.02 * i, w = 1.0 - 0.02 * i;
    params.push_back({-1e-6, v, w});
    params.push_back({1e-6, v, w});
  }
  auto normals = random_normals(params.size(), 3);
  for (std::size_t i = 0; i < params.size(); i += 2) normals[i + 1] = normals[i];  // same rest normal per pair
  const Result r = run(FfdBackend::cpu_fast, F, e, params, normals, glm::dvec3(0.0));
  for (std::size_t i = 0; i < params.size(); i += 2) {
    EXPECT_LT(glm::length(r.positions[i] - r.positions[i + 1]), 1e-4);
    EXPECT_LT(std::acos(std::min(1.0, glm::dot(r.normals[i], r.normals[i + 1]))), 1e-3);
  }
}

TEST(FfdFast, HugeLatticeUsesTheGatherKernelAndMatches) {
  const Embedding e = test_embedding();
  // 60³ controls, order 4: 57³ cells × (192 + 9) floats ≈ 37 M > kMaxCellTableFloats.
  const KnotVector k = KnotVector::clamped_uniform(4, 60);
  const auto F = bent_lattice(e, k, k, k);
  const auto params = test_params(F, 20000, 4);
  const auto normals = random_normals(params.size(), 5);
  FfdFastEvaluator fast;
  fast.bind_vertices(params, normals);
  fast.set_lattice(F, e);
  EXPECT_FALSE(fast.uses_cell_tables());
  for (glm::dvec3 off : {glm::dvec3(0.0), glm::dvec3(0.01, -0.02, 0.03)}) {
    fast.evaluate(off);
    Result f, r = run(FfdBackend::cpu_ref, F, e, params, normals, off);
    fast.read_results(f.positions, f.normals);
    EXPECT_LE(max_rel_error(f.positions, r.positions, F), kPosTol);
    EXPECT_LE(max_angle(f.normals, r.normals), kNormalTol);
  }
  EXPECT_EQ(fast.block_count(), 0u);
}

TEST(FfdFast, ChangingKnotVectorsRebinsVertices) {
  const Embedding e = test_embedding();
  const auto params = random_points(5000, glm::dvec3(0.0), glm::dvec3(1.0), 9);
  const auto normals = random_normals(params.size(), 10);
  FfdFastEvaluator fast;
  fast.bind_vertices(params, normals);
  EXPECT_TRUE(fast.has_normals());
  EXPECT_EQ(fast.vertex_count(), params.size());
  for (KnotKind kind : {KnotKind::clamped_uniform, KnotKind::nonuniform_clamped, KnotKind::periodic_u}) {
    const auto F = random_lattice(kind, {4, 3, 2}, 11);
    fast.set_lattice(F, e);
    fast.evaluate();
    EXPECT_TRUE(fast.uses_cell_tables());
    EXPECT_GE(fast.block_count() * 16, params.size());
    Result f, r = run(FfdBackend::cpu_ref, F, e, params, normals, glm::dvec3(0.0));
    fast.read_results(f.positions, f.normals);
    EXPECT_LE(max_rel_error(f.positions, r.positions, F), kPosTol) << name_of(kind);
    EXPECT_LE(max_angle(f.normals, r.normals), kNormalTol) << name_of(kind);
  }
}

TEST(FfdFast, InstructionSetSelection) {
  const std::vector<std::string> isas = ffd_fast_available_isas();
  ASSERT_FALSE(isas.empty());
#if defined(__x86_64__)
  EXPECT_EQ(isas.front(), "sse");
  EXPECT_STREQ(ffd_fast_select_isa("sse"), "sse");
#endif
  EXPECT_EQ(ffd_fast_select_isa("auto"), isas.back());
  EXPECT_EQ(std::string(ffd_fast_isa()), isas.back());
  EXPECT_THROW(ffd_fast_select_isa("neon9"), std::invalid_argument);
  EXPECT_EQ(std::string(ffd_fast_isa()), isas.back());  // unchanged by the failed request
}

TEST(FfdFast, ManySpansInTheOffsetPath) {
  // Span tables longer than two vector registers take the lane-loop lookup (40 non-uniform spans along u, 24 uniform
  // along v); every instruction set, with offsets that move vertices across many spans.
  const Embedding e = test_embedding();
  std::vector<double> k{0, 0, 0};
  for (int i = 1; i < 40; ++i) k.push_back(std::pow(i / 40.0, 1.3));
  k.insert(k.end(), {1, 1, 1});
  const KnotVector ku(3, k);
  ASSERT_FALSE(ku.has_uniform_spans());
  const auto F = bent_lattice(e, ku, KnotVector::clamped_uniform(4, 27), KnotVector::clamped_uniform(2, 3));
  const auto params = test_params(F, 3000, 21);
  const auto normals = random_normals(params.size(), 22);
  for (glm::dvec3 off : {glm::dvec3(0.0), glm::dvec3(0.23, -0.31, 0.05), glm::dvec3(-0.02, 0.004, 0.0)}) {
    const Result ref = run(FfdBackend::cpu_ref, F, e, params, normals, off);
    for (const std::string& isa : ffd_fast_available_isas()) {
      IsaScope scope(isa);
      const Result fast = run(FfdBackend::cpu_fast, F, e, params, normals, off);
      EXPECT_LE(max_rel_error(fast.positions, ref.positions, F), kPosTol) << isa << " offset " << off.x;
      EXPECT_LE(max_angle(fast.normals, ref.normals), kNormalTol) << isa << " offset " << off.x;
    }
  }
}

TEST(FfdFast, EvaluateIntoEqualsReadResultsIntoBitForBit) {
  // The double-writing kernels (Python's out= path) against evaluate + read_results_into: every instruction set, at
  // rest and with an offset, with and without normals, and the gather kernel's fallback; read_results afterwards
  // refuses, since the float buffers are not that evaluation's.
  const Embedding e = test_embedding();
  const auto F = random_lattice(KnotKind::nonuniform_clamped, {4, 3, 2}, 31);
  const KnotVector big = KnotVector::clamped_uniform(4, 60);
  const auto huge = bent_lattice(e, big, big, big);
  const auto params = test_params(F, 4000, 32);
  const auto normals = random_normals(params.size(), 33);
  for (const auto* lattice : {&F, &huge})
    for (bool with_normals : {true, false})
      for (glm::dvec3 off : {glm::dvec3(0.0), glm::dvec3(0.13, -0.07, 0.02)})
        for (const std::string& isa : lattice == &huge ? std::vector<std::string>{"auto"} : ffd_fast_available_isas()) {
          IsaScope scope(isa);
          FfdFastEvaluator fast;
          fast.bind_vertices(params, with_normals ? normals : std::vector<glm::dvec3>{});
          fast.set_lattice(*lattice, e);
          std::vector<double> p0(3 * params.size()), n0(3 * params.size(), -7.0);
          std::vector<double> p1(3 * params.size()), n1(3 * params.size(), -7.0);
          fast.evaluate(off);
          fast.read_results_into(p0.data(), n0.data());
          fast.evaluate_into(off, p1.data(), n1.data());
          const std::string what = isa + (with_normals ? " normals" : "") + (lattice == &huge ? " gather" : "");
          EXPECT_EQ(std::memcmp(p0.data(), p1.data(), p0.size() * sizeof(double)), 0) << what;
          EXPECT_EQ(std::memcmp(n0.data(), n1.data(), n0.size() * sizeof(double)), 0) << what;
          if (fast.uses_cell_tables()) {
            std::vector<glm::dvec3> rp, rn;
            EXPECT_THROW(fast.read_results(rp, rn), std::logic_error) << what;
          }
          fast.evaluate_into(off, p1.data(), nullptr);  // normals not wanted
          EXPECT_EQ(std::memcmp(p0.data(), p1.data(), p0.size() * sizeof(double)), 0) << what;
        }
}
