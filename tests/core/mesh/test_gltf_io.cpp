// scene.glb export: what write_glb writes, read back, is what was given (float32 positions, order, names, colours).
#include <algorithm>
#include <fstream>
#include <iterator>

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

// Object names come from the user's files in any encoding (an OBJ group in Latin-1, a truncated multi-byte name):
// glTF's JSON needs UTF-8, so each bad byte becomes U+FFFD and well-formed names stay as they are.
TEST(GltfIo, NamesThatAreNotUtf8AreRepairedNotFatal) {
  TempDir dir;
  const TriMesh a = grid_mesh(2, 0.0);
  const std::string latin1 = "caf\xE9", truncated = "\xE2\x82", surrogate = "\xED\xA0\x80x",
                    fine = "na\xC3\xAFve \xF0\x9F\x90\x9C";
  write_glb(dir / "s.glb", {{latin1, &a, glm::vec3(1)},
                            {truncated, &a, glm::vec3(1)},
                            {surrogate, &a, glm::vec3(1)},
                            {fine, &a, glm::vec3(1)}});
  const auto objects = read_gltf_objects(dir / "s.glb");
  ASSERT_EQ(objects.size(), 4u);
  const std::string bad = "\xEF\xBF\xBD";
  EXPECT_EQ(objects[0].name, "caf" + bad);
  EXPECT_EQ(objects[1].name, bad + bad);
  EXPECT_EQ(objects[2].name, bad + bad + bad + "x");
  EXPECT_EQ(objects[3].name, fine);
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

TEST(GltfIo, InsideFacesGetTheirOwnPrimitiveAndMaterial) {
  TempDir dir;
  TriMesh a = grid_mesh(4, 0.0);
  a.face_material.assign(a.triangle_count(), kMaterialSurface);
  for (std::size_t f = 5; f < a.triangle_count(); f += 4) a.face_material[f] = kMaterialInside;
  const std::size_t inside = std::count(a.face_material.begin(), a.face_material.end(), kMaterialInside);
  GltfNode node{"cut", &a, glm::vec3(0.2f, 0.4f, 0.6f)};
  node.inside_color = glm::vec3(0.7f, 0.1f, 0.05f);
  write_glb(dir / "s.glb", {node});

  // Read back: the vertices are shared (not duplicated), surface faces first then inside faces, each in face order.
  const auto objects = read_gltf_objects(dir / "s.glb");
  ASSERT_EQ(objects.size(), 1u);
  const TriMesh& got = objects[0].mesh;
  EXPECT_EQ(got.vertex_count(), a.vertex_count());
  ASSERT_EQ(got.triangle_count(), a.triangle_count());
  ASSERT_EQ(got.face_material.size(), got.triangle_count());
  std::vector<glm::uvec3> surface, cut;
  for (std::size_t f = 0; f < a.triangle_count(); ++f)
    (a.face_material[f] == kMaterialInside ? cut : surface).push_back(a.triangles[f]);
  for (std::size_t f = 0; f < got.triangle_count(); ++f) {
    const bool is_inside = f >= surface.size();
    EXPECT_EQ(got.face_material[f], is_inside ? kMaterialInside : kMaterialSurface) << f;
    EXPECT_EQ(got.triangles[f], is_inside ? cut[f - surface.size()] : surface[f]) << f;
  }
  EXPECT_EQ(std::size_t(std::count(got.face_material.begin(), got.face_material.end(), kMaterialInside)), inside);
  EXPECT_FLOAT_EQ(objects[0].color.y, 0.4f);
  EXPECT_FLOAT_EQ(objects[0].inside_color.x, 0.7f);
  EXPECT_FLOAT_EQ(objects[0].inside_color.z, 0.05f);

  // The same mesh without inside faces is written byte for byte as a mesh without face_material.
  TriMesh plain = a;
  plain.face_material.assign(a.triangle_count(), kMaterialSurface);
  TriMesh none = a;
  none.face_material.clear();
  write_glb(dir / "p.glb", {{"cut", &plain, glm::vec3(0.2f, 0.4f, 0.6f)}});
  write_glb(dir / "n.glb", {{"cut", &none, glm::vec3(0.2f, 0.4f, 0.6f)}});
  std::ifstream f1(dir / "p.glb", std::ios::binary), f2(dir / "n.glb", std::ios::binary);
  const std::string p((std::istreambuf_iterator<char>(f1)), {}), n((std::istreambuf_iterator<char>(f2)), {});
  EXPECT_EQ(p, n);
  EXPECT_EQ(p.find(".inside"), std::string::npos);
  EXPECT_TRUE(read_gltf_objects(dir / "n.glb")[0].mesh.face_material.empty());

  // Only inside faces: one primitive, the inside one.
  TriMesh all = a;
  all.face_material.assign(a.triangle_count(), kMaterialInside);
  write_glb(dir / "i.glb", {{"cut", &all, glm::vec3(1.0f)}});
  const TriMesh back = read_gltf_objects(dir / "i.glb")[0].mesh;
  EXPECT_EQ(back.triangles, a.triangles);
  EXPECT_EQ(back.face_material, all.face_material);
  // A face_material of the wrong size is an error.
  TriMesh bad = a;
  bad.face_material.pop_back();
  EXPECT_THROW(write_glb(dir / "bad.glb", {{"bad", &bad, glm::vec3(1)}}), MeshIoError);
}

}  // namespace
}  // namespace trispline::core
