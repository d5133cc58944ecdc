// mesh.subdivide (core/commands/mesh_subdivide.h): the command around core::loop_subdivide (its own tests are in
// tests/core/mesh/test_loop_subdivision.cpp) — the Venus bust, undo bit for bit, the triangle budget, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "core/commands/camera_set.h"
#include "core/commands/mesh_subdivide.h"
#include "core/commands/place_sketch.h"
#include "core/commands/scene_load.h"
#include "core/commands/scene_primitive.h"
#include "core/scene/primitives.h"
#include "tests/mesh_topology.h"

namespace trispline::core {
namespace mesh_subdivide_test {

using nlohmann::json;

void run(Scene& s, const char* line) { ScenePrimitiveCommand::parse(json::parse(line), CommandContext{})->redo(s); }

TEST(MeshSubdivide, CommandUndoRestoresBitForBit) {
  Scene s;
  run(s, R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","translate":[1,0,0],"scale":0.5})");
  const Scene before = s;
  const SceneObject& b0 = *before.find("ball");
  auto cmd = MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"ball","levels":2})"), {});
  EXPECT_EQ(cmd->to_json(), json::parse(R"({"cmd":"mesh.subdivide","object":"ball","levels":2,"scheme":"loop"})"));
  cmd->redo(s);
  const SceneObject& b1 = *s.find("ball");
  EXPECT_EQ(b1.rest_mesh->triangle_count(), b0.rest_mesh->triangle_count() * 16);
  EXPECT_EQ(b1.world_mesh->vertex_count(), b1.rest_mesh->vertex_count());
  test::expect_closed_manifold(*b1.rest_mesh);
  EXPECT_EQ(cmd->stats().at("triangles_after").get<std::size_t>(), b1.rest_mesh->triangle_count());
  // World mesh = transform of the subdivided rest mesh (scale 0.5, x + 1).
  EXPECT_LT(glm::length(b1.world_mesh->positions[7] - (0.5 * b1.rest_mesh->positions[7] + glm::dvec3(1, 0, 0))), 1e-12);
  cmd->undo(s);
  const SceneObject& b2 = *s.find("ball");
  EXPECT_EQ(b2.rest_mesh, b0.rest_mesh);
  ASSERT_EQ(b2.world_mesh->positions.size(), b0.world_mesh->positions.size());
  EXPECT_EQ(0, std::memcmp(b2.world_mesh->positions.data(), b0.world_mesh->positions.data(),
                           b0.world_mesh->positions.size() * sizeof(glm::dvec3)));
  EXPECT_EQ(b2.world_mesh->triangles, b0.world_mesh->triangles);
  // Redo gives the same mesh again; a second command on the same input gives the same bytes (determinism).
  cmd->redo(s);
  Scene other = before;
  MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"ball","levels":2})"), {})->redo(other);
  const TriMesh& x = *s.find("ball")->rest_mesh;
  const TriMesh& y = *other.find("ball")->rest_mesh;
  ASSERT_EQ(x.positions.size(), y.positions.size());
  EXPECT_EQ(0, std::memcmp(x.positions.data(), y.positions.data(), x.positions.size() * sizeof(glm::dvec3)));
  EXPECT_EQ(x.triangles, y.triangles);
}

TEST(MeshSubdivide, VenusBust) {
  Scene s;
  const std::string path = std::string(TRISPLINE_SOURCE_DIR) + "/assets/data/venus.obj";
  SceneLoadCommand::parse(json{{"cmd", "scene.load"}, {"path", path}, {"name", "venus"}}, {})->redo(s);
  const TriMesh rest = *s.find("venus")->rest_mesh;
  ASSERT_GT(rest.triangle_count(), 1000u);
  MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"venus","levels":2})"), {})->redo(s);
  const TriMesh& sub = *s.find("venus")->rest_mesh;
  EXPECT_EQ(sub.triangle_count(), rest.triangle_count() * 16);
  // Edge manifoldness is kept: no edge gains faces; boundary edges (if any) double per level.
  const test::Topology t0 = test::topology(rest), t1 = test::topology(sub);
  EXPECT_EQ(t1.nonmanifold_edges, t0.nonmanifold_edges * 4);
  EXPECT_EQ(t1.boundary_edges, t0.boundary_edges * 4);
  EXPECT_EQ(t1.repeated_halfedges, t0.repeated_halfedges * 4);
  // The shape stays: same bounding box to 5 % of its diagonal.
  Aabb b0, b1;
  for (const glm::dvec3& p : rest.positions) b0.extend(p);
  for (const glm::dvec3& p : sub.positions) b1.extend(p);
  EXPECT_LT(glm::length(b1.lo - b0.lo) + glm::length(b1.hi - b0.hi), 0.05 * b0.diagonal());
}

// The result's size is checked before OpenSubdiv runs: the bunny's 69,666 triangles at 4 levels would be 17.8 M
// (3.6 GB at peak in a replay), over the 8 M budget; 3 levels (4.5 M) are within it.
TEST(MeshSubdivide, AResultOverTheTriangleBudgetIsRefusedBeforeSubdividing) {
  Scene s;
  const std::string path = std::string(TRISPLINE_SOURCE_DIR) + "/assets/data/bunny.obj";
  SceneLoadCommand::parse(json{{"cmd", "scene.load"}, {"path", path}, {"name", "bunny"}}, {})->redo(s);
  const auto rest = s.find("bunny")->rest_mesh;
  ASSERT_EQ(rest->triangle_count(), 69666u);
  try {
    MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"bunny","levels":4})"), {})->redo(s);
    ADD_FAILURE() << "4 levels of the bunny were accepted";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.field(), "levels");
    EXPECT_NE(std::string(e.what()).find("17834496 triangles (at most 8000000)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.find("bunny")->rest_mesh, rest);
}

TEST(MeshSubdivide, BadInputNamesTheFieldAndChangesNothing) {
  Scene s;
  run(s, R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":3})");
  run(s, R"({"cmd":"scene.primitive","kind":"sphere","name":"ball","scale":[0.5,0.2,0.2]})");
  CameraSetCommand::parse(json::parse(R"({"cmd":"camera.set","eye":[0,3,3],"target":[0,0,0],"up":[0,1,0],
                                          "fov_deg":45,"viewport":[800,600]})"),
                          {})
      ->redo(s);
  PlaceSketchCommand::parse(json::parse(R"({"cmd":"place.sketch","stroke":[[250,360],[400,350],[550,360]],
      "object":"ball","width":0.3,"height":0.3,"samples":[24,8],"order":[4,4,3],"controls":[8,4,3]})"),
                            {})
      ->redo(s);
  const Scene before = s;
  auto expect_field = [&](const char* line, const char* field) {
    try {
      MeshSubdivideCommand::parse(json::parse(line), {})->redo(s);
      ADD_FAILURE() << line << " was accepted";
    } catch (const CommandError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
    for (const char* id : {"ground", "ball"}) {
      EXPECT_EQ(s.find(id)->rest_mesh, before.find(id)->rest_mesh);
      EXPECT_EQ(s.find(id)->world_mesh, before.find(id)->world_mesh);
    }
  };
  expect_field(R"({"cmd":"mesh.subdivide","object":"ground","levels":0})", "levels");
  expect_field(R"({"cmd":"mesh.subdivide","object":"ground","levels":5})", "levels");
  expect_field(R"({"cmd":"mesh.subdivide","object":"ground","levels":2,"scheme":"catmark"})", "scheme");
  expect_field(R"({"cmd":"mesh.subdivide","object":"nobody"})", "object");
  expect_field(R"({"cmd":"mesh.subdivide","object":"ball"})", "object");  // has an FFD lattice
  try {
    MeshSubdivideCommand::parse(json::parse(R"({"cmd":"mesh.subdivide","object":"ball"})"), {})->redo(s);
  } catch (const CommandError& e) {
    EXPECT_NE(std::string(e.what()).find("subdivide before deforming"), std::string::npos) << e.what();
  }
}

}  // namespace mesh_subdivide_test
}  // namespace trispline::core
