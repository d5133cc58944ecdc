#include <epoxy/gl.h>

#include "gl_test.h"

namespace trispline::gpu::test {
namespace {

core::Scene red_sphere_scene(const glm::dvec3& center) {
  core::Scene s;
  s.insert(make_object("ball", uv_sphere(center, 1.0), {0.8f, 0.03f, 0.02f}));
  return s;
}

int count_if(const std::vector<unsigned char>& img, int w, int h, bool (*pred)(const Rgba&)) {
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) n += pred(pixel(img, w, x, y)) ? 1 : 0;
  return n;
}

bool close_to(int a, float b01) { return std::abs(a - int(b01 * 255.0f + 0.5f)) <= 3; }

}  // namespace

TEST_F(GlTest, RedSphereInFrontIsRedInTheCentreAndBackgroundAtCorners) {
  Renderer r;
  const core::Camera cam = front_camera();
  ViewOptions opt;
  opt.show_grid = false;
  const std::vector<unsigned char> img = render(r, red_sphere_scene({0, 0, 0}), cam, opt);
  EXPECT_TRUE(reddish(pixel(img, 160, 80, 60)));
  const Rgba tl = pixel(img, 160, 0, 0), bl = pixel(img, 160, 0, 119), br = pixel(img, 160, 159, 119);
  EXPECT_TRUE(close_to(tl.r, opt.style.background_top.x) && close_to(tl.g, opt.style.background_top.y) &&
              close_to(tl.b, opt.style.background_top.z))
      << tl.r << " " << tl.g << " " << tl.b;
  EXPECT_TRUE(close_to(bl.r, opt.style.background_bottom.x) && close_to(bl.b, opt.style.background_bottom.z))
      << bl.r << " " << bl.b;
  EXPECT_FALSE(reddish(br));
  EXPECT_EQ(tl.a, 255);
  EXPECT_EQ(r.last_stats().objects_drawn, 1);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, SphereBehindTheCameraDoesNotAppear) {
  Renderer r;
  const core::Camera cam = front_camera();
  const std::vector<unsigned char> empty = render(r, core::Scene{}, cam);
  const std::vector<unsigned char> behind = render(r, red_sphere_scene({0, 0, 7}), cam);
  EXPECT_EQ(count_if(behind, 160, 120, reddish), 0);
  EXPECT_EQ(behind, empty);
}

TEST_F(GlTest, StrokeIsDrawnWhereItsPixelsAre) {
  Renderer r;
  ViewOptions opt;
  opt.add_stroke({{20.0, 30.5}, {80.0, 30.5}, {140.0, 30.5}}).width_px = 5.0f;
  const std::vector<unsigned char> img = render(r, core::Scene{}, front_camera(), opt);
  auto orange = [](const Rgba& p) { return p.r > 200 && p.g > 60 && p.g < 170 && p.b < 60; };
  for (int x : {20, 50, 80, 110, 140}) EXPECT_TRUE(orange(pixel(img, 160, x, 30))) << "x " << x;
  EXPECT_FALSE(orange(pixel(img, 160, 80, 40)));
  EXPECT_FALSE(orange(pixel(img, 160, 10, 30)));
}

TEST_F(GlTest, SameSceneTwiceGivesIdenticalImages) {
  const core::Scene scene = red_sphere_scene({0.3, 0.2, 0});
  ViewOptions opt;
  opt.selected = "ball";
  opt.add_stroke({{10, 10}, {100, 90}});
  Renderer a;
  const std::vector<unsigned char> first = render(a, scene, front_camera(), opt);
  EXPECT_EQ(render(a, scene, front_camera(), opt), first);  // cached buffers
  Renderer b;
  EXPECT_EQ(render(b, scene, front_camera(), opt), first);  // a fresh renderer
}

TEST_F(GlTest, BuffersAreCachedOnWorldMeshIdentity) {
  Renderer r;
  core::Scene scene = red_sphere_scene({0, 0, 0});
  render(r, scene, front_camera());
  EXPECT_EQ(r.last_stats().uploads, 1);
  render(r, scene, front_camera());
  EXPECT_EQ(r.last_stats().uploads, 0);
  core::SceneObject o = *scene.find("ball");
  o.world_mesh = std::make_shared<const core::TriMesh>(uv_sphere({0, 0, 0}, 0.5));
  scene.replace(o);
  render(r, scene, front_camera());
  EXPECT_EQ(r.last_stats().uploads, 1);
  EXPECT_EQ(r.last_stats().cached_meshes, 1);
  scene.clear();
  render(r, scene, front_camera());
  EXPECT_EQ(r.last_stats().cached_meshes, 0);
}

TEST_F(GlTest, SelectionDrawsAnOutline) {
  Renderer r;
  const core::Scene scene = red_sphere_scene({0, 0, 0});
  ViewOptions opt;
  opt.show_grid = false;
  auto outline = [](const Rgba& p) { return p.r > 200 && p.g > 120 && p.g < 190 && p.b < 90; };
  EXPECT_EQ(count_if(render(r, scene, front_camera(), opt), 160, 120, outline), 0);
  opt.selected = "ball";
  const std::vector<unsigned char> img = render(r, scene, front_camera(), opt);
  // Silhouette radius ≈ 37 px; the outline ring (2 px) has ~2π·38·2 ≈ 470 pixels.
  EXPECT_GT(count_if(img, 160, 120, outline), 250);
  EXPECT_FALSE(outline(pixel(img, 160, 80, 60)));
}

TEST_F(GlTest, GridAndWireframeChangeTheImageWithoutGlErrors) {
  Renderer r;
  core::Camera cam = front_camera();
  cam.eye = {0, 2.5, 4};
  const core::Scene scene = red_sphere_scene({0, 1, 0});
  ViewOptions plain;
  plain.show_grid = false;
  ViewOptions grid;
  ViewOptions wire = plain;
  wire.wireframe = true;
  const auto a = render(r, scene, cam, plain), b = render(r, scene, cam, grid), c = render(r, scene, cam, wire);
  EXPECT_NE(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, ContactSamplesAreGreenWhereHitAndRedWhereFilled) {
  Renderer r;
  const core::Camera cam = front_camera();
  core::Scene scene;
  core::SceneObject o = make_object("obj", uv_sphere({0, 0, -30}, 0.1), {0.5f, 0.5f, 0.5f});  // far away
  auto rec = std::make_shared<core::PlacementRecord>();
  rec->samples_u = 2;
  rec->samples_v = 1;
  rec->contact_points = {{-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  rec->contact_hit = {1, 0};
  o.placement = rec;
  scene.insert(o);
  ViewOptions opt;
  opt.show_grid = false;
  opt.show_contact_surface = true;
  const std::vector<unsigned char> img = render(r, scene, cam, opt);
  const glm::dvec3 p0 = cam.project(rec->contact_points[0]), p1 = cam.project(rec->contact_points[1]);
  const Rgba hit = pixel(img, 160, int(p0.x), int(p0.y)), filled = pixel(img, 160, int(p1.x), int(p1.y));
  EXPECT_TRUE(hit.g > 150 && hit.r < 150) << hit.r << " " << hit.g << " " << hit.b;
  EXPECT_TRUE(filled.r > 150 && filled.g < 120) << filled.r << " " << filled.g << " " << filled.b;
  opt.show_contact_surface = false;
  EXPECT_TRUE(!reddish(pixel(render(r, scene, cam, opt), 160, int(p1.x), int(p1.y))));
}

}  // namespace trispline::gpu::test
