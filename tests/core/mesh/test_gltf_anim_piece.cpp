// Animation pieces (core/mesh/gltf_anim_io.h): a recording split by frames, each piece starting with the range's
// first frame, joins into the bytes one builder over the whole range writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/mesh/gltf_anim_io.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

namespace fs = std::filesystem;

// A quad strip of `n` quads whose vertices move with frame `f` by an irrational amount (deltas are not exact floats),
// one object that never moves, one without a mesh.
struct Frame {
  TriMesh moving, still;
  std::vector<GltfNode> nodes() const {
    return {GltfNode{"moving", &moving, glm::vec3(0.9f, 0.5f, 0.2f)}, GltfNode{"still", &still},
            GltfNode{"empty", nullptr}};
  }
};

TriMesh strip(int n, double t, bool extra_triangle = false) {
  TriMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2; ++j) {
      m.positions.push_back({i + 0.1 * std::sin(t + i), j + std::sqrt(2.0) * t, 0.3 * std::cos(t * 1.7 + j)});
      m.normals.push_back(glm::normalize(glm::dvec3(std::sin(t), 1, std::cos(t))));
      m.uvs.push_back({double(i) / n, double(j)});
    }
  for (int i = 0; i < n; ++i) {
    const unsigned a = 2 * i;
    m.triangles.push_back({a, a + 2, a + 1});
    m.triangles.push_back({a + 1, a + 2, a + 3});
  }
  if (extra_triangle) m.triangles.push_back({0, 3, 1});
  return m;
}

Frame frame(int f, bool topology_change = false) {
  Frame fr;
  fr.moving = strip(6, f * 0.37, topology_change && f >= 7);
  fr.still = strip(2, 0.0);
  return fr;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class AnimationPieces : public ::testing::Test {
 protected:
  // A folder per test: ctest runs the tests of this file in parallel processes.
  fs::path dir;
  void SetUp() override {
    dir = fs::path(TRISPLINE_BINARY_DIR) / "test_out" / "gltf_anim_piece" /
          ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  // One builder over [first, last], or the pieces [first, a-1], [a, b-1], [b, last] joined.
  static MorphAnimationBuilder whole(int first, int last, bool topo) {
    MorphAnimationBuilder b(24.0, first);
    for (int f = first; f <= last; ++f) b.add_frame(frame(f, topo).nodes());
    return b;
  }
  MorphAnimationBuilder piece(int base, int a, int b, bool topo) {
    MorphAnimationBuilder p(24.0, base);
    if (a > base) p.add_frame(frame(base, topo).nodes());
    for (int f = a; f <= b; ++f) p.add_frame(frame(f, topo).nodes());
    const fs::path path = dir / ("piece_" + std::to_string(a) + ".piece");
    p.write_piece(path);
    return MorphAnimationBuilder::read_piece(path);  // through the file, as the farm does
  }
};

TEST_F(AnimationPieces, JoinedPiecesWriteTheSameGlbAsOneRecording) {
  whole(3, 14, false).write_glb(dir / "whole.glb");
  MorphAnimationBuilder joined = piece(3, 3, 6, false);
  ASSERT_TRUE(joined.append_piece(piece(3, 7, 10, false)));
  ASSERT_TRUE(joined.append_piece(piece(3, 11, 14, false)));
  EXPECT_EQ(joined.frame_count(), 12);
  joined.write_glb(dir / "joined.glb");
  const std::string a = bytes(dir / "whole.glb"), b = bytes(dir / "joined.glb");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "joined animation.glb differs from one recording's (" << a.size() << " vs " << b.size()
                      << " bytes)";
}

TEST_F(AnimationPieces, PieceRoundTripsLosslessly) {
  const MorphAnimationBuilder b = whole(1, 5, false);
  b.write_piece(dir / "p.piece");
  b.write_glb(dir / "a.glb");
  MorphAnimationBuilder::read_piece(dir / "p.piece").write_glb(dir / "b.glb");
  EXPECT_EQ(bytes(dir / "a.glb"), bytes(dir / "b.glb"));
}

TEST_F(AnimationPieces, TopologyChangeIsNotJoinedAndLeavesTheBuilderUnchanged) {
  MorphAnimationBuilder joined = piece(1, 1, 4, true);
  ASSERT_TRUE(joined.append_piece(piece(1, 5, 6, true)));
  EXPECT_FALSE(joined.append_piece(piece(1, 7, 9, true)));  // frame 7 on has one more triangle
  EXPECT_EQ(joined.frame_count(), 6);
  joined.write_glb(dir / "joined.glb");
  whole(1, 6, true).write_glb(dir / "whole.glb");
  EXPECT_EQ(bytes(dir / "joined.glb"), bytes(dir / "whole.glb"));
}

TEST_F(AnimationPieces, PieceWithAnotherBaseIsRefused) {
  MorphAnimationBuilder joined = piece(1, 1, 4, false);
  EXPECT_FALSE(joined.append_piece(piece(2, 5, 6, false)));  // based on frame 2, not 1
  EXPECT_EQ(joined.frame_count(), 4);
}

TEST_F(AnimationPieces, BadPieceFilesThrow) {
  EXPECT_THROW(MorphAnimationBuilder::read_piece(dir / "missing.piece"), MeshIoError);
  std::ofstream(dir / "junk.piece", std::ios::binary) << "not a piece at all";
  EXPECT_THROW(MorphAnimationBuilder::read_piece(dir / "junk.piece"), MeshIoError);
  whole(1, 3, false).write_piece(dir / "p.piece");
  const std::string full = bytes(dir / "p.piece");
  std::ofstream(dir / "cut.piece", std::ios::binary) << full.substr(0, full.size() / 2);
  EXPECT_THROW(MorphAnimationBuilder::read_piece(dir / "cut.piece"), MeshIoError);
}

}  // namespace
}  // namespace trispline::core
