// mesh.subdivide (core/commands/mesh_subdivide.h): uniform Loop subdivision through OpenSubdiv — counts, closed
// 2-manifolds stay so, uvs linear, face materials inherited, the Venus bust, undo bit for bit, bad input refused.
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

namespace trispline::core {
namespace {

using nlohmann::json;

// Undirected edge → number of faces; directed edges used twice (orientation broken).
struct Edges {
  std::map<std::pair<unsigned, unsigned>, int> count;
  std::size_t repeated_directed = 0;
};
Edges edges_of(const TriMesh& m) {
  Edges e;
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (const glm::uvec3& f : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const unsigned a = f[k], b = f[(k + 1) % 3];
      ++e.count[{std::min(a, b), std::max(a, b)}];
      if (++directed[{a, b}] == 2) ++e.repeated_directed;
    }
  return e;
}

void expect_closed_manifold(const TriMesh& m) {
  const Edges e = edges_of(m);
  std::size_t bad = 0;
  for (const auto& [edge, n] : e.count) bad += (n != 2);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(e.repeated_directed, 0u);
}

TEST(MeshSubdivide, LoopCountsAndClosedSphere) {
  const TriMesh sphere = make_sphere(24, 12);
  expect_closed_manifold(sphere);
  const std::size_t V = sphere.vertex_count(), F = sphere.triangle_count(), E = edges_of(sphere).count.size();
  ASSERT_EQ(V - E + F, 2u);  // genus 0
  for (int levels = 1; levels <= 3; ++levels) {
    const TriMesh s = loop_subdivide(sphere, levels);
    EXPECT_EQ(s.triangle_count(), F << (2 * levels));
    expect_closed_manifold(s);
    const std::size_t e = edges_of(s).count.size();
    EXPECT_EQ(s.vertex_count() - e + s.triangle_count(), 2u);  // still a sphere
    if (levels == 1) {
      EXPECT_EQ(s.vertex_count(), V + E);  // one new vertex per edge
    }
    EXPECT_EQ(s.normals.size(), s.vertex_count());
    // Loop shrinks a convex sphere slightly inwards and smooths it: every vertex within [0.97, 1].
    for (const glm::dvec3& p : s.positions) {
      EXPECT_LE(glm::length(p), 1.0 + 1e-12);
      EXPECT_GT(glm::length(p), 0.97);
    }
    // Vertex children come first, in the input order: near their parents.
    for (std::size_t v = 0; v < V; ++v) EXPECT_LT(glm::length(s.positions[v] - sphere.positions[v]), 0.03) << v;
  }
  EXPECT_EQ(loop_subdivide(sphere, 0).positions, sphere.positions);
  EXPECT_THROW(loop_subdivide(sphere, -1), std::invalid_argument);
}

TEST(MeshSubdivide, UvsLinearAndMaterialsInherited) {
  // The plane: uv is an affine function of (x, z); Loop's masks reproduce affine functions on the regular grid and
  // along straight boundaries, and uvs are interpolated linearly, so it stays so — except near the two grid corners
  // with two faces (smooth boundary vertices, not Sdc corners: the boundary rule rounds them off).
  TriMesh plane = make_plane(8);
  ASSERT_EQ(plane.uvs.size(), plane.vertex_count());
  plane.face_material.assign(plane.triangle_count(), kMaterialSurface);
  for (std::size_t f = 0; f < plane.triangle_count(); f += 3) plane.face_material[f] = kMaterialInside;
  const std::size_t inside = std::count(plane.face_material.begin(), plane.face_material.end(), kMaterialInside);
  for (int levels = 1; levels <= 2; ++levels) {
    const TriMesh s = loop_subdivide(plane, levels);
    ASSERT_EQ(s.uvs.size(), s.vertex_count());
    // The affine map (x, z) → uv, fitted on the first triangle and checked on every input vertex.
    const glm::uvec3 q = plane.triangles[0];
    const glm::dvec3 pa = plane.positions[q[0]], pb = plane.positions[q[1]], pc = plane.positions[q[2]];
    const glm::dmat2 P(pb.x - pa.x, pb.z - pa.z, pc.x - pa.x, pc.z - pa.z);
    const glm::dmat2 T(plane.uvs[q[1]] - plane.uvs[q[0]], plane.uvs[q[2]] - plane.uvs[q[0]]);
    const glm::dmat2 A = T * glm::inverse(P);
    auto expected = [&](const glm::dvec3& p) { return plane.uvs[q[0]] + A * glm::dvec2(p.x - pa.x, p.z - pa.z); };
    for (std::size_t v = 0; v < plane.vertex_count(); ++v) ASSERT_LT(glm::length(plane.uvs[v] - expected(plane.positions[v])), 1e-12);
    for (std::size_t v = 0; v < s.vertex_count(); ++v) {
      const glm::dvec3 p = s.positions[v];
      if (std::abs(p.x) < 0.5 || std::abs(p.z) < 0.5) {
        EXPECT_LT(glm::length(s.uvs[v] - expected(p)), 1e-12) << v;
      }
      EXPECT_NEAR(s.positions[v].y, 0.0, 1e-15);
    }
    // Materials: the 4^levels children of a face keep its slot.
    ASSERT_EQ(s.face_material.size(), s.triangle_count());
    EXPECT_EQ(std::size_t(std::count(s.face_material.begin(), s.face_material.end(), kMaterialInside)),
              inside << (2 * levels));
    // Level 1: each child's slot is that of the input triangle containing its centroid (the plane stays planar).
    if (levels == 1) {
      for (std::size_t f = 0; f < s.triangle_count(); ++f) {
        const glm::uvec3& t = s.triangles[f];
        const glm::dvec3 c = (s.positions[t[0]] + s.positions[t[1]] + s.positions[t[2]]) / 3.0;
        std::size_t parent = plane.triangle_count();
        for (std::size_t g = 0; g < plane.triangle_count() && parent == plane.triangle_count(); ++g) {
          const glm::uvec3& q = plane.triangles[g];
          const glm::dvec3 a = plane.positions[q[0]], b = plane.positions[q[1]], e = plane.positions[q[2]];
          auto side = [&](glm::dvec3 u, glm::dvec3 w) { return (w.x - u.x) * (c.z - u.z) - (w.z - u.z) * (c.x - u.x); };
          const double s1 = side(a, b), s2 = side(b, e), s3 = side(e, a);
          if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) parent = g;
        }
        ASSERT_LT(parent, plane.triangle_count());
        EXPECT_EQ(s.face_material[f], plane.face_material[parent]) << f;
      }
    }
  }
  // Level 1: the original vertices keep their uvs exactly, every new vertex has the midpoint uv of an input edge
  // (linear interpolation), one per edge.
  const TriMesh s1 = loop_subdivide(plane, 1);
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) EXPECT_EQ(s1.uvs[v], plane.uvs[v]);
  std::map<std::pair<double, double>, int> midpoints;
  for (const auto& [e, n] : edges_of(plane).count) {
    const glm::dvec2 m = 0.5 * (plane.uvs[e.first] + plane.uvs[e.second]);
    ++midpoints[{m.x, m.y}];
  }
  EXPECT_EQ(s1.vertex_count() - plane.vertex_count(), edges_of(plane).count.size());
  for (std::size_t v = plane.vertex_count(); v < s1.vertex_count(); ++v)
    EXPECT_EQ(midpoints.count({s1.uvs[v].x, s1.uvs[v].y}), 1u) << v;
  // No face_material in → none out.
  plane.face_material.clear();
  EXPECT_TRUE(loop_subdivide(plane, 1).face_material.empty());
}

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
  expect_closed_manifold(*b1.rest_mesh);
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
  const Edges e0 = edges_of(rest), e1 = edges_of(sub);
  std::size_t boundary0 = 0, boundary1 = 0, over0 = 0, over1 = 0;
  for (const auto& [edge, n] : e0.count) boundary0 += (n == 1), over0 += (n > 2);
  for (const auto& [edge, n] : e1.count) boundary1 += (n == 1), over1 += (n > 2);
  EXPECT_EQ(over1, over0 * 4);
  EXPECT_EQ(boundary1, boundary0 * 4);
  EXPECT_EQ(e1.repeated_directed, e0.repeated_directed * 4);
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
                                          "fov_deg":45,"viewport":[800,600]})"), {})->redo(s);
  PlaceSketchCommand::parse(json::parse(R"({"cmd":"place.sketch","stroke":[[250,360],[400,350],[550,360]],
      "object":"ball","width":0.3,"height":0.3,"samples":[24,8],"order":[4,4,3],"controls":[8,4,3]})"), {})->redo(s);
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

}  // namespace
}  // namespace trispline::core
