// DFFD core (core/dffd/dffd.h): discontinuity insertion / opening in the lattice, mesh splitting at a
// parameter plane, and the two together through ffd_evaluate (seed §6.3.1 Def. 6, §6.3.2).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "core/dffd/dffd.h"
#include "core/ffd/ffd.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"
#include "tests/core/ffd/ffd_test_util.h"
#include "tests/mesh_topology.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

using test::bent_lattice;
using test::identity_lattice;
using test::Topology;
using test::topology;

// ---------------------------------------------------------------- mesh topology helpers

// Connected components of the boundary-edge graph (= boundary loops for a manifold boundary).
std::size_t boundary_loops(const std::vector<std::pair<unsigned, unsigned>>& edges) {
  std::map<unsigned, unsigned> parent;
  auto find = [&](unsigned x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& [a, b] : edges) parent.emplace(a, a), parent.emplace(b, b);
  for (const auto& [a, b] : edges) parent[find(a)] = find(b);
  std::size_t n = 0;
  for (const auto& [v, p] : parent) n += (find(v) == v);
  return n;
}

double total_area(const TriMesh& m) {
  double a = 0.0;
  for (const glm::uvec3& f : m.triangles)
    a += 0.5 * glm::length(glm::cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]));
  return a;
}

TriMesh make_torus(int nu, int nv) { return trispline::test::torus_mesh(nu, nv, true); }

// uv = (x, y) of the position: a linear function, so interpolated uvs must equal it at the new positions.
void add_linear_uvs(TriMesh& m) {
  m.uvs.clear();
  for (const glm::dvec3& p : m.positions) m.uvs.push_back({p.x, p.y});
}

// Checks (a) 2-manifold edges, orientation, (c) sides, (d) area, params consistency; (b) for closed inputs.
// cross_sections < 0: the input is not closed, (b) is not checked.
MeshSplit check_split(const TriMesh& mesh, const Embedding& e, int axis, double u0, double eps, int cross_sections) {
  const std::vector<glm::dvec3> params = embed_points(e, mesh.positions);
  const Topology before = topology(mesh);
  EXPECT_EQ(before.nonmanifold_edges, 0u);
  EXPECT_EQ(before.repeated_halfedges, 0u);
  MeshSplit s = split_mesh_at_parameter(mesh, params, axis, u0, eps);
  const TriMesh& m = s.mesh;
  const std::size_t nv = m.vertex_count();
  EXPECT_EQ(s.params.size(), nv);
  EXPECT_EQ(s.side.size(), nv);
  EXPECT_EQ(m.normals.size(), mesh.normals.empty() ? 0u : nv);
  EXPECT_EQ(m.uvs.size(), mesh.uvs.empty() ? 0u : nv);
  EXPECT_GT(s.cut_edges + s.duplicated_on_plane, 0u);  // a cut through mesh vertices only has no cut edges
  // (a) 2-manifold edges, consistent orientation, no duplicate / degenerate faces.
  const Topology after = topology(m);
  EXPECT_TRUE(is_manifold(after));
  // (c) no face with vertices on both sides; sides agree with the params.
  for (const glm::uvec3& f : m.triangles) {
    EXPECT_EQ(s.side[f[0]], s.side[f[1]]);
    EXPECT_EQ(s.side[f[0]], s.side[f[2]]);
  }
  for (std::size_t v = 0; v < nv; ++v) {
    EXPECT_TRUE(s.side[v] == -1 || s.side[v] == 1);
    if (s.side[v] < 0) {
      EXPECT_LE(s.params[v][axis], u0 - 0.5 * eps) << v;
    } else {
      EXPECT_GE(s.params[v][axis], u0 + 0.5 * eps) << v;
    }
  }
  // (d) area preserved.
  const double a0 = total_area(mesh), a1 = total_area(m);
  EXPECT_NEAR(a1, a0, 1e-12 * a0);
  // (e) new vertices: params = E(position) off the split axis, uvs = the linear uv function, unit normals.
  for (std::size_t v = mesh.vertex_count(); v < nv; ++v) {
    const glm::dvec3 p = e.apply(m.positions[v]);
    for (int c = 0; c < 3; ++c) {
      if (c != axis) {
        EXPECT_NEAR(s.params[v][c], p[c], 1e-12);
      }
    }
    EXPECT_NEAR(std::abs(s.params[v][axis] - u0), eps, 1e-15);
    if (!m.uvs.empty()) {
      EXPECT_NEAR(m.uvs[v].x, m.positions[v].x, 1e-12);
      EXPECT_NEAR(m.uvs[v].y, m.positions[v].y, 1e-12);
    }
    if (!m.normals.empty()) {
      EXPECT_NEAR(glm::length(m.normals[v]), 1.0, 1e-12);
    }
  }
  // (b) closed input: the boundary is exactly the cut, two loops per cross-section loop.
  if (cross_sections >= 0) {
    EXPECT_EQ(before.boundary.size(), 0u);
    std::size_t minus = 0, plus = 0;
    for (const auto& [a, b] : after.boundary) {
      EXPECT_NEAR(std::abs(s.params[a][axis] - u0), eps, 1e-15);
      EXPECT_NEAR(std::abs(s.params[b][axis] - u0), eps, 1e-15);
      (s.side[a] < 0 ? minus : plus) += 1;
    }
    EXPECT_EQ(minus, plus);
    EXPECT_EQ(boundary_loops(after.boundary), 2u * static_cast<std::size_t>(cross_sections));
  }
  return s;
}

Embedding box_embedding(const TriMesh& m) { return embed_bounding_box(m.positions, EmbeddingAxes{}); }

// ---------------------------------------------------------------- insert / open discontinuity

TrivariateBSpline<glm::dvec3> test_lattice() {
  return bent_lattice(Embedding{}, KnotVector::clamped_uniform(3, 5), KnotVector::clamped_uniform(4, 6),
                      KnotVector::clamped_uniform(3, 4));
}

std::vector<glm::dvec3> sample_points() {
  std::vector<glm::dvec3> pts;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 7; ++j)
      for (int k = 0; k <= 6; ++k) pts.push_back({i / 10.0, j / 7.0, k / 6.0});
  pts.push_back({0.5, 0.31, 0.77});
  pts.push_back({0.4999, 0.62, 0.13});
  return pts;
}

TEST(Dffd, InsertDiscontinuityKeepsFunctionAndMakesCoincidentPlanes) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double u0 : {0.5, 0.123, -1.0}) {  // -1: an existing interior knot (multiplicity 1)
      TrivariateBSpline<glm::dvec3> F = test_lattice();
      if (u0 < 0) u0 = F.knots(axis)[F.orders()[axis]];
      const TrivariateBSpline<glm::dvec3> G = F;
      const int m0 = F.knots(axis).multiplicity(u0);
      const Discontinuity d = insert_discontinuity(F, axis, u0);
      EXPECT_EQ(d.axis, axis);
      EXPECT_EQ(d.u0, u0);
      EXPECT_EQ(d.plus_plane, d.minus_plane + 1);
      const int order = F.orders()[axis];
      EXPECT_EQ(F.knots(axis).multiplicity(u0), order);
      EXPECT_EQ(F.control_counts()[axis], G.control_counts()[axis] + order - m0);
      for (const glm::dvec3& p : sample_points()) EXPECT_LT(glm::length(F.eval(p) - G.eval(p)), 1e-12) << axis;
      // The two planes coincide before they are moved.
      const glm::ivec3 c = F.control_counts();
      for (int k = 0; k < c.z; ++k)
        for (int j = 0; j < c.y; ++j)
          for (int i = 0; i < c.x; ++i) {
            glm::ivec3 idx(i, j, k);
            if (idx[axis] != d.minus_plane) continue;
            glm::ivec3 nxt = idx;
            nxt[axis] = d.plus_plane;
            EXPECT_LT(glm::length(F.control_point(i, j, k) - F.control_point(nxt.x, nxt.y, nxt.z)), 1e-12);
          }
    }
  }
}

TEST(Dffd, InsertDiscontinuityErrorsLeaveLatticeUntouched) {
  TrivariateBSpline<glm::dvec3> F = test_lattice();
  const TrivariateBSpline<glm::dvec3> G = F;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double u0 : {0.0, 1.0, -0.2, 1.3, nan, inf}) EXPECT_THROW(insert_discontinuity(F, 0, u0), std::invalid_argument);
  EXPECT_THROW(insert_discontinuity(F, 3, 0.5), std::invalid_argument);
  EXPECT_THROW(insert_discontinuity(F, -1, 0.5), std::invalid_argument);
  EXPECT_EQ(F.control_points(), G.control_points());
  EXPECT_EQ(F.knots(0).knots(), G.knots(0).knots());
  insert_discontinuity(F, 1, 0.4);
  const auto cps = F.control_points();
  try {
    insert_discontinuity(F, 1, 0.4);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("already a discontinuity"), std::string::npos) << e.what();
  }
  EXPECT_EQ(F.control_points(), cps);
  auto P = TrivariateBSpline<glm::dvec3>(KnotVector::periodic_uniform(3, 6), KnotVector::clamped_uniform(2, 2),
                                         KnotVector::clamped_uniform(2, 2), std::vector<glm::dvec3>(24));
  EXPECT_THROW(insert_discontinuity(P, 0, 0.5), std::invalid_argument);
}

TEST(Dffd, OpenDiscontinuityMovesOnlyTheTwoPlanes) {
  TrivariateBSpline<glm::dvec3> F = test_lattice();
  const Discontinuity d = insert_discontinuity(F, 0, 0.45);
  const TrivariateBSpline<glm::dvec3> closed = F;
  const glm::dvec3 dm(-0.1, 0.02, 0.05), dp(0.2, 0.0, -0.03);
  open_discontinuity(F, d, dm, dp);
  const std::vector<double>& U = F.knots(0).knots();
  const int order = F.orders()[0];
  const double lo = U[d.minus_plane], hi = U[d.plus_plane + order];  // support of the two planes: [lo, hi)
  const double delta = 1e-9;
  std::size_t far = 0;
  for (const glm::dvec3& p : sample_points()) {
    const glm::dvec3 a{0.45 - delta, p.y, p.z}, b{0.45 + delta, p.y, p.z};
    const glm::dvec3 gap = F.eval(b) - F.eval(a);
    EXPECT_LT(glm::length(gap - (dp - dm)), 1e-6);
    EXPECT_NEAR(glm::length(gap), glm::length(dp - dm), 1e-6);
    if (p.x < lo - 1e-9 || p.x > hi + 1e-9) {
      EXPECT_EQ(F.eval(p), closed.eval(p)) << p.x;
      ++far;
    } else if (p.x > lo + 1e-3 && p.x < hi - 1e-3) {
      EXPECT_GT(glm::length(F.eval(p) - closed.eval(p)), 1e-6) << p.x;
    }
  }
  EXPECT_GT(far, 100u);
  // Errors: a lattice / disc pair that does not match, non-finite deltas; F untouched.
  const auto cps = F.control_points();
  Discontinuity wrong = d;
  wrong.minus_plane = 0, wrong.plus_plane = 1;
  EXPECT_THROW(open_discontinuity(F, wrong, dm, dp), std::invalid_argument);
  wrong = d, wrong.u0 = 0.3;
  EXPECT_THROW(open_discontinuity(F, wrong, dm, dp), std::invalid_argument);
  wrong = d, wrong.axis = 1;
  EXPECT_THROW(open_discontinuity(F, wrong, dm, dp), std::invalid_argument);
  EXPECT_THROW(open_discontinuity(F, d, glm::dvec3(std::nan(""), 0, 0), dp), std::invalid_argument);
  EXPECT_EQ(F.control_points(), cps);
}

// ---------------------------------------------------------------- mesh splitting

TEST(Dffd, SplitSphereThroughOnPlaneVertices) {
  // x = 0 goes through both poles and two meridians of vertices (|x| ≤ 1e-16): on-plane vertices are duplicated.
  TriMesh sphere = make_sphere(64, 32);
  add_linear_uvs(sphere);
  const MeshSplit s = check_split(sphere, box_embedding(sphere), 0, 0.5, 1e-9, 1);
  EXPECT_GT(s.duplicated_on_plane, 0u);
  // Normals: sphere normals = positions, so a renormalised interpolated normal is position / |position|.
  for (std::size_t v = sphere.vertex_count(); v < s.mesh.vertex_count(); ++v)
    EXPECT_LT(glm::length(s.mesh.normals[v] - glm::normalize(s.mesh.positions[v])), 1e-12);
}

TEST(Dffd, SplitSphereOffVertices) {
  TriMesh sphere = make_sphere(40, 21);
  add_linear_uvs(sphere);
  for (int axis = 0; axis < 3; ++axis) {
    const MeshSplit s = check_split(sphere, box_embedding(sphere), axis, 0.37, 1e-7, 1);
    EXPECT_EQ(s.duplicated_on_plane, 0u);
    EXPECT_EQ(s.mesh.vertex_count(), sphere.vertex_count() + 2 * s.cut_edges);
  }
}

TEST(Dffd, SplitTorusGivesFourLoops) {
  for (int nu : {48, 47}) {
    TriMesh torus = make_torus(nu, 24);
    add_linear_uvs(torus);
    check_split(torus, box_embedding(torus), 0, 0.5, 1e-9, 2);  // x = 0: two circles
    check_split(torus, box_embedding(torus), 2, 0.5, 1e-9, 2);  // z = 0: inner and outer circle
    check_split(torus, box_embedding(torus), 0, 0.1, 1e-9, 1);  // x near the end: one circle
  }
}

TEST(Dffd, SplitTeapotAndDeterminism) {
  const TriMesh teapot = make_primitive(PrimitiveKind::Teapot);
  const Embedding e = box_embedding(teapot);
  const std::vector<glm::dvec3> params = embed_points(e, teapot.positions);
  for (int axis = 0; axis < 3; ++axis) {
    const MeshSplit a = split_mesh_at_parameter(teapot, params, axis, 0.43, 1e-9);
    const MeshSplit b = split_mesh_at_parameter(teapot, params, axis, 0.43, 1e-9);
    EXPECT_GT(a.cut_edges, 0u);
    EXPECT_NEAR(total_area(a.mesh), total_area(teapot), 1e-12 * total_area(teapot));
    for (const glm::uvec3& f : a.mesh.triangles) {
      EXPECT_EQ(a.side[f[0]], a.side[f[1]]);
      EXPECT_EQ(a.side[f[0]], a.side[f[2]]);
    }
    // (g) bit-identical.
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    EXPECT_EQ(0, std::memcmp(a.mesh.positions.data(), b.mesh.positions.data(), a.mesh.positions.size() * 24));
    EXPECT_EQ(0, std::memcmp(a.params.data(), b.params.data(), a.params.size() * 24));
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    EXPECT_EQ(a.mesh.normals.size(), b.mesh.normals.size());
    EXPECT_EQ(0, std::memcmp(a.mesh.normals.data(), b.mesh.normals.data(), a.mesh.normals.size() * 24));
    EXPECT_EQ(a.side, b.side);
  }
}

TEST(Dffd, PlaneMissingTheMeshReturnsItUnchanged) {
  TriMesh sphere = make_sphere(16, 8);
  add_linear_uvs(sphere);
  const std::vector<glm::dvec3> params = embed_points(box_embedding(sphere), sphere.positions);
  for (double u0 : {-0.01, 1.01, 7.0}) {
    const MeshSplit s = split_mesh_at_parameter(sphere, params, 1, u0, 1e-9);
    EXPECT_EQ(s.cut_edges, 0u);
    EXPECT_EQ(s.duplicated_on_plane, 0u);
    EXPECT_EQ(s.mesh.positions, sphere.positions);
    EXPECT_EQ(s.mesh.normals, sphere.normals);
    EXPECT_EQ(s.mesh.uvs, sphere.uvs);
    EXPECT_EQ(s.mesh.triangles, sphere.triangles);
    EXPECT_EQ(s.params, params);
  }
}

TEST(Dffd, SplitRejectsBadInput) {
  const TriMesh sphere = make_sphere(8, 4);
  const std::vector<glm::dvec3> params = embed_points(box_embedding(sphere), sphere.positions);
  const double nan = std::nan("");
  EXPECT_THROW(split_mesh_at_parameter(sphere, params, 3, 0.5, 1e-9), std::invalid_argument);
  EXPECT_THROW(split_mesh_at_parameter(sphere, params, 0, nan, 1e-9), std::invalid_argument);
  EXPECT_THROW(split_mesh_at_parameter(sphere, params, 0, 0.5, -1e-9), std::invalid_argument);
  EXPECT_THROW(split_mesh_at_parameter(sphere, params, 0, 0.5, nan), std::invalid_argument);
  EXPECT_THROW(split_mesh_at_parameter(sphere, std::vector<glm::dvec3>(3), 0, 0.5, 1e-9), std::invalid_argument);
  TriMesh bad = sphere;
  bad.triangles.push_back({0, 1, 999});
  EXPECT_THROW(split_mesh_at_parameter(bad, params, 0, 0.5, 1e-9), std::invalid_argument);
}

#ifdef TRISPLINE_HAVE_BUNNY
TEST(Dffd, SplitStanfordBunny) {
  const TriMesh bunny = load_mesh(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/bunny.obj");
  ASSERT_GT(bunny.triangle_count(), 60000u);
  const Embedding e = box_embedding(bunny);
  for (int axis = 0; axis < 3; ++axis) {
    const MeshSplit s = check_split(bunny, e, axis, 0.5, 1e-9, -1);
    EXPECT_GT(s.cut_edges, 50u);
  }
}
#endif

// ---------------------------------------------------------------- integration: lattice + mesh ("left open")

TEST(Dffd, SphereOpensAlongTheCut) {
  const TriMesh sphere = make_sphere(64, 32);
  const Embedding e = box_embedding(sphere);  // x ∈ [-1, 1] → u = (x + 1) / 2
  auto F = identity_lattice(e, KnotVector::clamped_uniform(3, 5), KnotVector::clamped_uniform(3, 5),
                            KnotVector::clamped_uniform(3, 5));
  const Discontinuity d = insert_discontinuity(F, 0, 0.5);
  const MeshSplit s = split_mesh_at_parameter(sphere, embed_points(e, sphere.positions), 0, 0.5, 1e-9);
  open_discontinuity(F, d, glm::dvec3(-0.2, 0, 0), glm::dvec3(0.2, 0, 0));
  std::vector<glm::dvec3> out;
  ffd_evaluate(F, s.params, out);
  ASSERT_EQ(out.size(), s.mesh.vertex_count());
  const double support_lo = F.knots(0)[d.minus_plane], support_hi = F.knots(0)[d.plus_plane + 3];  // 1/3, 2/3
  for (std::size_t v = 0; v < out.size(); ++v) {
    const glm::dvec3 x = s.mesh.positions[v];
    if (s.side[v] < 0) {
      EXPECT_LT(out[v].x, -0.15) << v;  // no vertex in the gap (-0.15, 0.15)
    } else {
      EXPECT_GT(out[v].x, 0.15) << v;
    }
    EXPECT_NEAR(out[v].y, x.y, 1e-12);
    EXPECT_NEAR(out[v].z, x.z, 1e-12);
    const double u = s.params[v].x;
    if (u < support_lo || u > support_hi) {
      EXPECT_NEAR(out[v].x, x.x, 1e-12);
    }
    if (std::abs(u - 0.5) <= 1e-9 + 1e-15) {
      EXPECT_NEAR(out[v].x, s.side[v] * 0.2, 1e-6);  // the cut rims
    }
  }
  // The mapped mesh (same topology) is 2-manifold, its boundary is the two rims at x = ∓0.2.
  TriMesh mapped = s.mesh;
  mapped.positions = out;
  const Topology t = topology(mapped);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.repeated_halfedges, 0u);
  EXPECT_EQ(boundary_loops(t.boundary), 2u);
  for (const auto& [a, b] : t.boundary) {
    EXPECT_NEAR(std::abs(out[a].x), 0.2, 1e-6);
    EXPECT_NEAR(std::abs(out[b].x), 0.2, 1e-6);
  }
}

}  // namespace
}  // namespace trispline::core
