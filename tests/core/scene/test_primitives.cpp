// scene.primitive meshes: kinds, bounds from the conventions, closedness, orientation, determinism.
#include "core/scene/primitives.h"
#include "primitive_checks.h"

namespace trispline::core {
namespace {

void expect_bounds(const TriMesh& m, glm::dvec3 lo, glm::dvec3 hi, double tol, const std::string& what) {
  const Aabb b = mesh_bounds(m);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(b.lo[c], lo[c], tol) << what << " lo[" << c << "]";
    EXPECT_NEAR(b.hi[c], hi[c], tol) << what << " hi[" << c << "]";
  }
}

TEST(Primitives, ParseKinds) {
  for (const char* name : {"teapot", "plane", "sphere", "box", "cylinder", "terrain"})
    EXPECT_EQ(primitive_kind_name(parse_primitive_kind(name)), name);
  try {
    parse_primitive_kind("torus");
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("torus"), std::string::npos);
    EXPECT_NE(msg.find("teapot, plane, sphere, box, cylinder, terrain"), std::string::npos);
  }
  EXPECT_THROW(parse_primitive_kind("Teapot"), std::invalid_argument);
}

TEST(Primitives, PlaneIsTwoByTwoInXzFacingUp) {
  const TriMesh m = make_primitive(PrimitiveKind::Plane);
  test::expect_valid_with_unit_normals(m, "plane");
  expect_bounds(m, {-1, 0, -1}, {1, 0, 1}, 1e-15, "plane");
  EXPECT_EQ(m.vertex_count(), 33u * 33u);
  EXPECT_EQ(m.triangle_count(), 2u * 32u * 32u);
  for (const auto& t : m.triangles) {  // CCW seen from +y
    const glm::dvec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    ASSERT_GT(n.y, 0.0);
  }
}

TEST(Primitives, ClosedPrimitivesAreWatertightAndPositive) {
  const double pi = std::acos(-1.0);
  struct Case {
    PrimitiveKind kind;
    glm::dvec3 lo, hi;
    double volume, vol_tol;
    bool split_edges;
  };
  const Case cases[] = {
      {PrimitiveKind::Sphere, glm::dvec3(-1), glm::dvec3(1), 4.0 / 3.0 * pi, 0.02, false},
      {PrimitiveKind::Box, glm::dvec3(-1), glm::dvec3(1), 8.0, 1e-12, true},
      {PrimitiveKind::Cylinder, {-1, -1, -1}, {1, 1, 1}, 2.0 * pi, 0.02, true},
  };
  for (const auto& c : cases) {
    const std::string what = primitive_kind_name(c.kind);
    const TriMesh m = make_primitive(c.kind);
    test::expect_valid_with_unit_normals(m, what);
    expect_bounds(m, c.lo, c.hi, 1e-12, what);
    const double v = signed_volume(m);
    EXPECT_GT(v, 0.0) << what;
    EXPECT_NEAR(v, c.volume, c.vol_tol) << what;
    // Split (flat-shaded) edges have their own vertices: consistent orientation is checked where vertices are shared.
    int boundary = 0;
    EXPECT_EQ(test::orientation_defects(m, &boundary), 0) << what;
    if (!c.split_edges) {
      EXPECT_EQ(boundary, 0) << what;
    }
    // Normals point outwards: away from the centre for the sphere; along the face for box/cylinder caps.
    for (std::size_t i = 0; i < m.vertex_count(); ++i)
      ASSERT_GE(glm::dot(m.normals[i], m.positions[i]), 0.0) << what << " vertex " << i;
  }
}

TEST(Primitives, TerrainHeightsAndSeeds) {
  const TriMesh a = make_primitive(PrimitiveKind::Terrain, 7);
  test::expect_valid_with_unit_normals(a, "terrain");
  expect_bounds(a, {-1, 0, -1}, {1, 0.3, 1}, 1e-15, "terrain");
  for (const auto& p : a.positions) {
    ASSERT_GE(p.y, 0.0);
    ASSERT_LE(p.y, 0.3);
  }
  EXPECT_EQ(a.vertex_count(), 129u * 129u);
  for (const auto& n : a.normals) ASSERT_GT(n.y, 0.0);  // a height field faces up

  const TriMesh same = make_primitive(PrimitiveKind::Terrain, 7);
  EXPECT_EQ(same.positions, a.positions);  // bit-identical
  EXPECT_EQ(same.normals, a.normals);
  const TriMesh other = make_primitive(PrimitiveKind::Terrain, 8);
  EXPECT_NE(other.positions, a.positions);
  EXPECT_EQ(other.triangles, a.triangles);  // same grid
  // Smooth: neighbouring samples (2/128 apart) differ by far less than the full height range.
  double max_step = 0;
  for (std::size_t i = 1; i < a.positions.size(); ++i)
    if (a.positions[i].x > a.positions[i - 1].x)
      max_step = std::max(max_step, std::abs(a.positions[i].y - a.positions[i - 1].y));
  EXPECT_LT(max_step, 0.03);
}

TEST(Primitives, SeedOnlyAffectsTerrainAndEverythingIsDeterministic) {
  for (auto kind : {PrimitiveKind::Teapot, PrimitiveKind::Plane, PrimitiveKind::Sphere, PrimitiveKind::Box,
                    PrimitiveKind::Cylinder}) {
    const TriMesh a = make_primitive(kind, 1), b = make_primitive(kind, 2);
    EXPECT_EQ(a.positions, b.positions) << primitive_kind_name(kind);
    EXPECT_EQ(a.normals, b.normals) << primitive_kind_name(kind);
    EXPECT_EQ(a.triangles, b.triangles) << primitive_kind_name(kind);
  }
}

TEST(Primitives, BadResolutionsThrow) {
  EXPECT_THROW(make_plane(0), std::invalid_argument);
  EXPECT_THROW(make_sphere(2, 8), std::invalid_argument);
  EXPECT_THROW(make_cylinder(2), std::invalid_argument);
  EXPECT_THROW(make_terrain(0, 1), std::invalid_argument);
  EXPECT_THROW(make_teapot(1), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
