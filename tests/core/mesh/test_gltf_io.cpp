// scene.glb export: what write_glb writes, read back, is what was given (float32 positions, order, names, colours).
#include "core/mesh/gltf_io.h"
#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;

TriMesh grid_mesh(int n, double z) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back({0.1 * i + 1e-9 * j, 0.1 * j, z + 0.3333333333 * i * j});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const unsigned a = i + (n + 1) * j;
      m.triangles.push_back({a, a + 1, a + n + 2});
      m.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  compute_vertex_normals(m);
  return m;
}

TEST(GltfIo, GlbExportThenLoadIsIdenticalInFloat) {
  TempDir dir;
  const TriMesh a = grid_mesh(7, 0.0);
  TriMesh b = test::tetrahedron();
  b.uvs = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}};
  write_glb(dir / "scene.glb", {{"teapot", &a, {0.9f, 0.6f, 0.0f}}, {"bunny.001", &b, {0.1f, 0.2f, 0.3f}}});
  EXPECT_FALSE(std::filesystem::exists(dir / "scene.glb.tmp"));

  const auto objects = read_gltf_objects(dir / "scene.glb");
  ASSERT_EQ(objects.size(), 2u);
  const TriMesh* src[] = {&a, &b};
  const char* names[] = {"teapot", "bunny.001"};
  for (int k = 0; k < 2; ++k) {
    const TriMesh& got = objects[k].mesh;
    EXPECT_EQ(objects[k].name, names[k]);
    ASSERT_EQ(got.vertex_count(), src[k]->vertex_count());
    ASSERT_EQ(got.triangles, src[k]->triangles);
    for (std::size_t i = 0; i < got.positions.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(got.positions[i][c], double(float(src[k]->positions[i][c]))) << names[k] << " vertex " << i;
  }
  EXPECT_EQ(objects[0].mesh.normals.size(), a.vertex_count());
  EXPECT_TRUE(objects[0].mesh.uvs.empty());
  ASSERT_EQ(objects[1].mesh.uvs.size(), 4u);
  EXPECT_EQ(objects[1].mesh.uvs[3], glm::dvec2(0.5, 0.5));
  EXPECT_FLOAT_EQ(objects[1].color.z, 0.3f);

  // load_mesh merges all nodes in order.
  const TriMesh merged = load_mesh(dir / "scene.glb");
  EXPECT_EQ(merged.vertex_count(), a.vertex_count() + b.vertex_count());
  EXPECT_EQ(merged.triangles.back(), b.triangles.back() + glm::uvec3(unsigned(a.vertex_count())));
}

TEST(GltfIo, OverwritesAtomicallyAndIsDeterministic) {
  TempDir dir;
  const TriMesh a = grid_mesh(3, 1.0);
  write_glb(dir / "s.glb", {{"a", &a, glm::vec3(0.5f)}});
  std::ifstream f1(dir / "s.glb", std::ios::binary);
  const std::string first((std::istreambuf_iterator<char>(f1)), {});
  write_glb(dir / "s.glb", {{"a", &a, glm::vec3(0.5f)}});
  std::ifstream f2(dir / "s.glb", std::ios::binary);
  const std::string second((std::istreambuf_iterator<char>(f2)), {});
  EXPECT_EQ(first, second);
  EXPECT_EQ(first.substr(0, 4), "glTF");
}

TEST(GltfIo, EmptyObjectsBecomeMeshlessNodesAndBadMeshesThrow) {
  TempDir dir;
  const TriMesh a = grid_mesh(2, 0.0);
  const TriMesh empty;
  write_glb(dir / "s.glb", {{"empty", &empty, glm::vec3(1)}, {"a", &a, glm::vec3(1)}, {"null", nullptr, glm::vec3(1)}});
  const auto objects = read_gltf_objects(dir / "s.glb");
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].name, "a");

  TriMesh bad = a;
  bad.triangles.push_back({0, 1, 99});
  EXPECT_THROW(write_glb(dir / "bad.glb", {{"bad", &bad, glm::vec3(1)}}), MeshIoError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
  EXPECT_THROW(write_glb(dir / "no/such/dir/x.glb", {{"a", &a, glm::vec3(1)}}), MeshIoError);
}

}  // namespace
}  // namespace trispline::core
