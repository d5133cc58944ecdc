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

struct BadFile {
  const char* name;
  std::string content;
  const char* reason;
};

// Writes each file into a fresh folder and loads it expecting MeshIoError with its reason.
void expect_errors(const std::vector<BadFile>& files) {
  TempDir dir;
  for (const BadFile& f : files) {
    write_text(dir / f.name, f.content);
    expect_error(dir / f.name, f.reason);
  }
}

TEST(MeshIoErrors, MissingFile) {
  TempDir dir;
  for (const char* name : {"nope.obj", "nope.ply", "nope.off", "nope.stl", "nope.gltf", "nope.glb"})
    expect_error(dir / name, "file not found");
}

TEST(MeshIoErrors, UnsupportedExtension) {
  expect_errors({
      {"mesh.xyz", "1 2 3\n", "unsupported extension"},
      {"noext", "v 0 0 0\n", "unsupported extension"},
  });
}

TEST(MeshIoErrors, CorruptFiles) {
  expect_errors({
      {"bad.ply", "ply\nformat binary_little_endian 1.0\nelement vertex banana\nend_header\n\x01\x02", "cannot parse"},
      {"bad.glb", "glTF\x02\0\0\0garbage garbage garbage", "cannot parse"},
      {"bad.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ ", "cannot parse"},
      {"bad.off", "OFF\n3 x 0\n", "cannot parse"},
      {"bad.stl", std::string(40, '\x07'), "cannot parse"},  // binary STL shorter than its 84-byte header
  });
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
  expect_errors({
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite vertex coordinate"},
      {"inf.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n", "non-finite vertex coordinate"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n", "non-finite vertex coordinate"},
      {"nan.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 NaN 0\n3 0 1 2\n",
       "non-finite vertex coordinate"},
      {"nan.stl",
       "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex nan 0 0\n"
       "   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n",
       "non-finite vertex coordinate"},
  });
}

TEST(MeshIoErrors, EmptyMeshes) {
  expect_errors({
      {"empty.obj", "# nothing here\n", "empty mesh"},
      {"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "empty mesh (no triangles)"},
      {"empty.off", "OFF\n0 0 0\n", "empty mesh"},
      {"empty.gltf", "{ \"asset\": { \"version\": \"2.0\" } }", "empty mesh"},
  });
}

TEST(MeshIoErrors, OffFacesAssimpWouldDrop) {
  // assimp drops an OFF face of 0 or more than 9 corners without counting it, so later lines would be read as faces.
  expect_errors({
      {"zero.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0\n3 0 1 2\n3 0 2 3\n", "face 0 has no corners"},
      {"ten.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n10 0 1 2 3 0 1 2 3 0 1\n", "has 10 corners"},
  });
}

TEST(MeshIoErrors, IndexOutOfRange) {
  expect_errors({
      {"oor.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "out of range"},
      {"neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n", "out of range"},
      {"oor.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "out of range"},
      {"oor.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "out of range"},
      // glTF: 3 float positions then uint16 indices {0, 1, 7}.
      {"oor.gltf",
       R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
       R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
       R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)"
       R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAcAAAA="}],)"
       R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
       R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
       R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})",
       "out of range"},
  });
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
