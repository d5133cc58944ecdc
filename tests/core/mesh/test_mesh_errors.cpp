// Every bad input gives MeshIoError whose message names the reason.
#include <gmock/gmock.h>

#include <limits>

#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;
using test::write_text;
using ::testing::HasSubstr;

// Loads `path` expecting MeshIoError with `reason` in its message.
void expect_error(const std::filesystem::path& path, const std::string& reason) {
  try {
    load_mesh(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const MeshIoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(reason)) << path;
    EXPECT_THAT(e.what(), HasSubstr(path.filename().string())) << "message should name the file";
  }
}

TEST(MeshIoErrors, MissingFile) {
  TempDir dir;
  for (const char* name : {"nope.obj", "nope.ply", "nope.off", "nope.stl", "nope.gltf", "nope.glb"})
    expect_error(dir / name, "file not found");
}

TEST(MeshIoErrors, UnsupportedExtension) {
  TempDir dir;
  write_text(dir / "mesh.xyz", "1 2 3\n");
  expect_error(dir / "mesh.xyz", "unsupported extension");
  write_text(dir / "noext", "v 0 0 0\n");
  expect_error(dir / "noext", "unsupported extension");
}

TEST(MeshIoErrors, CorruptFiles) {
  TempDir dir;
  write_text(dir / "bad.ply", "ply\nformat binary_little_endian 1.0\nelement vertex banana\nend_header\n\x01\x02");
  expect_error(dir / "bad.ply", "cannot parse");
  write_text(dir / "bad.glb", "glTF\x02\0\0\0garbage garbage garbage");
  expect_error(dir / "bad.glb", "cannot parse");
  write_text(dir / "bad.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ ");
  expect_error(dir / "bad.gltf", "cannot parse");
  write_text(dir / "bad.off", "OFF\n3 x 0\n");
  expect_error(dir / "bad.off", "cannot parse");
  write_text(dir / "bad.stl", std::string(40, '\x07'));  // binary STL shorter than its 84-byte header
  expect_error(dir / "bad.stl", "cannot parse");
}

TEST(MeshIoErrors, NonFiniteCoordinates) {
  TempDir dir;
  // Binary PLY carries NaN / inf bit patterns exactly.
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, bad, 0};
    ply.append(reinterpret_cast<const char*>(v), sizeof v);
    const unsigned char n = 3;
    const int idx[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(&n), 1);
    ply.append(reinterpret_cast<const char*>(idx), sizeof idx);
    write_text(dir / "nan.ply", ply);
    expect_error(dir / "nan.ply", "non-finite vertex coordinate");
  }
}

TEST(MeshIoErrors, NonFiniteCoordinatesInTextFormats) {
  // OpenMesh's text readers would drop or zero these; the loader reports them.
  TempDir dir;
  write_text(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_error(dir / "nan.obj", "non-finite vertex coordinate");
  write_text(dir / "inf.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n");
  expect_error(dir / "inf.obj", "non-finite vertex coordinate");
  write_text(dir / "inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n");
  expect_error(dir / "inf.off", "non-finite vertex coordinate");
  write_text(dir / "nan.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 NaN 0\n3 0 1 2\n");
  expect_error(dir / "nan.ply", "non-finite vertex coordinate");
  write_text(dir / "nan.stl",
             "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex nan 0 0\n"
             "   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n");
  expect_error(dir / "nan.stl", "non-finite vertex coordinate");
}

TEST(MeshIoErrors, EmptyMeshes) {
  TempDir dir;
  write_text(dir / "empty.obj", "# nothing here\n");
  expect_error(dir / "empty.obj", "empty mesh");
  write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_error(dir / "points.obj", "empty mesh (no triangles)");
  write_text(dir / "empty.off", "OFF\n0 0 0\n");
  expect_error(dir / "empty.off", "empty mesh");
  write_text(dir / "empty.gltf", "{ \"asset\": { \"version\": \"2.0\" } }");
  expect_error(dir / "empty.gltf", "empty mesh");
}

TEST(MeshIoErrors, IndexOutOfRange) {
  TempDir dir;
  write_text(dir / "oor.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  expect_error(dir / "oor.obj", "out of range");
  write_text(dir / "neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n");
  expect_error(dir / "neg.obj", "out of range");
  write_text(dir / "oor.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  expect_error(dir / "oor.off", "out of range");
  write_text(dir / "oor.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  expect_error(dir / "oor.ply", "out of range");
  // glTF: 3 float positions then uint16 indices {0, 1, 7}.
  write_text(
      dir / "oor.gltf",
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)"
      R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAcAAAA="}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})");
  expect_error(dir / "oor.gltf", "out of range");
}

TEST(MeshIoErrors, ValidateMeshDirectly) {
  TriMesh m = test::tetrahedron();
  EXPECT_NO_THROW(validate_mesh(m, "tet"));
  TriMesh bad = m;
  bad.triangles.push_back({0, 1, 4});
  EXPECT_THROW(validate_mesh(bad, "tet"), MeshIoError);
  bad = m;
  bad.positions[2].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate_mesh(bad, "tet"), MeshIoError);
  bad = m;
  bad.normals.resize(2);
  EXPECT_THROW(validate_mesh(bad, "tet"), MeshIoError);
  EXPECT_THROW(validate_mesh(TriMesh{}, "nothing"), MeshIoError);
}

TEST(MeshIoErrors, SaveRejectsUnsupportedExtension) {
  TempDir dir;
  EXPECT_THROW(save_mesh(dir / "t.stl", test::tetrahedron()), MeshIoError);
  EXPECT_THROW(save_mesh(dir / "t.obj", TriMesh{}), MeshIoError);
}

}  // namespace
}  // namespace trispline::core
