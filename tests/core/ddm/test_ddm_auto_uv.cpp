// Automatic UV charts (core/ddm/ddm_auto_uv.h): on meshes without texture coordinates (a sphere, a torus, the Stanford
// bunny) every uv triangle is counter-clockwise (no flipped chart), uvs lie in [0,1]², the split mesh keeps the
// triangles and their positions, texel density is even (area distortion reported), the result is the same bit for bit
// on a second run, and bad meshes are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/ddm/ddm_auto_uv.h"
#include "core/ddm/ddm_chart_size.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"
#include "tests/test_shapes.h"

namespace trispline::core {
namespace {

// Checks the contract of ddm_auto_uv on `mesh`; returns its stats.
DdmAutoUvStats check_unwrap(const TriMesh& mesh, const char* name) {
  DdmAutoUvStats st;
  const TriMesh out = ddm_auto_uv(mesh, &st);
  EXPECT_EQ(out.triangle_count(), mesh.triangle_count()) << name;
  EXPECT_EQ(out.uvs.size(), out.vertex_count()) << name;
  EXPECT_EQ(out.normals.size(), out.vertex_count()) << name;
  EXPECT_GE(out.vertex_count(), mesh.vertex_count()) << name;
  std::size_t flipped = 0;
  for (std::size_t f = 0; f < out.triangle_count(); ++f) {
    const glm::uvec3 t = out.triangles[f], o = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out.positions[t[k]], mesh.positions[o[k]]) << name << " face " << f;
    const glm::dvec2 e1 = out.uvs[t[1]] - out.uvs[t[0]], e2 = out.uvs[t[2]] - out.uvs[t[0]];
    const double world = glm::length(
        glm::cross(mesh.positions[o[1]] - mesh.positions[o[0]], mesh.positions[o[2]] - mesh.positions[o[0]]));
    if (world > 0.0 && !(e1.x * e2.y - e1.y * e2.x > 0.0)) ++flipped;
  }
  EXPECT_EQ(flipped, 0u) << name << ": uv triangles not counter-clockwise";
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const glm::dvec2& uv : out.uvs) lo = glm::min(lo, uv), hi = glm::max(hi, uv);
  EXPECT_GE(std::min(lo.x, lo.y), 0.0) << name;
  EXPECT_LE(std::max(hi.x, hi.y), 1.0) << name;
  EXPECT_GE(st.area_distortion_p95, 1.0);
  EXPECT_GE(st.area_distortion, st.area_distortion_p95);
  EXPECT_GT(st.charts, 0u);
  const TriMesh again = ddm_auto_uv(mesh);
  EXPECT_EQ(again.uvs, out.uvs) << name << ": not deterministic";
  EXPECT_EQ(again.triangles, out.triangles) << name;
  std::printf("%s: %zu triangles, %zu charts (%zu splits), area distortion max/min %.3f, p97.5/p2.5 %.3f, %.0f ms\n",
              name, mesh.triangle_count(), st.charts, st.splits, st.area_distortion, st.area_distortion_p95, st.ms);
  (void)ddm_uv_chart_size(out);  // a usable uv base
  return st;
}

TEST(DdmAutoUv, SphereAndTorusUnwrapWithoutFlips) {
  const DdmAutoUvStats sphere = check_unwrap(make_sphere(32, 16), "sphere 32x16");
  EXPECT_LT(sphere.area_distortion_p95, 2.0);
  const DdmAutoUvStats torus = check_unwrap(test::torus_mesh(48, 24, false), "torus 48x24");
  EXPECT_LT(torus.area_distortion_p95, 2.0);
}

#ifdef TRISPLINE_HAVE_BUNNY
TEST(DdmAutoUv, StanfordBunny) {
  const TriMesh bunny = load_mesh(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/bunny.obj");
  ASSERT_TRUE(bunny.uvs.empty());
  const DdmAutoUvStats st = check_unwrap(bunny, "bunny");
  EXPECT_LT(st.area_distortion_p95, 2.0);
}
#endif

TEST(DdmAutoUv, BadMeshesAreRefused) {
  EXPECT_THROW(ddm_auto_uv(TriMesh{}), std::invalid_argument);
  TriMesh fin;  // three triangles on one edge
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  EXPECT_THROW(ddm_auto_uv(fin), std::invalid_argument);
  TriMesh bad = make_sphere(8, 4);
  bad.triangles[0][1] = 999;
  EXPECT_THROW(ddm_auto_uv(bad), std::invalid_argument);
  EXPECT_THROW(ddm_auto_uv(make_sphere(8, 4), nullptr, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
