// The showcase render (README picture): the default scene of assets/scenes/default.jsonl built through the core
// API — the teapot with the Stanford bunny placed along a stroke over its body — with the lattice, the contact
// samples and the stroke shown. Writes <build>/gpu_showcase.png for eyeballing.
#include <epoxy/gl.h>

#include <filesystem>

#include "core/image/image_io.h"
#include "core/mesh/mesh_io.h"
#include "core/placement/sketch_placement.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/primitives.h"
#include "gl_test.h"

namespace trispline::gpu::test {
namespace {

core::SceneObject object_from(const std::string& name, const core::TriMesh& rest, const core::Transform& t,
                              const glm::vec3& color) {
  core::SceneObject o;
  o.name = name;
  o.source = name;
  o.rest_mesh = std::make_shared<const core::TriMesh>(rest);
  o.transform = t;
  o.color = color;
  o.refresh();
  return o;
}

}  // namespace

TEST_F(GlTest, ShowcaseDefaultScene) {
  core::Scene scene;
  scene.insert(object_from("teapot", core::make_teapot(), {}, {0.86f, 0.84f, 0.80f}));

  // The bunny comes from the asset script (git-ignored); a capsule-like sphere stands in when it is absent.
  const std::filesystem::path bunny_path = TRISPLINE_SOURCE_DIR "/assets/data/bunny.obj";
  core::Transform bt;
  core::TriMesh bunny;
  if (std::filesystem::exists(bunny_path)) {
    bunny = core::load_mesh(bunny_path);
    bt.scale = glm::dvec3(0.25);
    bt.translate = {1.5, 0.25, 0.0};
  } else {
    bunny = uv_sphere({0, 0, 0}, 1.0);
    bt.scale = {0.5, 0.15, 0.15};
    bt.translate = {1.5, 0.25, 0.0};
  }
  core::SceneObject placed = object_from("bunny", bunny, bt, {0.90f, 0.55f, 0.20f});

  core::Camera cam;
  cam.eye = {0.0, 1.7, 2.1};
  cam.target = {0.0, 0.38, 0.0};
  cam.fov_deg = 40.0;
  cam.viewport = {1280, 720};
  scene.camera = cam;
  scene.camera_set = true;

  core::SketchPlacementParams params;
  params.stroke_px = {{436.2, 337.8}, {471.2, 366.8}, {534.6, 389.4}, {617.8, 400.2},
                      {705.5, 396.5}, {780.3, 379.3}, {830.0, 352.8}};
  params.camera = cam;
  params.half_width = 0.14;
  params.height = 0.4;
  params.samples_u = 48;
  params.samples_v = 12;
  params.volume = core::PlacementVolume::Offset;
  params.order = {4, 4, 3};
  params.controls = {12, 5, 3};
  params.axes = {0, 1};
  core::RayCaster rays;
  rays.add_mesh(*scene.find("teapot")->world_mesh);
  rays.commit();
  const core::SketchPlacementResult res = core::place_along_stroke(rays, params, placed.world_rest_mesh().positions);
  placed.ffd = std::make_shared<const core::FfdBinding>(res.binding);
  placed.placement = std::make_shared<const core::PlacementRecord>(res.record);
  placed.refresh();
  scene.insert(placed);

  ViewOptions opt;
  opt.show_lattice = true;
  opt.show_contact_surface = true;
  opt.selected = "bunny";
  opt.add_stroke(params.stroke_px);
  Renderer r;
  const std::vector<unsigned char> img = render(r, scene, cam, opt);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_EQ(r.last_stats().objects_drawn, 2);
  // Somewhere near the stroke's middle the orange stroke or bunny shows.
  const Rgba mid = pixel(img, 1280, 618, 400);
  EXPECT_GT(mid.r, mid.b + 40) << mid.r << " " << mid.g << " " << mid.b;

  const std::string out = TRISPLINE_BINARY_DIR "/gpu_showcase.png";
  core::write_image_rgba8(out, 1280, 720, img);
  std::printf("wrote %s\n", out.c_str());
  opt.show_lattice = opt.show_contact_surface = false;
  opt.overlays.strokes.clear();
  core::write_image_rgba8(TRISPLINE_BINARY_DIR "/gpu_showcase_clean.png", 1280, 720, render(r, scene, cam, opt));
}

TEST_F(GlTest, LatticeOverlayAppearsOnlyWhenAsked) {
  using core::KnotVector;
  std::vector<glm::dvec3> cps;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) cps.push_back({i ? 1.2 : -1.2, j ? 1.2 : -1.2, k ? 1.2 : -1.2});
  core::TrivariateBSpline<glm::dvec3> lattice(KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                                              KnotVector::clamped_uniform(2, 2), cps);
  core::Scene scene;
  core::SceneObject o = make_object("ball", uv_sphere({0, 0, 0}, 1.0), {0.2f, 0.2f, 0.2f});
  o.ffd = std::make_shared<const core::FfdBinding>(core::FfdBinding{lattice, core::Embedding{}, {}});
  scene.insert(o);
  ViewOptions opt;
  opt.show_grid = false;
  Renderer r;
  core::Camera cam = front_camera();
  cam.eye = {0.0, 0.0, 6.0};                                                            // the whole lattice in view
  auto bluish_near = [](const std::vector<unsigned char>& img, const glm::dvec3& at) {  // 1-px lines: look around
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const Rgba p = pixel(img, 160, int(at.x) + dx, int(at.y) + dy);
        if (p.b > 150 && p.b > p.r + 50) return true;
      }
    return false;
  };
  // The lattice's front corner (1.2, 1.2, 1.2) projects to the upper right, outside the sphere.
  ASSERT_GT(cam.project({1.2, 1.2, 1.2}).y, 1.0);
  const glm::dvec3 c = cam.project({1.2, 1.2, 1.2});
  const glm::dvec3 e = cam.project({0.0, 1.2, 1.2});  // middle of a front edge
  EXPECT_FALSE(bluish_near(render(r, scene, cam, opt), e));
  opt.show_lattice = true;
  const std::vector<unsigned char> img = render(r, scene, cam, opt);
  EXPECT_TRUE(bluish_near(img, e));
  const Rgba corner = pixel(img, 160, int(c.x), int(c.y));
  EXPECT_GT(corner.r + corner.g + corner.b, 500);  // white control point
}

}  // namespace trispline::gpu::test
