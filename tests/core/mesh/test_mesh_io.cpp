// Round trips through every supported format; the files are written by the test itself.
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>

#include "core/mesh/gltf_io.h"
#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;
using test::write_text;

// Loads `text` written to `dir / name`.
TriMesh load_text(const TempDir& dir, const std::string& name, const std::string& text) {
  write_text(dir / name, text);
  return load_mesh(dir / name);
}

void expect_same_mesh(const TriMesh& a, const TriMesh& b, double tol) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    EXPECT_LE(glm::length(a.positions[i] - b.positions[i]), tol) << "vertex " << i;
  for (std::size_t f = 0; f < a.triangles.size(); ++f) EXPECT_EQ(a.triangles[f], b.triangles[f]) << "triangle " << f;
}

TEST(MeshIo, ObjQuadIsFanTriangulatedInFileOrder) {
  TempDir dir;
  const TriMesh m =
      load_text(dir, "quad.obj",
                "# a unit quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n");
  ASSERT_EQ(m.vertex_count(), 5u);
  EXPECT_EQ(m.positions[4], glm::dvec3(2, 0, 0));
  ASSERT_EQ(m.triangle_count(), 3u);
  EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(m.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(m.triangles[2], glm::uvec3(1, 4, 2));
  ASSERT_EQ(m.normals.size(), 5u);  // computed: the file has none
  for (const auto& n : m.normals) EXPECT_NEAR(glm::length(n - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(MeshIo, ObjWithNormalsAndTexcoordsKeepsThem) {
  TempDir dir;
  const TriMesh m =
      load_text(dir, "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n");
  ASSERT_EQ(m.vertex_count(), 3u);
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_EQ(m.uvs[1], glm::dvec2(1, 1));  // vt 1 0 in glTF's v-down convention (model_load.h)
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_EQ(m.normals[2], glm::dvec3(0, 0, 1));
}

// Vertices come back in order of first use by the triangles (assimp's per-corner meshes, welded); a mesh already in
// that order — every loaded mesh — comes back exactly in order.
TEST(MeshIo, ObjAndPlySaveLoadRoundTrip) {
  TempDir dir;
  TriMesh m = test::tetrahedron();
  m.positions[3] = {0.1234567890123, -2.5e-7, 1.0 / 3.0};
  compute_vertex_normals(m);
  const std::vector<unsigned> first_use = {0, 2, 1, 3};  // tetrahedron() starts with the triangle (0, 2, 1)
  TriMesh reordered = m;
  for (std::size_t i = 0; i < first_use.size(); ++i) {
    reordered.positions[i] = m.positions[first_use[i]];
    reordered.normals[i] = m.normals[first_use[i]];
  }
  for (auto& t : reordered.triangles)
    for (int k = 0; k < 3; ++k)
      t[k] = static_cast<unsigned>(std::find(first_use.begin(), first_use.end(), t[k]) - first_use.begin());
  for (const char* name : {"t.obj", "t.ply"}) {
    save_mesh(dir / name, m);
    const TriMesh back = load_mesh(dir / name);
    // OBJ is written with 17 significant digits; PLY as float32 by OpenMesh: both well within 1e-6 here.
    expect_same_mesh(reordered, back, 1e-6);
    ASSERT_EQ(back.normals.size(), m.normals.size()) << name;
    EXPECT_GT(signed_volume(back), 0.0) << name;
    save_mesh(dir / name, back);
    expect_same_mesh(back, load_mesh(dir / name), 1e-6);
  }
}

TEST(MeshIo, AsciiPlyLoads) {
  TempDir dir;
  const TriMesh m =
      load_text(dir, "a.ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(m.positions[2], glm::dvec3(1, 1, 0));
}

TEST(MeshIo, OffLoadsInFileOrder) {
  TempDir dir;
  const TriMesh m = load_text(
      dir, "a.off", "OFF\n# comment\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 -1 # apex\n4 0 1 2 3\n3 1 0 4\n");
  ASSERT_EQ(m.vertex_count(), 5u);
  EXPECT_EQ(m.positions[4], glm::dvec3(0.5, 0.5, -1));
  ASSERT_EQ(m.triangle_count(), 3u);
  EXPECT_EQ(m.triangles[2], glm::uvec3(1, 0, 4));
}

TEST(MeshIo, AsciiStlMergesSharedCorners) {
  TempDir dir;
  const TriMesh m =
      load_text(dir, "a.stl",
                "solid quad\n"
                " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n"
                " endfacet\n"
                " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n"
                " endfacet\nendsolid quad\n");
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(mesh_bounds(m).hi, glm::dvec3(1, 1, 0));
}

TEST(MeshIo, BinaryStlLoads) {
  TempDir dir;
  std::string bytes(80, ' ');
  const std::uint32_t n = 1;
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  const float tri[12] = {0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0};  // normal, then 3 corners
  bytes.append(reinterpret_cast<const char*>(tri), sizeof tri);
  bytes.append(2, '\0');
  const TriMesh m = load_text(dir, "b.stl", bytes);
  EXPECT_EQ(m.vertex_count(), 3u);
  ASSERT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(mesh_bounds(m).hi, glm::dvec3(2, 2, 0));
}

// A .gltf with two nodes (a parent with a translation, a child with a uniform scale), uint16 and uint8 indices.
void write_test_gltf(const std::filesystem::path& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.buffers.resize(1);
  auto& data = model.buffers[0].data;
  auto add = [&](const void* p, std::size_t n, int ctype, int type, std::size_t count) {
    while (data.size() % 4) data.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = data.size();
    v.byteLength = n;
    data.insert(data.end(), static_cast<const unsigned char*>(p), static_cast<const unsigned char*>(p) + n);
    model.bufferViews.push_back(v);
    tinygltf::Accessor a;
    a.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
    a.componentType = ctype;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
  };
  const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::uint16_t idx16[] = {0, 1, 2};
  const std::uint8_t idx8[] = {0, 1, 2};
  const int p = add(pos, sizeof pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3);
  model.accessors[p].minValues = {0, 0, 0};
  model.accessors[p].maxValues = {1, 1, 0};
  const int n = add(nrm, sizeof nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3);
  const int i16 = add(idx16, sizeof idx16, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 3);
  const int i8 = add(idx8, sizeof idx8, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 3);
  for (int ind : {i16, i8}) {
    tinygltf::Mesh mesh;
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = p;
    prim.attributes["NORMAL"] = n;
    prim.indices = ind;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
  }
  tinygltf::Node parent, child;
  parent.name = "parent";
  parent.mesh = 0;
  parent.translation = {10, 0, 0};
  parent.children = {1};
  child.name = "child";
  child.mesh = 1;
  child.scale = {2, 2, 2};
  model.nodes = {parent, child};
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes = {scene};
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), false, true, true, false));
}

TEST(MeshIo, GltfNodesTransformsAndIndexTypes) {
  TempDir dir;
  write_test_gltf(dir / "two.gltf");
  const auto objects = read_gltf_objects(dir / "two.gltf");
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].name, "parent");
  EXPECT_EQ(objects[1].name, "child");
  EXPECT_EQ(objects[0].mesh.positions[1], glm::dvec3(11, 0, 0));  // translated
  EXPECT_EQ(objects[1].mesh.positions[1], glm::dvec3(12, 0, 0));  // parent translation ∘ child scale
  const TriMesh m = load_mesh(dir / "two.gltf");
  EXPECT_EQ(m.vertex_count(), 6u);
  ASSERT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(m.triangles[1], glm::uvec3(3, 4, 5));
  ASSERT_EQ(m.normals.size(), 6u);
  EXPECT_EQ(m.normals[4], glm::dvec3(0, 0, 1));
}

TEST(MeshIo, BoundsAndNormals) {
  TriMesh m = test::tetrahedron();
  const Aabb b = mesh_bounds(m);
  EXPECT_EQ(b.lo, glm::dvec3(0));
  EXPECT_EQ(b.hi, glm::dvec3(1));
  compute_vertex_normals(m);
  ASSERT_EQ(m.normals.size(), 4u);
  // Vertex 0 sees the three axis-aligned faces (equal areas): normal along −(1,1,1).
  EXPECT_NEAR(glm::length(m.normals[0] + glm::normalize(glm::dvec3(1))), 0.0, 1e-12);
  EXPECT_NEAR(signed_volume(m), 1.0 / 6.0, 1e-15);
  EXPECT_FALSE(mesh_bounds(TriMesh{}).valid());
}

}  // namespace
}  // namespace trispline::core
