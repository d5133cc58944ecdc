// OBJ / PLY / OFF / STL files as they come from other tools (through assimp): every face loads or the file is
// refused with a reason — per-face colours, COFF, comments and tabs (Geomview's samples), loose points and lines,
// truncated lines, 4-D OFF, UTF-16 text; and hostile files are refused by their size and head before they cost
// memory (sparse files, headers claiming 10⁹ elements, a path that is a device, a FIFO or a folder).
#include <gmock/gmock.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"
#include "tests/error_field.h"

namespace trispline::core {
namespace {

using test::TempDir;
using test::write_text;
using ::testing::HasSubstr;

std::string error_of(const std::filesystem::path& path, const MeshLoadOptions& options = {}) {
  return trispline::test::message_of<MeshIoError>([&] { load_mesh(path, options); }, "(loaded)");
}

// The error of loading `text` written to `dir / name`, "(loaded)" when it loads.
std::string error_of(const TempDir& dir, const std::string& name, const std::string& text,
                     const MeshLoadOptions& options = {}) {
  write_text(dir / name, text);
  return error_of(dir / name, options);
}

// The head of an ASCII PLY file of three float vertices, up to the next element's line.
const std::string kPlyThreeVertices =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

long max_rss_kb() {
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

// A file of `size` bytes that starts with `head` and is a hole (zeros, no disk) after it.
void write_sparse(const std::filesystem::path& p, const std::string& head, std::uintmax_t size) {
  write_text(p, head);
  std::filesystem::resize_file(p, size);
}

// Geomview's OFF as its sample files write it: comments, tabs, blank lines, RGBA per face.
TEST(MeshFiles, OffWithCommentsTabsBlankLinesAndFaceColoursLoadsEveryFace) {
  TempDir dir;
  write_text(dir / "facecube.off",
             "# a cube with a colour per face\nOFF\n8 6 12\n\n"
             "\t1 1 1\n\t1 1 -1   # a comment after a vertex\n\t1 -1 1\n\t1 -1 -1\n"
             "\t-1 1 1\n\t-1 1 -1\n\t-1 -1 1\n\t-1 -1 -1\n\n"
             "4 0 2 3 1\t1.0 0.0 0.0 1.0\n4 4 5 7 6\t0 1 0 1\n4 0 1 5 4\t0 0 1 1\n"
             "4 2 6 7 3\t1 1 0 1\n4 0 4 6 2  # no colour\n4 1 3 7 5\t0 1 1 1\n");
  const TriMesh m = load_mesh(dir / "facecube.off");
  EXPECT_EQ(m.triangle_count(), 12u);  // 6 quads: the old reader kept 1–3 triangles of such files
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_NEAR(std::abs(signed_volume(m)), 8.0, 1e-12);
}

TEST(MeshFiles, CoffWithVertexColoursAndNoKeywordOffLoad) {
  TempDir dir;
  write_text(dir / "coff.off",
             "COFF\n4 2 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n1 1 0 0 0 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n3 0 2 3\n");
  EXPECT_EQ(load_mesh(dir / "coff.off").triangle_count(), 2u);
  write_text(dir / "bare.off", "# no keyword: Geomview allows it\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(dir / "bare.off").triangle_count(), 1u);
  // Counts starting with 4 (or any digit) are counts, not the 4-D prefix: 4 vertices, 2 faces.
  write_text(dir / "bare4.off", "4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  EXPECT_EQ(load_mesh(dir / "bare4.off").triangle_count(), 2u);
  // "4 01 2006161000": 4 vertices, 1 face, 2·10⁹ edges (ignored) — assimp alone read 1 vertex and 2·10⁹ faces and
  // allocated 32 GB; now a truncated file like any other
  EXPECT_THAT(error_of(dir, "claims.off", "4 01  2006161000 013\n0 0 0\n"),
              HasSubstr("cannot parse: the OFF file ends after 0 of its 1 faces"));
}

TEST(MeshFiles, FourDimensionalOffIsRefusedNotProjected) {
  TempDir dir;
  EXPECT_THAT(error_of(dir, "tetra4.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n"),
              HasSubstr("4-D or n-D OFF file"));
}

TEST(MeshFiles, TruncatedObjLinesAreRefusedWithTheirLine) {
  TempDir dir;
  EXPECT_THAT(error_of(dir, "short_v.obj", "v 0 0 0\nv 1 0 0\nv 1 1\nv 0 1 0\nf 1 2 4\n"),
              HasSubstr("line 3: a vertex needs 3 coordinates, 2 given"));
  EXPECT_THAT(error_of(dir, "two_corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n"),
              HasSubstr("line 5: a face needs at least 3 corners, 2 given"));
}

// An OBJ's material library is never opened, neither the one it names nor the one assimp falls back to: the reader
// serves assimp the checked bytes under one name, with every `mtllib` line made a comment. (The fallback, and a
// `mtllib` naming the served file itself, once read the OBJ as a material file, whose parser wrote through a null
// material: a segfault.)
TEST(MeshFiles, ObjMaterialLibrariesAreNotOpened) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  write_text(dir / "fallback.obj", "mtllib cube.mtl\nnormals, two groups\n" + tri);
  EXPECT_EQ(load_mesh(dir / "fallback.obj").triangle_count(), 1u);
  // A material file that exists beside it, and one that would never end, are not read either.
  write_text(dir / "cube.mtl", "newmtl skin\nKd 1 0 0\n");
  write_text(dir / "beside.obj", "mtllib cube.mtl\nusemtl skin\n" + tri);
  EXPECT_EQ(load_mesh(dir / "beside.obj").triangle_count(), 1u);
  write_text(dir / "zero.obj", "mtllib /dev/zero\n" + tri);
  EXPECT_EQ(load_mesh(dir / "zero.obj").triangle_count(), 1u);
  // Whatever name assimp is served under (its importers pick by extension), a library of that name is not read.
  write_text(dir / "itself.obj", "mtllib mesh.obj\n  mtllib input.obj\nnormals, two groups\n" + tri + "\tmtllib x\n");
  EXPECT_EQ(load_mesh(dir / "itself.obj").triangle_count(), 1u);
}

TEST(MeshFiles, LooseGeometryIsRefusedUnlessAskedToIgnoreIt) {
  TempDir dir;
  EXPECT_THAT(error_of(dir, "mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nl 1 4\np 4\n"),
              HasSubstr("holds 1 point and 1 line elements besides its 1 faces"));
  MeshLoadOptions ignore;
  ignore.ignore_loose = true;
  MeshLoadReport report;
  const TriMesh m = load_mesh(dir / "mixed.obj", ignore, &report);
  EXPECT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(report.ignored_points, 1u);
  EXPECT_EQ(report.ignored_lines, 1u);
  EXPECT_EQ(report.loader, "assimp");
  EXPECT_THAT(error_of(dir, "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n", ignore),
              HasSubstr("empty mesh (no triangles): only 0 points and 2 lines"));
}

TEST(MeshFiles, OffFaceCountInTheHeaderMustMatch) {
  TempDir dir;  // assimp would load the two faces present and only warn that the header said three
  EXPECT_THAT(error_of(dir, "short.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"),
              HasSubstr("cannot parse: the OFF file ends after 2 of its 3 faces"));
  // A face whose corner count is more than the indices on its line: assimp read past the face it built (a segfault
  // found by fuzz_mesh_off).
  EXPECT_THAT(error_of(dir, "long_face.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n255\n3 0 2 3\n"),
              HasSubstr("OFF face 0: '255' does not hold the corner count"));
}

TEST(MeshFiles, Utf16ObjLoads) {
  TempDir dir;
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::string be = "\xFE\xFF";
  for (char c : text) be += std::string{'\0', c};
  write_text(dir / "be.obj", be);
  EXPECT_EQ(load_mesh(dir / "be.obj").triangle_count(), 1u);  // assimp 5.2's own conversion loses the face
  EXPECT_THAT(error_of(dir, "odd.obj", be + "x"), HasSubstr("invalid UTF-16"));
}

TEST(MeshFiles, GroupsShareTheirVerticesAfterLoading) {
  TempDir dir;  // two OBJ groups (two assimp meshes) along a shared edge stay one connected mesh
  write_text(dir / "groups.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng a\nf 1 2 3\ng b\nf 1 3 4\n");
  const TriMesh m = load_mesh(dir / "groups.obj");
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 2u);
}

TEST(MeshFiles, RepeatedTrianglesAreRemovedAndCountedTheOtherSideIsKept) {
  TempDir dir;  // face 3 repeats face 1 rotated (same orientation); face 4 is face 1 reversed (its other side)
  write_text(dir / "repeat.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nf 2 3 1\nf 1 3 2\nf 3 1 2\n");
  MeshLoadReport report;
  const TriMesh m = load_mesh(dir / "repeat.obj", {}, &report);
  EXPECT_EQ(report.duplicate_faces, 2u);
  EXPECT_EQ(report.faces, 3u);
  ASSERT_EQ(m.triangle_count(), 3u);
  // the first copy stays where it was, the reversed face is kept, the order of the others is kept
  EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(m.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(m.triangles[2], glm::uvec3(0, 2, 1));

  TriMesh direct;  // on its own: face_material follows the faces kept
  direct.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  direct.triangles = {{0, 1, 2}, {1, 2, 0}, {0, 2, 1}};
  direct.face_material = {kMaterialSurface, kMaterialInside, kMaterialInside};
  EXPECT_EQ(remove_duplicate_triangles(direct), 1u);
  EXPECT_EQ(direct.face_material, (std::vector<MaterialSlot>{kMaterialSurface, kMaterialInside}));
}

TEST(MeshFiles, PlyFaceListsOfFewerThanThreeCornersNeverReachTheTriangulator) {
  TempDir dir;  // assimp flags such a mesh as polygons; its triangulation step then fails an assertion and aborts
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  EXPECT_THAT(error_of(dir, "zero.ply", head + "3 0 1 2\n0\n"), HasSubstr("zero.ply"));
  EXPECT_THAT(error_of(dir, "line.ply", head + "4 0 1 2 3\n2 0 2\n"), HasSubstr("1 line elements besides its 2 faces"));
  MeshLoadOptions ignore;
  ignore.ignore_loose = true;
  EXPECT_EQ(load_mesh(dir / "line.ply", ignore).triangle_count(), 2u);
}

TEST(MeshFiles, PlyHeaderGrammarIsCheckedBeforeAssimpReadsIt) {
  TempDir dir;
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string props = "property float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  // a free-text line (Blender 2.47 wrote one) is a comment
  write_text(dir / "note.ply", "ply\nformat ascii 1.0\nCreated by an exporter\nelement vertex 3\n" + props + faces +
                                   "end_header\n" + body);
  EXPECT_EQ(load_mesh(dir / "note.ply").triangle_count(), 1u);
  // properties before any element, and 'end_header' only inside another line (a fuzzer's input that crashed assimp)
  EXPECT_THAT(
      error_of(dir, "orphan.ply", "ply\nformat ascii 1.0\nelemeend_header4\n" + props + faces + "end_\n" + body),
      HasSubstr("no end_header line"));
  // end_header must end with a line break, and the header is text: assimp's line reader looped forever on a header of
  // free text holding a control character that ended in a bare end_header (a fuzzer's input).
  EXPECT_THAT(error_of(dir, "bare_end.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header"),
              HasSubstr("no end_header line ended by a line break"));
  EXPECT_THAT(
      error_of(dir, "control.ply", "ply\nformat ascii 1.0\nnote \x1e\n" + props + faces + "end_header\n" + body),
      HasSubstr("PLY header holds a control character (0x1e) at byte 26"));
  EXPECT_THAT(error_of(dir, "early.ply",
                       "ply\nformat ascii 1.0\n" + props + "element vertex 3\n" + faces + "end_header\n" + body),
              HasSubstr("a property before any element"));
  EXPECT_THAT(
      error_of(dir, "short.ply", "ply\nformat ascii 1.0\nelement vertex\n" + props + faces + "end_header\n" + body),
      HasSubstr("expected 'element NAME COUNT'"));
  // assimp ends an element's properties at the first other line, a comment too: its vertices would be read with two
  // properties instead of three (checked with assimp's own `assimp info`: 2 vertices of 3).
  EXPECT_THAT(error_of(dir, "comment.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\ncomment between\nproperty float y\n"
                       "property float z\n" +
                           faces + "end_header\n" + body),
              HasSubstr("a property must follow its element's line or another property"));
  // assimp reads "propErty" as a property; here it would be free text: keywords in another case are refused.
  EXPECT_THAT(error_of(dir, "case.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "propErty float z\n" +
                           faces + "end_header\n" + body),
              HasSubstr("'propErty float z': header keywords are lowercase"));
  // assimp fills one array per element kind: a second face element wrote past the faces of the first (valgrind on
  // `assimp info`: invalid writes). Names are compared as assimp does, without regard to case.
  EXPECT_THAT(error_of(dir, "two_faces.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\n" + props + faces +
                           "element Face 3\nproperty list uchar int vertex_indices\nend_header\n" + body +
                           "3 0 1 2\n3 0 1 2\n3 0 1 2\n"),
              HasSubstr("an element of this name is already declared"));
  EXPECT_THAT(error_of(dir, "two_x.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n" + props + faces +
                           "end_header\n0 0 0 0\n1 1 0 0\n0 0 1 0\n3 0 1 2\n"),
              HasSubstr("a property of this name is already declared in this element"));
  EXPECT_THAT(error_of(dir, "x_list.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar float x\n"
                       "property float y\nproperty float z\n" +
                           faces + "end_header\n2 0 0 0 0\n0 1 0\n0 0 0\n3 0 1 2\n"),
              HasSubstr("a vertex property cannot be a list"));
  // A misspelt vertex element took assimp 11 GB; a file without faces is a point cloud.
  EXPECT_THAT(
      error_of(dir, "verex.ply", "ply\nformat ascii 1.0\nelement verex 3\n" + props + faces + "end_header\n" + body),
      HasSubstr("no element 'vertex' with properties x, y and z"));
  EXPECT_THAT(error_of(dir, "no_z.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n" + faces +
                           "end_header\n0 0\n1 0\n0 1\n3 0 1 2\n"),
              HasSubstr("no element 'vertex' with properties x, y and z"));
  EXPECT_THAT(error_of(dir, "cloud.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\n" + props + "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
              HasSubstr("empty mesh (no triangles)"));
}

// Hostile files: refused by their size or head, before the whole file is read.
TEST(MeshFiles, SparseAndOverclaimingFilesAreRefusedBeforeTheyCostMemory) {
  TempDir dir;
  const long rss_before = max_rss_kb();
  // 2 GB, as the hostile-input probe's: a text OBJ of that size is over the memory budget by its size alone.
  write_sparse(dir / "sparse.obj", "v 0 0 0\n", 2'000'000'000ull);
  EXPECT_THAT(error_of(dir / "sparse.obj"), HasSubstr("memory budget"));
  write_sparse(dir / "sparse.ply", kPlyThreeVertices + "end_header\n", 2'000'000'000ull);
  EXPECT_THAT(error_of(dir / "sparse.ply"), HasSubstr("memory budget"));
  // Small enough for the budget: the NUL bytes of the hole are found in the head.
  write_sparse(dir / "holes.obj", "v 0 0 0\n", 100'000'000ull);
  EXPECT_THAT(error_of(dir / "holes.obj"), HasSubstr("NUL byte"));
  // Headers that claim far more than the file holds.
  EXPECT_THAT(
      error_of(dir, "claims.ply",
               "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
               "property float z\nend_header\n\x01\x02\x03\x04"),
      HasSubstr("exceed what a body of"));
  EXPECT_THAT(error_of(dir, "claims.off", "OFF\n1000000000 1 0\n0 0 0\n"), HasSubstr("more than a file of"));
  EXPECT_THAT(
      error_of(dir, "claims.stl", std::string(80, 'x') + std::string("\xFF\xFF\xFF\x0F", 4) + std::string(50, '\0')),
      HasSubstr("binary STL whose size matches its triangle count"));
  EXPECT_LT(max_rss_kb() - rss_before, 64 * 1024) << "a refused file cost more than 64 MB";
}

TEST(MeshFiles, BinaryPlyBodyMustMatchItsHeader) {
  TempDir dir;
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const int idx[3] = {0, 1, 2};
  ply += '\3';
  ply.append(reinterpret_cast<const char*>(idx), sizeof idx);
  write_text(dir / "exact.ply", ply);
  EXPECT_EQ(load_mesh(dir / "exact.ply").triangle_count(), 1u);
  write_text(dir / "short.ply", ply.substr(0, ply.size() - 13));  // the face is missing
  EXPECT_THAT(error_of(dir / "short.ply"), HasSubstr("truncated"));
  EXPECT_THAT(error_of(dir, "long.ply", ply + std::string(1 << 20, '\0')),
              HasSubstr("longer than its header can describe"));
}

// A list's count sizes assimp's vector before its items are read: a count the rest of the body cannot hold (10⁹ in a
// few bytes, -1 read as 4294967295) is refused by the body walk, in ASCII and binary, and costs no memory.
TEST(MeshFiles, PlyListCountsMustFitTheBody) {
  TempDir dir;
  const long rss_before = max_rss_kb();
  const std::string head =
      kPlyThreeVertices + "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  write_text(dir / "ok.ply", head + "3 0 1 2\n");
  EXPECT_EQ(load_mesh(dir / "ok.ply").triangle_count(), 1u);
  EXPECT_THAT(error_of(dir, "huge.ply", head + "1000000000 0 1 2\n"),
              HasSubstr("face 0: a list of 1000000000 items, more than the 3 values left on its line"));
  EXPECT_THAT(error_of(dir, "digits.ply", head + "99999999999999999999999 0 1 2\n"), HasSubstr("more than"));
  EXPECT_THAT(error_of(dir, "negative.ply", head + "-1 0 1 2\n"), HasSubstr("a count cannot be negative"));
  EXPECT_THAT(error_of(dir, "word.ply", head + "three 0 1 2\n"), HasSubstr("face 0: 'three' is not an integer"));
  EXPECT_THAT(error_of(dir, "cut.ply", head + "3 0 1\n"),
              HasSubstr("a list of 3 items, more than the 2 values left on its line"));
  // assimp reads an element a line: a list count is checked against its own line, not the rest of the file.
  std::string zeros;
  for (int k = 0; k < 2000; ++k) zeros += "0 ";
  EXPECT_THAT(error_of(dir, "lines.ply", head + "1000 0 1 2\n" + zeros + "\n"),
              HasSubstr("more than the 3 values left on its line"));
  EXPECT_THAT(error_of(dir, "short_line.ply", head.substr(0, head.size() - 6) + "0 1\n3 0 1 2\n"),
              HasSubstr("vertex 2: its line holds fewer values"));
  EXPECT_THAT(error_of(dir, "missing.ply", head), HasSubstr("the PLY body ends in face 0 of the 1"));
  EXPECT_THAT(error_of(dir, "float_count.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list double int vertex_indices\n"
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
              HasSubstr("a list's count type must be an integer type"));

  std::string bin =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n";
  const std::string one("\x3F\x80\0\0", 4), zero(4, '\0');  // 1.0f and 0.0f, big-endian
  bin += zero + zero + zero + one + zero + zero + zero + one + zero;
  EXPECT_THAT(error_of(dir, "bin_huge.ply", bin + std::string("\x3F\xFF\xFF\xFF", 4) + std::string(12, '\0')),
              HasSubstr("face 0: a list of 1073741823 items, more than the 3 items"));
  EXPECT_THAT(error_of(dir, "bin_negative.ply", bin + std::string("\xFF\xFF\xFF\xFF", 4) + std::string(12, '\0')),
              HasSubstr("a list of -1 items (a count cannot be negative)"));
  write_text(dir / "bin_ok.ply", bin + std::string("\0\0\0\3\0\0\0\0\0\0\0\1\0\0\0\2", 16));
  EXPECT_EQ(load_mesh(dir / "bin_ok.ply").triangle_count(), 1u);
  EXPECT_LT(max_rss_kb() - rss_before, 64 * 1024) << "a refused file cost more than 64 MB";
}

// assimp splits an ASCII line into values where a number stops parsing, not at spaces: `5-111` under a uchar is 5,
// then -111 as the next value, which as a signed list count asked for 34 GB (a fuzzer's input). Every value must be a
// whole number of its property's type, and assimp reads the body as written back by the walk (one element a line,
// comments, blank lines and what follows the values dropped), so the two read the same values.
TEST(MeshFiles, PlyValuesAreWholeNumbersOfTheirType) {
  TempDir dir;
  const long rss_before = max_rss_kb();
  const std::string head =
      kPlyThreeVertices + "element face 1\nproperty uchar flags\nproperty list int int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_THAT(error_of(dir, "glued.ply", head + vertices + "5-111 3 0 1 2\n"),
              HasSubstr("face 0: '5-111' is not an unsigned integer"));
  EXPECT_THAT(error_of(dir, "signed_uchar.ply", head + vertices + "-5 3 0 1 2\n"),
              HasSubstr("'-5' is not an unsigned integer"));
  EXPECT_THAT(error_of(dir, "real_index.ply", head + vertices + "0 3 0 1.0 2\n"), HasSubstr("'1.0' is not an integer"));
  EXPECT_THAT(error_of(dir, "comma.ply", head + "0 0 0\n1,5 0 0\n0 1 0\n0 3 0 1 2\n"),
              HasSubstr("vertex 1: '1,5' is not a number"));
  EXPECT_THAT(error_of(dir, "form_feed.ply", head + "0 0 0\n1\f-7 0 0\n0 1 0\n0 3 0 1 2\n"),
              HasSubstr("is not a number"));
  // Numbers as writers print them, comment and blank lines between elements, and text after an element's values.
  write_text(dir / "written.ply", head + "comment between\n\n  -0.5e+0 .25 1.\n+1E2 0 -3.5e-1\n\t0 1 0 tail\n" +
                                      "   \n0 3 +0 1 2 extra words\n");
  const TriMesh m = load_mesh(dir / "written.ply");
  ASSERT_EQ(m.triangle_count(), 1u);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const glm::dvec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  EXPECT_NEAR(lo.x, -0.5, 1e-6);
  EXPECT_NEAR(hi.x, 100.0, 1e-4);
  EXPECT_NEAR(hi.y, 1.0, 1e-6);
  EXPECT_NEAR(lo.z, -0.35, 1e-6);
  EXPECT_NEAR(hi.z, 1.0, 1e-6);
  EXPECT_LT(max_rss_kb() - rss_before, 64 * 1024) << "a refused file cost more than 64 MB";
}

// assimp does not skip an element it has no use for by its declared size: with one between the vertices and the faces
// it read the faces from that element's data (a negative corner count as 4294946478 corners: 34 GB; CI's fuzzer).
// Such elements are checked with the rest of the body, then left out of what assimp reads.
TEST(MeshFiles, PlyElementsOtherThanTheMeshAreCheckedAndLeftOut) {
  TempDir dir;
  auto head = [](const std::string& format) {
    return "ply\nformat " + format + " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" +
           "element junk 2\nproperty double q\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  };
  write_text(dir / "ascii.ply", head("ascii") + "0 0 0\n1 0 0\n0 1 0\n7\n-3\n3 0 1 2\n");
  const TriMesh a = load_mesh(dir / "ascii.ply");
  EXPECT_EQ(a.vertex_count(), 3u);
  EXPECT_EQ(a.triangle_count(), 1u);
  // Big-endian floats 0 and 1, doubles 7 and -3 (the extra element's data: 16 bytes a face reader would misread).
  const std::string zero(4, '\0'), one("\x3F\x80\0\0", 4);
  std::string body = zero + zero + zero + one + zero + zero + zero + one + zero;
  body += std::string("\x40\x1C\0\0\0\0\0\0", 8) + std::string("\xC0\x08\0\0\0\0\0\0", 8);
  body += std::string("\x03\0\0\0\0\0\0\0\x01\0\0\0\x02", 13);
  write_text(dir / "binary.ply", head("binary_big_endian") + body);
  const TriMesh b = load_mesh(dir / "binary.ply");
  EXPECT_EQ(b.vertex_count(), 3u);
  EXPECT_EQ(b.triangle_count(), 1u);
  // The extra element is still walked: a value of the wrong type in it refuses the file.
  write_text(dir / "bad_extra.ply", head("ascii") + "0 0 0\n1 0 0\n0 1 0\n7\nseven\n3 0 1 2\n");
  EXPECT_THAT(error_of(dir / "bad_extra.ply"), HasSubstr("junk 1: 'seven' is not a number"));
}

TEST(MeshFiles, PathsThatAreNotRegularFilesSayWhatTheyAre) {
  TempDir dir;
  std::filesystem::create_directory(dir / "folder.obj");
  EXPECT_THAT(error_of(dir / "folder.obj"), HasSubstr("is a directory"));
  std::filesystem::create_symlink("/dev/zero", dir / "zero.ply");
  EXPECT_THAT(error_of(dir / "zero.ply"), HasSubstr("is a character device, not a regular file"));
  ASSERT_EQ(::mkfifo((dir / "pipe.off").c_str(), 0600), 0);
  EXPECT_THAT(error_of(dir / "pipe.off"), HasSubstr("is a FIFO"));
  EXPECT_THAT(error_of(dir / "missing.stl"), HasSubstr("file not found"));
}

}  // namespace
}  // namespace trispline::core
