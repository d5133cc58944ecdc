// mesh.refine (core/commands/mesh_refine.h) on the seed's cube under a bent and twisted lattice (Fig. 2.10): the
// refinement runs in object space and undo restores the object exactly; bad parameters name their field and change
// nothing. The algorithm's own tests: tests/core/ffd/test_refine.cpp.
#include <gtest/gtest.h>

#include "core/commands/mesh_refine.h"
#include "core/ffd/deformation_bounds.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/ffd/ffd_test_util.h"

namespace trispline::core {
namespace mesh_refine_test {

Scene cube_scene() {
  Scene s;
  SceneObject obj;
  obj.name = "cube";
  obj.source = "test:cube12";
  obj.rest_mesh = std::make_shared<const TriMesh>(test::cube12());
  obj.transform.translate = {0.5, 0.0, -0.25};
  obj.transform.scale = {1.0, 0.5, 1.0};
  const TriMesh world = obj.world_rest_mesh();
  obj.ffd = std::make_shared<const FfdBinding>(test::bent_twisted_binding(world));
  obj.refresh();
  s.insert(obj);
  SceneObject plain = obj;
  plain.name = "plain";
  plain.ffd.reset();
  plain.refresh();
  s.insert(plain);
  return s;
}

CommandPtr parse(const std::string& line) { return MeshRefineCommand::parse(nlohmann::json::parse(line), {}); }

TEST(MeshRefineCommand, RefinesInObjectSpaceAndUndoRestoresExactly) {
  Scene s = cube_scene();
  const SceneObject before = *s.find("cube");
  auto cmd = parse(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01,"criterion":"greville"})");
  cmd->redo(s);
  const SceneObject& after = *s.find("cube");
  EXPECT_GT(after.rest_mesh->triangles.size(), 12u);
  EXPECT_EQ(after.ffd->params.size(), after.rest_mesh->positions.size());
  EXPECT_EQ(&after.ffd->lattice == &before.ffd->lattice, false);
  // World rest positions of the refined object embed to the stored parameters (object-space refinement is exact).
  const TriMesh world = after.world_rest_mesh();
  for (std::size_t i = 0; i < world.positions.size(); ++i)
    EXPECT_LT(glm::length(after.ffd->embedding.apply(world.positions[i]) - after.ffd->params[i]), 1e-12);
  const nlohmann::json st = cmd->stats();
  EXPECT_EQ(st.at("triangles_before"), 12);
  EXPECT_EQ(st.at("triangles_after"), after.rest_mesh->triangles.size());
  EXPECT_LE(st.at("max_deviation_bound").get<double>(), 0.01);
  for (const char* k : {"iterations", "stopped_by_budget", "ms_refine", "ms_evaluate"})
    EXPECT_TRUE(st.contains(k)) << k;
  const std::vector<glm::dvec3> refined = after.rest_mesh->positions;
  cmd->undo(s);
  EXPECT_EQ(s.find("cube")->rest_mesh, before.rest_mesh);  // the same immutable mesh, bit for bit
  EXPECT_EQ(s.find("cube")->ffd, before.ffd);
  EXPECT_EQ(s.find("cube")->world_mesh, before.world_mesh);
  cmd->redo(s);  // redo gives the same refinement
  EXPECT_EQ(s.find("cube")->rest_mesh->positions, refined);
  // Round trip through the log line.
  EXPECT_EQ(parse(cmd->to_json().dump())->to_json(), cmd->to_json());
}

// "error":"bound": every final triangle's certified bound is within the tolerance (the refinement converged), for both
// split rules; the counts are the seed's cube comparison (§2.4.2, Fig. 2.10: midpoint vs Greville splits, here at the
// same certified tolerance), reported as test properties.
TEST(MeshRefineCommand, CertifiedRefinementBoundsEveryTriangle) {
  for (const char* criterion : {"midpoint", "greville", "best"}) {
    Scene s = cube_scene();
    auto cmd =
        parse(std::string(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.02,"error":"bound","criterion":")") +
              criterion + R"(","max_iterations":32})");
    cmd->redo(s);
    const nlohmann::json st = cmd->stats();
    EXPECT_EQ(st.at("stopped_by"), "converged") << criterion;
    ASSERT_TRUE(st.at("max_bound").is_number()) << criterion;
    EXPECT_LE(st.at("max_bound").get<double>(), 0.02) << criterion;
    EXPECT_GT(st.at("triangles_after").get<int>(), 12) << criterion;
    EXPECT_EQ(st.at("error"), "bound");
    RecordProperty(std::string("triangles_") + criterion, st.at("triangles_after").dump());
    // The certificate is real: the measured error of every final triangle is within it.
    const SceneObject& c = *s.find("cube");
    const auto& F = c.ffd->lattice;
    for (std::size_t f = 0; f < c.rest_mesh->triangles.size(); f += 7) {
      const glm::uvec3 t = c.rest_mesh->triangles[f];
      EXPECT_LE(triangle_error_sampled(F, c.ffd->params[t.x], c.ffd->params[t.y], c.ffd->params[t.z], 8), 0.02)
          << criterion << " triangle " << f;
    }
  }
}

TEST(MeshRefineCommand, BadParametersNameTheirField) {
  Scene s = cube_scene();
  const Scene before = s;
  const auto field_of = [&](const char* line) {
    return trispline::test::command_field_of<MeshRefineCommand>(s, nlohmann::json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"nobody","tolerance":0.01})"), "object");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"plain","tolerance":0.01})"), "object");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":0})"), "tolerance");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":-1})"), "tolerance");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01,"criterion":"bisect"})"), "criterion");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01,"criterion":"best"})"), "criterion")
      << "best chooses by the certified bound: only with error bound";
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01,"max_iterations":-2})"),
            "max_iterations");
  EXPECT_EQ(field_of(R"({"cmd":"mesh.refine","object":"cube","tolerance":0.01,"max_triangles":5})"), "max_triangles");
  // Below float32's resolution at the cube's size: refused before any round (1e-300 once ran to the triangle budget).
  for (const char* tiny : {R"({"cmd":"mesh.refine","object":"cube","tolerance":1e-300})",
                           R"({"cmd":"mesh.refine","object":"cube","tolerance":5e-324,"error":"bound"})",
                           R"({"cmd":"mesh.refine","object":"cube","tolerance":1e-12,"max_triangles":8000000})"})
    EXPECT_EQ(field_of(tiny), "tolerance") << tiny;
  EXPECT_EQ(s.find("cube")->rest_mesh->triangles.size(), 12u);  // untouched
  trispline::test::expect_same_meshes(s, before);
}

}  // namespace mesh_refine_test
}  // namespace trispline::core
