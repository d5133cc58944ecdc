// The DFFD scenes as users replay them (tests/logs/dffd_split_cylinder.jsonl, dffd_walk_bars.jsonl; seed Fig. 6.7,
// 6.10, 6.11): the real bunny cut by a cylinder left open has boundary loops only on the discontinuity, stitched and
// capped it is a closed 2-manifold; walking through the bars it is split (and capped) where a bar passes, whole
// before and after, and the same frame evaluates to the same mesh bit for bit.
#include <gtest/gtest.h>

#include <filesystem>

#include "editor/commands/history.h"
#include "editor/replay/replay.h"
#include "tests/editor/session_test_util.h"
#include "tests/mesh_topology.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

TEST(DffdLogs, CylinderCutOpenStitchedCapped) {
  core::Scene scene;
  ASSERT_TRUE(test::replay_log(scene, "dffd_split_cylinder.jsonl"));
  const core::SceneObject& open = *scene.find("open");
  ASSERT_TRUE(open.dffd);
  const core::test::Topology t_open = core::test::topology(*open.world_mesh);
  EXPECT_TRUE(is_manifold(t_open));
  EXPECT_GT(t_open.boundary_edges, 100u);  // the opening's rims
  // Every boundary vertex is a cut vertex at u0 ∓ eps.
  const core::TriMesh rest = open.world_rest_mesh();
  const core::MeshSplit split = core::dffd_split(*open.dffd, rest, open.offset_at(0.0));
  const double u0 = open.dffd->discontinuities.at(0).u0;
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& f : split.mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  for (const auto& [e, n] : edges)
    if (n == 1) {
      for (unsigned v : {e.first, e.second}) ASSERT_NEAR(std::abs(split.params[v].x - u0), open.dffd->eps, 1e-12);
    }
  for (const char* name : {"stitched", "capped"}) {
    const core::SceneObject& o = *scene.find(name);
    const core::test::Topology t = core::test::topology(*o.world_mesh);
    EXPECT_EQ(t.openmesh_rejected, 0u) << name;
    EXPECT_EQ(t.boundary_edges, 0u) << name;
    EXPECT_EQ(t.nonmanifold_edges, 0u) << name;
    EXPECT_EQ(t.duplicate_faces, 0u) << name;
    EXPECT_TRUE(o.world_mesh->has_inside_faces()) << name;
  }
}

TEST(DffdLogs, WalkThroughBarsSplitsOnlyWhereABarPasses) {
  core::Scene scene;
  ASSERT_TRUE(test::replay_log(scene, "dffd_walk_bars.jsonl"));
  const core::SceneObject& walker = *scene.find("walker");
  ASSERT_TRUE(walker.dffd_animated());
  const std::size_t nv = walker.rest_mesh->vertex_count();
  int split_frames = 0;
  for (int frame : {1, 30, 45, 60, 75, 90, 120}) {
    const core::Scene still = core::scene_at_time(scene, scene.timeline.time_of_frame(frame));
    const core::TriMesh& m = *still.find("walker")->world_mesh;
    const core::test::Topology t = core::test::topology(m);
    EXPECT_EQ(t.boundary_edges, 0u) << "frame " << frame;
    EXPECT_EQ(t.nonmanifold_edges, 0u) << "frame " << frame;
    EXPECT_EQ(t.openmesh_rejected, 0u) << "frame " << frame;
    if (m.vertex_count() > nv) ++split_frames;
    if (frame == 1 || frame == 120) {
      EXPECT_EQ(m.vertex_count(), nv) << "whole before and after the bars";
    }
  }
  EXPECT_GE(split_frames, 3);
  const core::Scene a = core::scene_at_time(scene, 2.5), b = core::scene_at_time(scene, 2.5);
  EXPECT_EQ(a.find("walker")->world_mesh->positions, b.find("walker")->world_mesh->positions);
}

}  // namespace
