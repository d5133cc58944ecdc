// Real input: the Stanford bunny fetched by the asset script (glmark2-data). Compiled only when the file exists at
// configure time (see CMakeLists.txt), so it never skips silently.
#include <gtest/gtest.h>

#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

TEST(MeshIoAssets, StanfordBunny) {
  const TriMesh m = load_mesh(std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/bunny.obj");
  EXPECT_EQ(m.vertex_count(), 34835u);
  EXPECT_GT(m.triangle_count(), 60000u);
  EXPECT_EQ(m.normals.size(), m.vertex_count());
  EXPECT_TRUE(mesh_bounds(m).valid());
}

}  // namespace
}  // namespace trispline::core
