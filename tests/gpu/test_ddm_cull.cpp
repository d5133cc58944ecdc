// Culling and thinning of live DDM layers (gpu/view/ddm_cull.h, the renderer's ViewOptions::ddm) on the teapot's body
// covered with thorns: the frustum test never drops an instance with a vertex of the CPU reference mesh inside the
// view (from views around, close to and inside the pot); rendered for real on llvmpipe, the culled image is the full
// one (frustum: pixel for pixel; with the facing-away cone: within a few pixels), the thinned one draws a power-of-two
// share under the budget, and the stats count what was left out.
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_remove.h"
#include "core/scene/primitives.h"
#include "gl_test.h"
#include "gpu/view/ddm_cull.h"

namespace trispline::gpu::test {
namespace {

// The teapot primitive with its body covered by thorns 0.1 world units across, as the Tile Paint panel makes them.
core::SceneObject thorny_teapot() {
  core::SceneObject o = make_object("teapot", core::make_primitive(core::PrimitiveKind::Teapot), {0.8f, 0.6f, 0.2f});
  o.source = "primitive:teapot";
  o.rest_mesh = o.world_mesh;
  core::DdmLayerSpec spec;
  spec.tiles = {"thorn"};
  spec.tile_size = 0.1;
  spec.height = 0.15;
  spec.base = core::DdmBaseKind::teapot_body;
  o.ddm_layers.push_back(core::make_ddm_layer(o, "thorns", spec, true));
  return o;
}

core::Camera camera(glm::dvec3 eye, glm::dvec3 target, int w = 320, int h = 240) {
  core::Camera c;
  c.eye = eye;
  c.target = target;
  c.viewport = {w, h};
  return c;
}

std::vector<core::Camera> views() {
  // The teapot primitive spans about [-0.9, 0.9] × [0, 0.8] × [-0.6, 0.6].
  return {camera({0, 1, 3}, {0, 0.4, 0}),           // the whole pot
          camera({2, 1.2, 1.5}, {0, 0.4, 0}),       // from the side, above
          camera({0.5, 0.6, 1.0}, {0.6, 0.45, 0}),  // close: most of the pot out of view
          camera({0, 0.5, 0.1}, {1, 0.4, 0}),       // inside the pot, looking at its wall
          camera({0, -1.5, 1}, {0, 0.4, 0})};       // from below
}

// Pixels whose colour differs by more than `tolerance` (of 255) in some channel.
int count_different_by(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int tolerance) {
  int n = 0;
  for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
    n += std::abs(a[i] - b[i]) > tolerance || std::abs(a[i + 1] - b[i + 1]) > tolerance ||
         std::abs(a[i + 2] - b[i + 2]) > tolerance;
  return n;
}

int count_different(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  return count_different_by(a, b, 0);
}

class DdmCullTest : public GlTest {};

TEST(DdmCull, FrustumNeverDropsAnInstanceWithAVertexInView) {
  const core::SceneObject o = thorny_teapot();
  const core::DdmLayer& layer = *o.ddm_layers.front();
  const DdmInstanceBounds bounds = ddm_instance_bounds(layer);
  ASSERT_EQ(bounds.spheres.size(), layer.instances.size());
  std::vector<std::size_t> first(layer.instances.size() + 1, 0);
  for (std::size_t k = 0; k < layer.instances.size(); ++k)
    first[k + 1] = first[k] + layer.tiles[std::size_t(layer.instances[k].tile)].mesh.vertex_count();
  std::size_t culled_somewhere = 0;
  for (const core::Camera& cam : views()) {
    DdmCullView view;
    view.view_proj = cam.projection_matrix() * cam.view_matrix();
    view.model = o.transform.matrix();
    view.eye = cam.eye;
    const DdmCuller culler(bounds, view);
    std::size_t in_view = 0, culled = 0, wrongly = 0;
    for (std::size_t k = 0; k < layer.instances.size(); ++k) {
      bool inside = false;
      for (std::size_t v = first[k]; v < first[k + 1] && !inside; ++v) {
        const glm::dvec4 c = view.view_proj * view.model * glm::dvec4(layer.mesh->positions[v], 1.0);
        inside = c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
      }
      const bool dropped = culler.test(k) == DdmCullReason::outside;
      in_view += inside;
      culled += dropped;
      wrongly += inside && dropped;
    }
    std::printf("[ddm cull] eye (%g, %g, %g): %zu of %zu instances with a vertex in view, %zu culled\n", cam.eye.x,
                cam.eye.y, cam.eye.z, in_view, layer.instances.size(), culled);
    EXPECT_EQ(wrongly, 0u) << "eye " << cam.eye.x << " " << cam.eye.y << " " << cam.eye.z;
    EXPECT_LE(culled + in_view, layer.instances.size() + 0u);
    culled_somewhere += culled;
  }
  EXPECT_GT(culled_somewhere, layer.instances.size()) << "the close and inside views leave many out";
}

TEST(DdmCull, BoundsNeedTheLayersOwnMeshAndRanksSpreadEvenly) {
  core::SceneObject o = thorny_teapot();
  auto animated = std::make_shared<core::DdmLayer>(*o.ddm_layers.front());
  animated->offset_velocity = {0.1, 0.0};
  EXPECT_TRUE(ddm_instance_bounds(*animated).empty()) << "its instances move: not bounded, never culled";
  auto stale = std::make_shared<core::DdmLayer>(*o.ddm_layers.front());
  stale->instances.pop_back();
  EXPECT_TRUE(ddm_instance_bounds(*stale).empty()) << "a mesh of another vertex count";
  std::size_t below_quarter = 0;
  for (std::size_t k = 0; k < 100000; ++k) below_quarter += ddm_lod_rank(k) < 0.25f;
  EXPECT_NEAR(double(below_quarter) / 100000.0, 0.25, 0.01);
}

TEST_F(DdmCullTest, CulledAndThinnedRendersMatchTheFullOne) {
  core::Scene scene;
  scene.insert(thorny_teapot());
  const std::size_t instances = scene.objects().front().ddm_layers.front()->instances.size();
  const std::size_t tile_vertices = scene.objects().front().ddm_layers.front()->tiles.front().mesh.vertex_count();
  Renderer renderer;
  ViewOptions full;
  ViewOptions frustum;
  frustum.ddm.cull = true;
  frustum.ddm.backface_margin_deg = -1.0;
  ViewOptions culled;
  culled.ddm.cull = true;  // frustum and the facing-away cone at its default margin
  std::size_t left_out = 0;
  for (const core::Camera& cam : views()) {
    const std::vector<unsigned char> a = render(renderer, scene, cam, full);
    EXPECT_EQ(renderer.last_stats().ddm_instances_drawn, instances);
    const std::vector<unsigned char> b = render(renderer, scene, cam, frustum);
    const RenderStats fs = renderer.last_stats();
    const std::vector<unsigned char> c = render(renderer, scene, cam, culled);
    const RenderStats cs = renderer.last_stats();
    const int pixels = cam.viewport.x * cam.viewport.y;
    std::printf(
        "[ddm cull render] eye (%g, %g, %g): frustum drew %zu, +facing away %zu of %zu; %d / %d pixels differ\n",
        cam.eye.x, cam.eye.y, cam.eye.z, fs.ddm_instances_drawn, cs.ddm_instances_drawn, instances,
        count_different(a, b), count_different(a, c));
    EXPECT_EQ(fs.ddm_instances, instances);
    EXPECT_EQ(fs.ddm_instances_drawn + fs.ddm_instances_culled, instances);
    EXPECT_EQ(fs.ddm_vertices, fs.ddm_instances_drawn * tile_vertices);
    EXPECT_EQ(count_different(a, b), 0) << "frustum culling draws the same pixels";
    EXPECT_LE(count_different(a, c), pixels / 1000) << "the facing-away cone leaves out hidden tiles only";
    EXPECT_LE(cs.ddm_instances_drawn, fs.ddm_instances_drawn);
    if (cam.eye.y < 0) {
      EXPECT_LT(cs.ddm_instances_drawn, fs.ddm_instances_drawn) << "from below the top faces away";
    }
    left_out += instances - cs.ddm_instances_drawn;
  }
  EXPECT_GT(left_out, instances) << "culling left tiles out";

  // Moving: thinned to a power-of-two share under the budget; at rest full detail again.
  ViewOptions moving = culled;
  moving.ddm.moving = true;
  moving.ddm.motion_budget_vertices = instances * tile_vertices / 10;
  const core::Camera cam = views().front();
  render(renderer, scene, cam, moving);
  const RenderStats ms = renderer.last_stats();
  EXPECT_LT(ms.ddm_keep, 1.0);
  EXPECT_GT(ms.ddm_instances_drawn, 0u);
  EXPECT_LE(double(ms.ddm_vertices), 1.5 * double(moving.ddm.motion_budget_vertices));
  render(renderer, scene, cam, culled);
  EXPECT_EQ(renderer.last_stats().ddm_keep, 1.0);
  EXPECT_GT(renderer.last_stats().ddm_instances_drawn, ms.ddm_instances_drawn);
}

TEST(DdmCull, LevelOfDetailFollowsTheSizeOnScreen) {
  // Spheres 10 units in front of the eye, 100, 30 and 10 pixels across with 100 pixels per unit at w = 1.
  DdmInstanceBounds b;
  for (double px : {100.0, 30.0, 10.0}) b.spheres.push_back({0.0f, 0.0f, -10.0f, float(px * 10.0 / 200.0)});
  b.normals.assign(3, {0.0f, 0.0f, 1.0f});
  b.lo = glm::dvec3(-6.0, -6.0, -16.0), b.hi = glm::dvec3(6.0, 6.0, -4.0);
  DdmCullView v;
  v.view_proj = glm::perspective(glm::radians(60.0), 1.0, 0.1, 100.0);
  v.frustum = false;
  DdmCuller off(b, v);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(off.level(k), 0) << "no screen-size LOD without pixels_per_unit";
  v.pixels_per_unit = 100.0;
  DdmCuller lod(b, v);
  EXPECT_EQ(lod.level(0), 0);  // 100 px ≥ kDdmLodPixels[0]
  EXPECT_EQ(lod.level(1), 1);  // 30 px
  EXPECT_EQ(lod.level(2), 2);  // 10 px
}

TEST_F(DdmCullTest, ScreenSizeLodDrawsFewerVerticesAndTheSamePicture) {
  core::Scene scene;
  scene.insert(thorny_teapot());
  Renderer renderer;
  ViewOptions culled;
  culled.ddm.cull = true;
  for (const int height : {240, 960}) {
    const core::Camera cam = camera({0, 1, 3}, {0, 0.4, 0}, height * 4 / 3, height);
    ViewOptions lod = culled;
    lod.ddm.pixels_per_unit = cam.projection_matrix()[1][1] * height * 0.5;
    const std::vector<unsigned char> a = render(renderer, scene, cam, culled);
    const RenderStats full = renderer.last_stats();
    const std::vector<unsigned char> b = render(renderer, scene, cam, lod);
    const RenderStats coarse = renderer.last_stats();
    const int pixels = cam.viewport.x * cam.viewport.y;
    std::printf(
        "[ddm screen lod] %d px high: %zu → %zu tile vertices for %zu tiles; of %d pixels %d differ, %d by more than "
        "16, %d by more than 64 levels\n",
        height, full.ddm_vertices, coarse.ddm_vertices, coarse.ddm_instances_drawn, pixels, count_different(a, b),
        count_different_by(a, b, 16), count_different_by(a, b, 64));
    EXPECT_EQ(coarse.ddm_instances_drawn, full.ddm_instances_drawn) << "the same tiles, coarser";
    // 240 pixels high: the thorns are 5–20 pixels across (level 1 and 2); 960: most are over 64 (level 0).
    EXPECT_LT(coarse.ddm_vertices, height == 240 ? full.ddm_vertices / 4 : full.ddm_vertices);
    EXPECT_LE(count_different_by(a, b, 64), pixels / 200) << "a coarser tile only where it is small on screen";
  }
}

}  // namespace
}  // namespace trispline::gpu::test
