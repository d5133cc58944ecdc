// core::loop_subdivide (core/mesh/loop_subdivision.h): uniform Loop subdivision through OpenSubdiv — counts, closed
// 2-manifolds stay so, vertex children first near their parents, uvs linear, face materials inherited.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/mesh/loop_subdivision.h"
#include "core/scene/primitives.h"
#include "tests/mesh_topology.h"

namespace trispline::core {
namespace {

TEST(LoopSubdivision, CountsAndAClosedSphereStaysClosed) {
  const TriMesh sphere = make_sphere(24, 12);
  test::expect_closed_manifold(sphere);
  const std::size_t V = sphere.vertex_count(), F = sphere.triangle_count(), E = test::edge_faces(sphere).size();
  ASSERT_EQ(V - E + F, 2u);  // genus 0
  for (int levels = 1; levels <= 3; ++levels) {
    const TriMesh s = loop_subdivide(sphere, levels);
    EXPECT_EQ(s.triangle_count(), F << (2 * levels));
    test::expect_closed_manifold(s);
    const std::size_t e = test::edge_faces(s).size();
    EXPECT_EQ(s.vertex_count() - e + s.triangle_count(), 2u);  // still a sphere
    if (levels == 1) {
      EXPECT_EQ(s.vertex_count(), V + E);  // one new vertex per edge
    }
    EXPECT_EQ(s.normals.size(), s.vertex_count());
    // Loop shrinks a convex sphere slightly inwards and smooths it: every vertex within [0.97, 1].
    for (const glm::dvec3& p : s.positions) {
      EXPECT_LE(glm::length(p), 1.0 + 1e-12);
      EXPECT_GT(glm::length(p), 0.97);
    }
    // Vertex children come first, in the input order: near their parents.
    for (std::size_t v = 0; v < V; ++v) EXPECT_LT(glm::length(s.positions[v] - sphere.positions[v]), 0.03) << v;
  }
  EXPECT_EQ(loop_subdivide(sphere, 0).positions, sphere.positions);
  EXPECT_THROW(loop_subdivide(sphere, -1), std::invalid_argument);
}

TEST(LoopSubdivision, UvsLinearAndMaterialsInherited) {
  // The plane: uv is an affine function of (x, z); Loop's masks reproduce affine functions on the regular grid and
  // along straight boundaries, and uvs are interpolated linearly, so it stays so — except near the two grid corners
  // with two faces (smooth boundary vertices, not Sdc corners: the boundary rule rounds them off).
  TriMesh plane = make_plane(8);
  ASSERT_EQ(plane.uvs.size(), plane.vertex_count());
  plane.face_material.assign(plane.triangle_count(), kMaterialSurface);
  for (std::size_t f = 0; f < plane.triangle_count(); f += 3) plane.face_material[f] = kMaterialInside;
  const std::size_t inside = std::count(plane.face_material.begin(), plane.face_material.end(), kMaterialInside);
  for (int levels = 1; levels <= 2; ++levels) {
    const TriMesh s = loop_subdivide(plane, levels);
    ASSERT_EQ(s.uvs.size(), s.vertex_count());
    // The affine map (x, z) → uv, fitted on the first triangle and checked on every input vertex.
    const glm::uvec3 q = plane.triangles[0];
    const glm::dvec3 pa = plane.positions[q[0]], pb = plane.positions[q[1]], pc = plane.positions[q[2]];
    const glm::dmat2 P(pb.x - pa.x, pb.z - pa.z, pc.x - pa.x, pc.z - pa.z);
    const glm::dmat2 T(plane.uvs[q[1]] - plane.uvs[q[0]], plane.uvs[q[2]] - plane.uvs[q[0]]);
    const glm::dmat2 A = T * glm::inverse(P);
    auto expected = [&](const glm::dvec3& p) { return plane.uvs[q[0]] + A * glm::dvec2(p.x - pa.x, p.z - pa.z); };
    for (std::size_t v = 0; v < plane.vertex_count(); ++v)
      ASSERT_LT(glm::length(plane.uvs[v] - expected(plane.positions[v])), 1e-12);
    for (std::size_t v = 0; v < s.vertex_count(); ++v) {
      const glm::dvec3 p = s.positions[v];
      if (std::abs(p.x) < 0.5 || std::abs(p.z) < 0.5) {
        EXPECT_LT(glm::length(s.uvs[v] - expected(p)), 1e-12) << v;
      }
      EXPECT_NEAR(s.positions[v].y, 0.0, 1e-15);
    }
    // Materials: the 4^levels children of a face keep its slot.
    ASSERT_EQ(s.face_material.size(), s.triangle_count());
    EXPECT_EQ(std::size_t(std::count(s.face_material.begin(), s.face_material.end(), kMaterialInside)),
              inside << (2 * levels));
    // Level 1: each child's slot is that of the input triangle containing its centroid (the plane stays planar).
    if (levels == 1) {
      for (std::size_t f = 0; f < s.triangle_count(); ++f) {
        const glm::uvec3& t = s.triangles[f];
        const glm::dvec3 c = (s.positions[t[0]] + s.positions[t[1]] + s.positions[t[2]]) / 3.0;
        std::size_t parent = plane.triangle_count();
        for (std::size_t g = 0; g < plane.triangle_count() && parent == plane.triangle_count(); ++g) {
          const glm::uvec3& q = plane.triangles[g];
          const glm::dvec3 a = plane.positions[q[0]], b = plane.positions[q[1]], e = plane.positions[q[2]];
          auto side = [&](glm::dvec3 u, glm::dvec3 w) { return (w.x - u.x) * (c.z - u.z) - (w.z - u.z) * (c.x - u.x); };
          const double s1 = side(a, b), s2 = side(b, e), s3 = side(e, a);
          if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) parent = g;
        }
        ASSERT_LT(parent, plane.triangle_count());
        EXPECT_EQ(s.face_material[f], plane.face_material[parent]) << f;
      }
    }
  }
  // Level 1: the original vertices keep their uvs exactly, every new vertex has the midpoint uv of an input edge
  // (linear interpolation), one per edge.
  const TriMesh s1 = loop_subdivide(plane, 1);
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) EXPECT_EQ(s1.uvs[v], plane.uvs[v]);
  std::map<std::pair<double, double>, int> midpoints;
  for (const auto& [e, n] : test::edge_faces(plane)) {
    const glm::dvec2 m = 0.5 * (plane.uvs[e.first] + plane.uvs[e.second]);
    ++midpoints[{m.x, m.y}];
  }
  EXPECT_EQ(s1.vertex_count() - plane.vertex_count(), test::edge_faces(plane).size());
  for (std::size_t v = plane.vertex_count(); v < s1.vertex_count(); ++v)
    EXPECT_EQ(midpoints.count({s1.uvs[v].x, s1.uvs[v].y}), 1u) << v;
  // No face_material in → none out.
  plane.face_material.clear();
  EXPECT_TRUE(loop_subdivide(plane, 1).face_material.empty());
}

}  // namespace
}  // namespace trispline::core
