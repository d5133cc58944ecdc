// Animation pieces (core/mesh/gltf_anim_io.h): a recording split by frames, each piece starting with the range's
// first frame, joins into the bytes one builder over the whole range writes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/mesh/gltf_anim_io.h"
#include "core/mesh/material_image.h"
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

// A textured object: a 4×2 PNG base colour texture, a mask material, and an image that could not be read.
std::shared_ptr<const MaterialSet> textured_set() {
  auto set = std::make_shared<MaterialSet>();
  std::vector<std::uint8_t> rgba;
  for (int i = 0; i < 4 * 2; ++i) rgba.insert(rgba.end(), {std::uint8_t(30 * i), 200, std::uint8_t(255 - 20 * i), 255});
  set->images.push_back(std::make_shared<const MaterialImage>(
      decode_material_image(encode_png_rgba8(4, 2, rgba), "", "bark", "bark.png")));
  MaterialImage missing;
  missing.uri = "leaves.png";
  missing.error = "file not found";
  set->images.push_back(std::make_shared<const MaterialImage>(missing));
  Material bark;
  bark.name = "bark";
  bark.base_color = {0.9, 0.7, 0.5, 1.0};
  bark.base_color_texture.image = 0;
  bark.base_color_texture.sampler.wrap_s = TextureWrap::ClampToEdge;
  bark.roughness = 0.4;
  Material leaves;
  leaves.name = "leaves";
  leaves.base_color_texture.image = 1;
  leaves.alpha_mode = AlphaMode::Mask;
  leaves.alpha_cutoff = 0.3;
  leaves.double_sided = true;
  set->materials = {bark, leaves};
  return set;
}

TEST_F(AnimationPieces, JoinedPiecesKeepMaterialsAndImagesByteForByte) {
  const auto set = textured_set();
  const auto textured = [&](int f) {
    Frame fr = frame(f);
    fr.moving.face_material.assign(fr.moving.triangles.size(), 0);
    for (std::size_t t = 0; t < fr.moving.face_material.size(); t += 3) fr.moving.face_material[t] = 1;
    return fr;
  };
  const auto nodes = [&](const Frame& fr) {
    std::vector<GltfNode> n = fr.nodes();
    n[0].materials = set;
    return n;
  };
  MorphAnimationBuilder whole_range(24.0, 1);
  for (int f = 1; f <= 6; ++f) whole_range.add_frame(nodes(textured(f)));
  whole_range.write_glb(dir / "whole.glb");
  const auto make_piece = [&](int a, int b) {
    MorphAnimationBuilder p(24.0, 1);
    if (a > 1) p.add_frame(nodes(textured(1)));
    for (int f = a; f <= b; ++f) p.add_frame(nodes(textured(f)));
    const fs::path path = dir / ("piece_" + std::to_string(a) + ".piece");
    p.write_piece(path);
    return MorphAnimationBuilder::read_piece(path);
  };
  MorphAnimationBuilder joined = make_piece(1, 3);
  ASSERT_TRUE(joined.append_piece(make_piece(4, 6)));
  joined.write_glb(dir / "joined.glb");
  const std::string a = bytes(dir / "whole.glb"), b = bytes(dir / "joined.glb");
  EXPECT_NE(a.find("\"bark\""), std::string::npos) << "the recording has no bark material";
  EXPECT_NE(a.find("image/png"), std::string::npos) << "the recording embeds no image";
  EXPECT_TRUE(a == b) << "joined animation.glb differs from one recording's (" << a.size() << " vs " << b.size()
                      << " bytes)";
}

TEST_F(AnimationPieces, HugeCountsInAPieceAreRefusedBeforeAllocating) {
  whole(1, 3, false).write_piece(dir / "p.piece");
  std::string full = bytes(dir / "p.piece");
  // The first object's name length (u32 after magic, fps, first, frames, objects), then its colour and the material
  // flag; the first segment's header and the base mesh's positions count follow.
  const std::size_t name_at = 8 + 8 + 4 + 4 + 4;
  const std::size_t positions_at = name_at + 4 + std::string("moving").size() + 12 + 1 + 4 + 4 + 4 + 1;
  std::string bad = full;
  const std::uint64_t huge = std::uint64_t(1) << 40;
  std::memcpy(bad.data() + positions_at, &huge, sizeof huge);
  std::ofstream(dir / "huge.piece", std::ios::binary) << bad;
  try {
    MorphAnimationBuilder::read_piece(dir / "huge.piece");
    FAIL() << "a piece declaring 2^40 positions was read";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("bytes left"), std::string::npos) << e.what();
  }
}

TEST_F(AnimationPieces, FrameCountsBeyondTheTimelineAreRefused) {
  // A piece without objects costs nothing per frame, so only the timeline bounds its frames (the key times alone
  // of 700 M frames would take 2.8 GB).
  MorphAnimationBuilder(24.0, 0).write_piece(dir / "empty.piece");  // no frames: refused on reading
  std::string full = bytes(dir / "empty.piece");
  const std::size_t first_at = 8 + 8, frames_at = first_at + 4;
  auto with = [&](std::int32_t first, std::int32_t frames) {
    std::string s = full;
    std::memcpy(s.data() + first_at, &first, 4);
    std::memcpy(s.data() + frames_at, &frames, 4);
    std::ofstream(dir / "x.piece", std::ios::binary | std::ios::trunc) << s;
    return dir / "x.piece";
  };
  EXPECT_EQ(MorphAnimationBuilder::read_piece(with(0, kMaxRecordedFrames)).frame_count(), kMaxRecordedFrames);
  EXPECT_THROW(MorphAnimationBuilder::read_piece(with(0, 700'000'000)), MeshIoError);
  EXPECT_THROW(MorphAnimationBuilder::read_piece(with(10, kMaxRecordedFrames - 9)), MeshIoError);
  EXPECT_THROW(MorphAnimationBuilder::read_piece(with(-5, 3)), MeshIoError);
  EXPECT_THROW(MorphAnimationBuilder::read_piece(with(kMaxRecordedFrames, 1)), MeshIoError);
}

TEST_F(AnimationPieces, AnAnimationOverTheGlbBudgetIsRefusedBeforeBuilding) {
  // 20 K frames of one moving quad: the weights alone are 20 K × 20 K floats (1.6 GB).
  TriMesh quad = strip(1, 0.0);
  MorphAnimationBuilder b(24.0, 0);
  for (int f = 0; f < 20000; ++f) {
    quad.positions[0].x = f * 1e-3;
    b.add_frame({GltfNode{"quad", &quad}});
  }
  EXPECT_GT(b.glb_data_bytes(), kMaxAnimationGlbBytes);
  try {
    b.write_glb(dir / "big.glb");
    FAIL() << "a 1.6 GB animation was written";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("MiB"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "big.glb"));
  EXPECT_LT(whole(1, 5, false).glb_data_bytes(), kMaxAnimationGlbBytes);
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
