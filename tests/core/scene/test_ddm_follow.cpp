// Tile layers following their object (core/scene/ddm_follow.h): the composition T (DDM) → host map → transform →
// FFD / DFFD, held against independent computations — ffd_evaluate of the transformed tiles, the exact Jacobian by
// central differences of the whole chain, host maps reproducing their triangles, DFFD instances never torn — and the
// paths that must not change at all (an undeformed object: transformed() bit for bit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/ffd/ffd.h"
#include "core/scene/ddm_follow.h"
#include "core/scene/scene_export.h"
#include "tests/ddm_follow_cases.h"

namespace trispline::core {
namespace {

using test::dffd_case;
using test::ffd_case;
using test::host_case;
using test::thorny_sphere;

TEST(DdmFollow, UndeformedObjectIsTheTransformBitForBit) {
  const SceneObject o = thorny_sphere();
  const DdmLayer& layer = *o.ddm_layers.front();
  const DdmLayerDeformation d(o, layer, 0.0);
  EXPECT_TRUE(d.rigid());
  const TriMesh a = ddm_layer_world_mesh(o, layer, *layer.mesh, 0.0);
  const TriMesh b = transformed(*layer.mesh, o.transform);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::dvec3)));
  EXPECT_EQ(0, std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(glm::dvec3)));
}

TEST(DdmFollow, FfdComposesAfterTheTransform) {
  const SceneObject o = ffd_case();
  const DdmLayer& layer = *o.ddm_layers.front();
  const DdmLayerDeformation d(o, layer, 0.0);
  ASSERT_FALSE(d.rigid());
  ASSERT_NE(d.lattice(), nullptr);
  EXPECT_TRUE(d.hosts().empty());
  const TriMesh out = d.apply(*layer.mesh);
  // Independent: T(x) world, then E + offset, then F.
  const TriMesh world = transformed(*layer.mesh, o.transform);
  std::vector<glm::dvec3> params = embed_points(o.ffd->embedding, world.positions);
  for (glm::dvec3& p : params) {
    EXPECT_TRUE(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= 0 && p.z <= 1) << "tile outside the box";
    p += o.param_offset;
  }
  std::vector<glm::dvec3> pos, nrm;
  ffd_evaluate(o.ffd->lattice, o.ffd->embedding, params, world.normals, pos, nrm);
  double worst = 0.0, worst_n = 0.0;
  for (std::size_t v = 0; v < pos.size(); ++v) {
    worst = std::max(worst, glm::length(pos[v] - out.positions[v]));
    worst_n = std::max(worst_n, glm::length(nrm[v] - out.normals[v]));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_n, 1e-12);
  // The tiles moved (the lattice is not the identity).
  double moved = 0.0;
  for (std::size_t v = 0; v < pos.size(); ++v) moved = std::max(moved, glm::length(pos[v] - world.positions[v]));
  EXPECT_GT(moved, 0.05);
}

// The normal of a mapped tile vertex is cof(J)·n, J the Jacobian of the whole chain x ↦ F(E(M·H·x) + offset) at the
// vertex: checked against J by central differences (every vertex is mapped on its own, so the whole layer mesh is
// shifted by ±h along each axis at once).
TEST(DdmFollow, NormalsAreThoseOfTheComposedMap) {
  for (const SceneObject& o : {ffd_case(), host_case()}) {
    const DdmLayer& layer = *o.ddm_layers.front();
    const DdmLayerDeformation d(o, layer, 0.0);
    const TriMesh out = d.apply(*layer.mesh);
    const double h = 1e-6;
    std::vector<TriMesh> shifted;
    for (int k = 0; k < 3; ++k)
      for (double s : {h, -h}) {
        TriMesh m = *layer.mesh;
        for (glm::dvec3& p : m.positions) p[k] += s;
        shifted.push_back(d.apply(m));
      }
    // Vertices whose parameters the lattice clamps (moved out of its box by the offset) have no Jacobian there.
    const TriMesh world = transformed(*layer.mesh, o.transform);
    double worst = 0.0;
    std::size_t checked = 0;
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
      if (o.ffd) {
        const glm::dvec3 p = o.ffd->embedding.apply(world.positions[v]) + o.param_offset;
        if (glm::any(glm::lessThan(p, glm::dvec3(1e-4))) || glm::any(glm::greaterThan(p, glm::dvec3(1 - 1e-4))))
          continue;
      }
      ++checked;
      glm::dmat3 J;
      for (int k = 0; k < 3; ++k) J[k] = (shifted[2 * k].positions[v] - shifted[2 * k + 1].positions[v]) / (2.0 * h);
      const glm::dvec3 n = glm::normalize(
          glm::dmat3(glm::cross(J[1], J[2]), glm::cross(J[2], J[0]), glm::cross(J[0], J[1])) * layer.mesh->normals[v]);
      worst = std::max(worst, glm::length(n - out.normals[v]));
    }
    EXPECT_GT(checked, out.positions.size() / 2);
    EXPECT_LT(worst, 1e-5) << (o.ffd ? "ffd" : "host maps");
  }
}

TEST(DdmFollow, HostMapsCarryTilesWithTheirTriangles) {
  const SceneObject o = host_case();
  const DdmLayer& layer = *o.ddm_layers.front();
  const DdmLayerDeformation d(o, layer, 0.0);
  ASSERT_FALSE(d.rigid());
  ASSERT_EQ(d.hosts().size(), layer.instances.size());
  EXPECT_EQ(d.lattice(), nullptr);
  // Every host map is a similarity (uniform scale × rotation) that takes a vertex of the old surface exactly onto
  // the same vertex of the warped one.
  const TriMesh& before = *layer.host_mesh;
  const TriMesh& after = *o.rest_mesh;
  for (const DdmHostMap& h : d.hosts()) {
    const glm::dmat3 mtm = glm::transpose(h.linear) * h.linear;
    const double s2 = mtm[0][0];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(mtm[c][r], r == c ? s2 : 0.0, 1e-9 * s2);
    bool anchored = false;
    for (std::size_t v = 0; v < before.positions.size() && !anchored; ++v)
      anchored = glm::length(h.linear * before.positions[v] + h.shift - after.positions[v]) < 1e-12;
    EXPECT_TRUE(anchored);
  }
  // The tiles moved with the surface: each instance's vertices are its old ones through its host map.
  const TriMesh out = d.apply(*layer.mesh);
  const glm::dmat4 m = o.transform.matrix();
  std::size_t v = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < layer.instances.size(); ++i)
    for (std::size_t k = 0; k < layer.tiles[0].mesh.vertex_count(); ++k, ++v) {
      const DdmHostMap& h = d.hosts()[i];
      const glm::dvec3 expect = glm::dvec3(m * glm::dvec4(h.linear * layer.mesh->positions[v] + h.shift, 1.0));
      worst = std::max(worst, glm::length(expect - out.positions[v]));
    }
  EXPECT_LT(worst, 1e-12);
}

TEST(DdmFollow, DffdNeverTearsAnInstance) {
  const SceneObject o = dffd_case();
  const DdmLayer& layer = *o.ddm_layers.front();
  const DdmLayerDeformation d(o, layer, 0.0);
  ASSERT_NE(d.lattice(), nullptr);
  ASSERT_EQ(d.param_lo().size(), layer.instances.size());
  const TriMesh out = d.apply(*layer.mesh);
  // The opening pulls the sides 0.6 apart: an instance torn across it would have an edge ≳ 0.3 long; tiles are
  // ≲ 0.5 across, their edges far shorter.
  double longest = 0.0;
  for (const glm::uvec3& t : out.triangles)
    for (int c = 0; c < 3; ++c)
      longest = std::max(longest, glm::length(out.positions[t[c]] - out.positions[t[(c + 1) % 3]]));
  const TriMesh plain = transformed(*layer.mesh, o.transform);
  double longest_plain = 0.0;
  for (const glm::uvec3& t : plain.triangles)
    for (int c = 0; c < 3; ++c)
      longest_plain = std::max(longest_plain, glm::length(plain.positions[t[c]] - plain.positions[t[(c + 1) % 3]]));
  EXPECT_LT(longest, 2.0 * longest_plain + 1e-9);
  // And instances on either side moved apart: some vertex moved by ≥ 0.25 in x.
  double dx_min = 0.0, dx_max = 0.0;
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    const double dx = out.positions[v].x - plain.positions[v].x;
    dx_min = std::min(dx_min, dx), dx_max = std::max(dx_max, dx);
  }
  EXPECT_LT(dx_min, -0.2);
  EXPECT_GT(dx_max, 0.2);
}

TEST(DdmFollow, ExportAndStillsCarryTheLayers) {
  Scene scene;
  scene.insert(ffd_case());
  const SceneExport ex = scene_export_nodes(scene);
  ASSERT_EQ(ex.nodes.size(), 2u);
  const SceneObject& o = *scene.find("ball");
  const TriMesh expect = ddm_layer_world_mesh(o, *o.ddm_layers.front(), *o.ddm_layers.front()->mesh, 0.0);
  ASSERT_EQ(ex.nodes[1].mesh->positions.size(), expect.positions.size());
  EXPECT_EQ(0, std::memcmp(ex.nodes[1].mesh->positions.data(), expect.positions.data(),
                           expect.positions.size() * sizeof(glm::dvec3)));
  // An offset animation moves the tiles with the object: a still at t = 1 differs from t = 0, deterministically.
  SceneObject moving = o;
  moving.offset_velocity = {0.1, 0.0, 0.0};
  scene.replace(moving);
  const Scene s1 = scene_at_time(scene, 1.0), s1b = scene_at_time(scene, 1.0);
  const SceneExport e1 = scene_export_nodes(s1), e1b = scene_export_nodes(s1b);
  ASSERT_EQ(e1.nodes.size(), 2u);
  EXPECT_EQ(0, std::memcmp(e1.nodes[1].mesh->positions.data(), e1b.nodes[1].mesh->positions.data(),
                           expect.positions.size() * sizeof(glm::dvec3)));
  double moved = 0.0;
  for (std::size_t v = 0; v < expect.positions.size(); ++v)
    moved = std::max(moved, glm::length(e1.nodes[1].mesh->positions[v] - expect.positions[v]));
  EXPECT_GT(moved, 0.01);
}

// The cpu_fast path of an FFD-carried layer against the reference, at two offsets (1e-5 × the layer's size; normals
// 1e-4).
TEST(DdmFollow, FastFollowerMatchesTheReference) {
  SceneObject o = ffd_case();
  const DdmLayer& layer = *o.ddm_layers.front();
  DdmFastFollower fast;
  fast.bind(o, *layer.mesh);
  ASSERT_EQ(fast.vertex_count(), layer.mesh->vertex_count());
  for (const glm::dvec3 offset : {glm::dvec3(0.02, 0.0, -0.01), glm::dvec3(-0.05, 0.03, 0.0)}) {
    o.param_offset = offset;
    const TriMesh ref = DdmLayerDeformation(o, layer, 0.0).apply(*layer.mesh);
    std::vector<glm::vec3> p, n;
    fast.evaluate(offset, p, n);
    Aabb box;
    for (const glm::dvec3& q : ref.positions) box.extend(q);
    double worst_p = 0.0, worst_n = 0.0;
    for (std::size_t v = 0; v < p.size(); ++v) {
      worst_p = std::max(worst_p, glm::length(glm::dvec3(p[v]) - ref.positions[v]));
      worst_n = std::max(worst_n, glm::length(glm::dvec3(n[v]) - ref.normals[v]));
    }
    EXPECT_LT(worst_p, 1e-5 * box.diagonal());
    EXPECT_LT(worst_n, 1e-4);
  }
  EXPECT_THROW(DdmFastFollower().bind(host_case(), *host_case().ddm_layers.front()->mesh), std::invalid_argument);
}

TEST(DdmFollow, BadInputIsRefused) {
  SceneObject o = ffd_case();
  EXPECT_THROW(DdmLayerDeformation(o, *o.ddm_layers.front(), std::nan("")), std::invalid_argument);
  const DdmLayerDeformation d(o, *o.ddm_layers.front(), 0.0);
  TriMesh short_mesh = *o.ddm_layers.front()->mesh;
  short_mesh.positions.pop_back();
  EXPECT_THROW(d.apply(short_mesh), std::invalid_argument);
  // A host mesh with more vertices than the object's surface cannot be followed.
  SceneObject h = host_case();
  auto layer = std::make_shared<DdmLayer>(*h.ddm_layers.front());
  TriMesh bigger = *layer->host_mesh;
  bigger.positions.push_back(glm::dvec3(0.0));
  layer->host_mesh = std::make_shared<const TriMesh>(std::move(bigger));
  EXPECT_THROW(DdmLayerDeformation(h, *layer, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::core
