// DFFD caps (core/dffd/dffd_cap.h): closing the two sides of a mesh split at a parameter plane with CGAL
// constrained Delaunay caps (seed §6.3.2, Fig. 6.2b). Topology is checked with OpenMesh.
#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "core/dffd/dffd.h"
#include "core/dffd/dffd_cap.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// OpenMesh view of the triangles of one side (side = 0: all triangles).
struct OmCheck {
  std::size_t rejected_faces = 0;  // add_face refused: complex (non-manifold) edge or vertex
  std::size_t boundary_edges = 0;
  std::size_t non_manifold_vertices = 0;
  std::size_t faces = 0;
};

OmCheck om_check(const MeshSplit& s, int side) {
  OmMesh om;
  std::vector<OmMesh::VertexHandle> vh;
  for (const glm::dvec3& p : s.mesh.positions) vh.push_back(om.add_vertex(OmMesh::Point(p.x, p.y, p.z)));
  OmCheck c;
  for (const glm::uvec3& f : s.mesh.triangles) {
    if (side != 0 && s.side[f[0]] != side) continue;
    if (!om.add_face(vh[f[0]], vh[f[1]], vh[f[2]]).is_valid()) ++c.rejected_faces;
  }
  for (auto e : om.edges()) c.boundary_edges += om.is_boundary(e);
  for (auto v : om.vertices())
    if (!om.is_isolated(v) && !om.is_manifold(v)) ++c.non_manifold_vertices;
  c.faces = om.n_faces();
  return c;
}

// Every undirected edge used by exactly two faces, every directed edge once (closed, consistently oriented).
void expect_closed_oriented(const TriMesh& m) {
  std::map<std::pair<unsigned, unsigned>, int> undirected, directed;
  for (const glm::uvec3& f : m.triangles)
    for (int e = 0; e < 3; ++e) {
      const unsigned a = f[e], b = f[(e + 1) % 3];
      ++undirected[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
    }
  std::size_t bad = 0, repeated = 0;
  for (const auto& [e, n] : undirected) bad += (n != 2);
  for (const auto& [e, n] : directed) repeated += (n != 1);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(repeated, 0u);
}

glm::dvec3 tri_normal(const TriMesh& m, const glm::uvec3& f) {  // area-weighted (|n| = 2 · area)
  return glm::cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]);
}

// Sum of area-weighted normals of the cap triangles (index ≥ first_cap) of one side.
glm::dvec3 cap_normal_sum(const MeshSplit& s, std::size_t first_cap, int side) {
  glm::dvec3 n(0.0);
  for (std::size_t f = first_cap; f < s.mesh.triangle_count(); ++f)
    if (s.side[s.mesh.triangles[f][0]] == side) n += tri_normal(s.mesh, s.mesh.triangles[f]);
  return n;
}

double cap_area(const MeshSplit& s, std::size_t first_cap, int side) {
  double a = 0.0;
  for (std::size_t f = first_cap; f < s.mesh.triangle_count(); ++f)
    if (s.side[s.mesh.triangles[f][0]] == side) a += 0.5 * glm::length(tri_normal(s.mesh, s.mesh.triangles[f]));
  return a;
}

TriMesh make_torus(int nu, int nv) { return trispline::test::torus_mesh(nu, nv, false); }

// Parameters = the bounding box mapped to [0,1]³ axis by axis (parameter axis k = world axis k, positive scale).
std::vector<glm::dvec3> box_params(const TriMesh& m) {
  Aabb box;
  for (const glm::dvec3& p : m.positions) box.extend(p);
  std::vector<glm::dvec3> params;
  for (const glm::dvec3& p : m.positions) params.push_back((p - box.lo) / box.size());
  return params;
}

// Splits, caps and checks: both sides closed 2-manifolds (OpenMesh + edge counts), materials, cap orientation
// (minus side faces +axis, plus side −axis) and planarity of the caps.
MeshSplit split_and_cap(const TriMesh& mesh, int axis, double u0, double eps, CapStats* stats_out = nullptr) {
  MeshSplit s = split_mesh_at_parameter(mesh, box_params(mesh), axis, u0, eps);
  const std::size_t first_cap = s.mesh.triangle_count();
  const CapStats st = cap_split_openings(s, axis, u0, eps);
  if (stats_out) *stats_out = st;
  EXPECT_EQ(st.open_chains, 0u);
  EXPECT_GE(st.loops, 2u);
  EXPECT_EQ(s.mesh.triangle_count(), first_cap + st.triangles);
  EXPECT_EQ(s.params.size(), s.mesh.vertex_count());  // no vertex added
  for (int side : {-1, 1}) {
    const OmCheck c = om_check(s, side);
    EXPECT_GT(c.faces, 0u);
    EXPECT_EQ(c.rejected_faces, 0u) << "side " << side;
    EXPECT_EQ(c.boundary_edges, 0u) << "side " << side;
    EXPECT_EQ(c.non_manifold_vertices, 0u) << "side " << side;
    // Orientation: the sum of area-weighted normals of a planar cap is ±(2 · area) along the axis.
    const glm::dvec3 n = cap_normal_sum(s, first_cap, side);
    glm::dvec3 e(0.0);
    e[axis] = side < 0 ? 1.0 : -1.0;
    EXPECT_NEAR(glm::dot(n, e), 2.0 * cap_area(s, first_cap, side), 1e-9 * glm::length(n)) << "side " << side;
    EXPECT_GT(glm::dot(n, e), 0.0);
  }
  expect_closed_oriented(s.mesh);
  EXPECT_EQ(s.mesh.face_material.size(), s.mesh.triangle_count());
  for (std::size_t f = 0; f < s.mesh.triangle_count(); ++f)
    EXPECT_EQ(s.mesh.face_material[f], f < first_cap ? kMaterialSurface : kMaterialInside) << f;
  return s;
}

TEST(DffdCap, SphereBothSidesClosedOnEveryAxis) {
  const TriMesh sphere = make_primitive(PrimitiveKind::Sphere);
  for (int axis = 0; axis < 3; ++axis) {
    CapStats st;
    split_and_cap(sphere, axis, 0.37, 1e-7, &st);
    EXPECT_EQ(st.loops, 2u) << axis;
    EXPECT_GT(st.triangles, 0u);
  }
  // Through on-plane vertices (x = 0 holds both poles and two meridians).
  CapStats st;
  const MeshSplit s = split_and_cap(sphere, 0, 0.5, 1e-9, &st);
  EXPECT_GT(s.duplicated_on_plane, 0u);
  EXPECT_EQ(st.loops, 2u);
  // Cap of a disc of radius 1: close to π, below it (inscribed polygon).
  const double a = cap_area(s, s.mesh.triangle_count() - st.triangles, -1);
  EXPECT_LT(a, M_PI);
  EXPECT_GT(a, 0.99 * M_PI);
}

TEST(DffdCap, TorusAnnulusKeepsItsHole) {
  const TriMesh torus = make_torus(48, 24);
  for (double u0 : {0.5, 0.55}) {  // z = 0 (through vertex rings) and z = 0.07
    CapStats st;
    MeshSplit s = split_and_cap(torus, 2, u0, 1e-9, &st);
    EXPECT_EQ(st.loops, 4u);  // inner and outer circle on each side
    const std::size_t first_cap = s.mesh.triangle_count() - st.triangles;
    for (int side : {-1, 1}) {
      // Outer and inner polygon areas (shoelace in z = const) from the open split's boundary edges of this side.
      std::map<std::pair<unsigned, unsigned>, std::pair<int, std::pair<unsigned, unsigned>>> uses;  // n, a → b
      for (std::size_t f = 0; f < first_cap; ++f)
        for (int e = 0; e < 3; ++e) {
          const unsigned a = s.mesh.triangles[f][e], b = s.mesh.triangles[f][(e + 1) % 3];
          auto& u = uses[{std::min(a, b), std::max(a, b)}];
          ++u.first, u.second = {a, b};
        }
      double a_out = 0.0, a_in = 0.0, r_in = 1e9;
      for (const auto& [key, u] : uses) {
        const auto [a, b] = u.second;
        if (u.first != 1 || s.side[a] != side) continue;
        const glm::dvec3 p = s.mesh.positions[a], q = s.mesh.positions[b];
        const double r = std::hypot(p.x, p.y);
        (r > 2.0 ? a_out : a_in) += 0.5 * (p.x * q.y - q.x * p.y);  // ± per edge direction: abs() below
        if (r < 2.0) r_in = std::min(r_in, r);
      }
      const double area = cap_area(s, first_cap, side);
      EXPECT_NEAR(area, std::abs(a_out) - std::abs(a_in), 1e-9 * area) << u0 << " side " << side;
      EXPECT_GT(std::abs(a_in), 4.0);  // the hole is there and not small (π · 1.3² ≈ 5.3)
      // No cap triangle covers the hole.
      for (std::size_t f = first_cap; f < s.mesh.triangle_count(); ++f) {
        const glm::uvec3& t = s.mesh.triangles[f];
        const glm::dvec3 c = (s.mesh.positions[t[0]] + s.mesh.positions[t[1]] + s.mesh.positions[t[2]]) / 3.0;
        EXPECT_GT(std::hypot(c.x, c.y), r_in * std::cos(M_PI / 48) - 1e-12);
      }
    }
  }
  // x = 0 cuts the tube twice: two separate discs per side, no hole.
  CapStats st;
  split_and_cap(torus, 0, 0.5, 1e-9, &st);
  EXPECT_EQ(st.loops, 4u);
}

// The box primitive carries its corners once per face (hard edges): the cut meets each seam in two vertices at one
// point. Welded on the section, each side still gets one loop and a closed surface: the cap is the box's
// cross-section and every side's area-weighted normals sum to zero.
TEST(DffdCap, HardEdgedBoxClosesAcrossItsSeams) {
  const TriMesh box = make_primitive(PrimitiveKind::Box);
  ASSERT_GT(box.vertex_count(), 8u);  // per-face corner copies
  Aabb bounds;
  for (const glm::dvec3& p : box.positions) bounds.extend(p);
  for (int axis = 0; axis < 3; ++axis) {
    for (double u0 : {0.37, 0.5}) {
      const double eps = 1e-7;
      MeshSplit s = split_mesh_at_parameter(box, box_params(box), axis, u0, eps);
      const std::size_t first_cap = s.mesh.triangle_count();
      const CapStats st = cap_split_openings(s, axis, u0, eps);
      EXPECT_EQ(st.open_chains, 0u) << axis << " " << u0;
      EXPECT_EQ(st.loops, 2u) << axis << " " << u0;
      EXPECT_EQ(st.fan_loops, 0u) << axis << " " << u0;
      const glm::dvec3 size = bounds.size();
      const double section = size[(axis + 1) % 3] * size[(axis + 2) % 3];
      for (int side : {-1, 1}) {
        EXPECT_NEAR(cap_area(s, first_cap, side), section, 1e-9 * section) << axis << " " << side;
        glm::dvec3 sum(0.0);
        double total = 0.0;
        for (const glm::uvec3& f : s.mesh.triangles)
          if (s.side[f[0]] == side) {
            const glm::dvec3 n = tri_normal(s.mesh, f);
            sum += n, total += glm::length(n);
          }
        EXPECT_LT(glm::length(sum), 1e-9 * total) << "side " << side << " of axis " << axis << " is not closed";
      }
    }
  }
}

TEST(DffdCap, OpenMeshLeavesChainsOpen) {
  // The plane primitive (open, in y = 0): the cut x = 0 gives one open chain per side, nothing to cap.
  const TriMesh plane = make_primitive(PrimitiveKind::Plane);
  std::vector<glm::dvec3> params;
  for (const glm::dvec3& p : plane.positions) params.push_back({(p.x + 1.0) / 2.0, 0.5, (p.z + 1.0) / 2.0});
  MeshSplit s = split_mesh_at_parameter(plane, params, 0, 0.43, 1e-9);
  const std::vector<glm::uvec3> before = s.mesh.triangles;
  const CapStats st = cap_split_openings(s, 0, 0.43, 1e-9);
  EXPECT_EQ(st.open_chains, 2u);
  EXPECT_EQ(st.loops, 0u);
  EXPECT_EQ(st.triangles, 0u);
  EXPECT_EQ(s.mesh.triangles, before);
  EXPECT_TRUE(s.mesh.face_material.empty());
  // A sphere with its top removed, cut through the opening: open arcs, not capped; a cut below the opening is
  // a closed circle and is capped.
  const TriMesh sphere = make_sphere(32, 16);
  TriMesh open = sphere;
  open.triangles.clear();
  for (const glm::uvec3& f : sphere.triangles)
    if (sphere.positions[f[0]].y + sphere.positions[f[1]].y + sphere.positions[f[2]].y < 3 * 0.5)
      open.triangles.push_back(f);
  const std::vector<glm::dvec3> op = box_params(sphere);
  MeshSplit a = split_mesh_at_parameter(open, op, 0, 0.5, 1e-9);
  const CapStats sa = cap_split_openings(a, 0, 0.5, 1e-9);
  EXPECT_EQ(sa.open_chains, 2u);
  EXPECT_EQ(sa.triangles, 0u);
  MeshSplit b = split_mesh_at_parameter(open, op, 1, 0.3, 1e-9);
  const CapStats sb = cap_split_openings(b, 1, 0.3, 1e-9);
  EXPECT_EQ(sb.open_chains, 0u);
  EXPECT_EQ(sb.loops, 2u);
  EXPECT_GT(sb.triangles, 0u);
  const OmCheck lower = om_check(b, -1);
  EXPECT_EQ(lower.boundary_edges, 0u);  // the lower part is closed by its cap
  EXPECT_EQ(lower.rejected_faces, 0u);
  EXPECT_GT(om_check(b, 1).boundary_edges, 0u);  // the upper part keeps the removed top open
}

TEST(DffdCap, MaterialsAndDeterminism) {
  TriMesh sphere = make_sphere(40, 21);
  sphere.face_material.assign(sphere.triangle_count(), kMaterialSurface);
  sphere.face_material[3] = kMaterialInside;  // an existing slot is kept
  const std::vector<glm::dvec3> params = box_params(sphere);
  MeshSplit a = split_mesh_at_parameter(sphere, params, 1, 0.61, 1e-8);
  MeshSplit b = split_mesh_at_parameter(sphere, params, 1, 0.61, 1e-8);
  const std::size_t n0 = a.mesh.triangle_count();
  const std::vector<MaterialSlot> mat0 = a.mesh.face_material;
  const CapStats sa = cap_split_openings(a, 1, 0.61, 1e-8, 7);
  const CapStats sb = cap_split_openings(b, 1, 0.61, 1e-8, 7);
  EXPECT_GT(sa.triangles, 0u);
  EXPECT_EQ(sa.triangles, sb.triangles);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.face_material, b.mesh.face_material);
  ASSERT_EQ(a.mesh.face_material.size(), a.mesh.triangle_count());
  EXPECT_TRUE(std::equal(mat0.begin(), mat0.end(), a.mesh.face_material.begin()));
  EXPECT_EQ(std::count(a.mesh.face_material.begin() + n0, a.mesh.face_material.end(), 7), long(sa.triangles));
  // A plane that misses the mesh: nothing appended, nothing changed.
  MeshSplit c = split_mesh_at_parameter(sphere, params, 1, 1.5, 1e-8);
  const CapStats sc = cap_split_openings(c, 1, 1.5, 1e-8);
  EXPECT_EQ(sc.loops + sc.open_chains + sc.triangles, 0u);
  EXPECT_EQ(c.mesh.triangles, sphere.triangles);
}

TEST(DffdCap, RejectsBadInput) {
  const TriMesh sphere = make_sphere(8, 4);
  MeshSplit s = split_mesh_at_parameter(sphere, box_params(sphere), 0, 0.5, 1e-9);
  EXPECT_THROW(cap_split_openings(s, 3, 0.5, 1e-9), std::invalid_argument);
  EXPECT_THROW(cap_split_openings(s, -1, 0.5, 1e-9), std::invalid_argument);
  MeshSplit bad = s;
  bad.params.pop_back();
  EXPECT_THROW(cap_split_openings(bad, 0, 0.5, 1e-9), std::invalid_argument);
  bad = s;
  bad.side.push_back(1);
  EXPECT_THROW(cap_split_openings(bad, 0, 0.5, 1e-9), std::invalid_argument);
  bad = s;
  bad.mesh.face_material.assign(2, kMaterialSurface);
  EXPECT_THROW(cap_split_openings(bad, 0, 0.5, 1e-9), std::invalid_argument);
  EXPECT_EQ(bad.mesh.triangles, s.mesh.triangles);  // untouched on error
}

#ifdef TRISPLINE_HAVE_BUNNY
TEST(DffdCap, StanfordBunnyCapsEveryCut) {
  const TriMesh bunny = load_mesh(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/bunny.obj");
  ASSERT_GT(bunny.triangle_count(), 60000u);
  MeshSplit whole;  // the asset is closed: the checks below then mean "each side is a closed 2-manifold"
  whole.mesh = bunny;
  whole.side.assign(bunny.vertex_count(), -1);
  ASSERT_EQ(om_check(whole, 0).boundary_edges, 0u);
  for (int axis = 0; axis < 3; ++axis) {
    CapStats st;
    split_and_cap(bunny, axis, 0.5, 1e-9, &st);  // no open chain, closed sides, orientation, materials
    EXPECT_GT(st.triangles, 500u) << axis;
  }
  // x = 0.5 crosses the asset in two separate sections (two loops per side).
  CapStats st;
  split_and_cap(bunny, 0, 0.5, 1e-9, &st);
  EXPECT_EQ(st.loops, 4u);
}
#endif

}  // namespace
}  // namespace trispline::core

namespace trispline::core {
namespace {

// Textured caps (CapTexturing): the caps get vertices of their own at the same points, with uvs that are the plane's
// two other parameter coordinates scaled per axis; the surface keeps its vertices, and welding the copies back onto
// the cut vertices gives the untextured caps' closed sides.
TEST(DffdCap, TexturedCapsOwnVerticesWithPlanarUvs) {
  const TriMesh sphere = make_primitive(PrimitiveKind::Sphere);
  const int axis = 2;
  const double u0 = 0.41, eps = 1e-7;
  const CapTexturing tex{glm::dvec3(3.0, 5.0, 7.0)};
  MeshSplit plain = split_mesh_at_parameter(sphere, box_params(sphere), axis, u0, eps);
  MeshSplit textured = plain;
  const std::size_t nv = plain.mesh.vertex_count(), first_cap = plain.mesh.triangle_count();
  const CapStats a = cap_split_openings(plain, axis, u0, eps);
  const CapStats b = cap_split_openings(textured, axis, u0, eps, kMaterialInside, tex);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.loops, b.loops);
  ASSERT_GT(b.triangles, 0u);
  // One copy per vertex the caps use, appended; params, side and sizes kept consistent.
  std::vector<std::uint32_t> used;
  for (std::size_t f = first_cap; f < plain.mesh.triangle_count(); ++f)
    for (int c = 0; c < 3; ++c) used.push_back(plain.mesh.triangles[f][c]);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  ASSERT_EQ(textured.mesh.vertex_count(), nv + used.size());
  EXPECT_EQ(textured.params.size(), textured.mesh.vertex_count());
  EXPECT_EQ(textured.side.size(), textured.mesh.vertex_count());
  EXPECT_EQ(textured.mesh.uvs.size(), textured.mesh.vertex_count());
  EXPECT_EQ(textured.mesh.normals.size(), textured.mesh.vertex_count());
  for (std::size_t f = 0; f < first_cap; ++f) EXPECT_EQ(textured.mesh.triangles[f], plain.mesh.triangles[f]) << f;
  for (std::size_t k = 0; k < used.size(); ++k) {
    const std::size_t v = nv + k, of = used[k];
    EXPECT_EQ(textured.mesh.positions[v], textured.mesh.positions[of]);
    EXPECT_EQ(textured.params[v], textured.params[of]);
    EXPECT_EQ(textured.side[v], textured.side[of]);
    EXPECT_DOUBLE_EQ(textured.mesh.uvs[v].x, textured.params[of][0] * 3.0);  // axis z: the plane's x and y
    EXPECT_DOUBLE_EQ(textured.mesh.uvs[v].y, textured.params[of][1] * 5.0);
  }
  // The cap triangles are the untextured ones on the copies, in the same order; all of them use only copies.
  for (std::size_t f = first_cap; f < textured.mesh.triangle_count(); ++f) {
    const glm::uvec3 t = textured.mesh.triangles[f], p = plain.mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      ASSERT_GE(t[c], nv) << f;
      EXPECT_EQ(used[t[c] - nv], p[c]) << f;
    }
    EXPECT_EQ(textured.mesh.face_material[f], kMaterialInside);
  }
  // Re-welded onto the vertices they copy, the caps close both sides as before.
  MeshSplit welded = textured;
  for (std::size_t f = first_cap; f < welded.mesh.triangle_count(); ++f)
    for (int c = 0; c < 3; ++c) welded.mesh.triangles[f][c] = used[welded.mesh.triangles[f][c] - nv];
  welded.mesh.positions.resize(nv);
  welded.mesh.normals.resize(nv);
  welded.mesh.uvs.resize(nv);
  welded.params.resize(nv);
  welded.side.resize(nv);
  for (int side : {-1, 1}) EXPECT_EQ(om_check(welded, side).boundary_edges, 0u) << side;
  EXPECT_EQ(welded.mesh.triangles, plain.mesh.triangles);
  // Non-finite texturing is refused, the split unchanged.
  MeshSplit bad = split_mesh_at_parameter(sphere, box_params(sphere), axis, u0, eps);
  const std::size_t bad_v = bad.mesh.vertex_count();
  EXPECT_THROW(cap_split_openings(bad, axis, u0, eps, kMaterialInside, CapTexturing{glm::dvec3(1.0, NAN, 1.0)}),
               std::invalid_argument);
  EXPECT_EQ(bad.mesh.vertex_count(), bad_v);
}

}  // namespace
}  // namespace trispline::core

namespace trispline::core {
namespace {

// Refined textured caps (CapTexturing::max_edge): every inner cap edge at most max_edge in the plane's parameters, the
// loop's edges kept (the refined caps' boundary is the unrefined caps' boundary, vertex for vertex), no T-junction
// (every other edge used twice), the parameter-space area unchanged, and new vertices in the plane.
TEST(DffdCap, RefinedTexturedCapsConformAndKeepTheLoop) {
  const TriMesh sphere = make_primitive(PrimitiveKind::Sphere);
  const int axis = 0;
  const double u0 = 0.43, eps = 1e-7, h = 0.03;
  MeshSplit coarse = split_mesh_at_parameter(sphere, box_params(sphere), axis, u0, eps);
  MeshSplit fine = coarse;
  const std::size_t first_cap = coarse.mesh.triangle_count();
  cap_split_openings(coarse, axis, u0, eps, kMaterialInside, CapTexturing{glm::dvec3(1.0), 0.0});
  CapTexturing with_normals{glm::dvec3(1.0), h};
  with_normals.plane_normals[0] = glm::dvec3(1, 0, 0);
  cap_split_openings(fine, axis, u0, eps, kMaterialInside, with_normals);
  ASSERT_GT(fine.mesh.triangle_count() - first_cap, 4 * (coarse.mesh.triangle_count() - first_cap));
  EXPECT_EQ(fine.params.size(), fine.mesh.vertex_count());
  EXPECT_EQ(fine.mesh.uvs.size(), fine.mesh.vertex_count());
  auto edge_uses = [&](const MeshSplit& s) {
    std::map<std::pair<unsigned, unsigned>, int> uses;
    for (std::size_t f = first_cap; f < s.mesh.triangle_count(); ++f)
      for (int e = 0; e < 3; ++e) {
        const unsigned a = s.mesh.triangles[f][e], b = s.mesh.triangles[f][(e + 1) % 3];
        ++uses[{std::min(a, b), std::max(a, b)}];
      }
    return uses;
  };
  auto boundary = [&](const MeshSplit& s) {
    std::set<std::pair<unsigned, unsigned>> b;
    for (const auto& [e, n] : edge_uses(s)) {
      EXPECT_LE(n, 2);
      if (n == 1) b.insert(e);
    }
    return b;
  };
  EXPECT_EQ(boundary(fine), boundary(coarse));  // the loop, vertex for vertex; no T-junction inside
  auto area2d = [&](const MeshSplit& s) {
    double area = 0.0;
    for (std::size_t f = first_cap; f < s.mesh.triangle_count(); ++f) {
      const glm::uvec3 t = s.mesh.triangles[f];
      const glm::dvec3 p = s.params[t[0]], q = s.params[t[1]], r = s.params[t[2]];
      area += std::abs((q.y - p.y) * (r.z - p.z) - (q.z - p.z) * (r.y - p.y)) / 2;
    }
    return area;
  };
  EXPECT_NEAR(area2d(fine), area2d(coarse), 1e-12);
  for (const auto& [e, n] : edge_uses(fine)) {
    if (n != 2) continue;
    const glm::dvec3 d = fine.params[e.first] - fine.params[e.second];
    EXPECT_LE(std::max(std::abs(d.y), std::abs(d.z)), h) << e.first << "-" << e.second;
  }
  for (std::size_t v = coarse.mesh.vertex_count(); v < fine.mesh.vertex_count(); ++v) {
    EXPECT_NEAR(fine.params[v].x, u0 + fine.side[v] * eps, 1e-12);                     // on its side's cap plane
    EXPECT_EQ(fine.mesh.normals[v], glm::dvec3(fine.side[v] < 0 ? 1.0 : -1.0, 0, 0));  // facing out of its side
    EXPECT_NEAR(fine.mesh.uvs[v].x, fine.params[v].y, 1e-12);
  }
  // Deterministic.
  MeshSplit again = split_mesh_at_parameter(sphere, box_params(sphere), axis, u0, eps);
  cap_split_openings(again, axis, u0, eps, kMaterialInside, with_normals);
  EXPECT_EQ(again.mesh.triangles, fine.mesh.triangles);
  EXPECT_EQ(again.mesh.positions, fine.mesh.positions);
}

}  // namespace
}  // namespace trispline::core
