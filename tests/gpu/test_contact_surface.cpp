// The contact surface S(u,v) = F(u,v,0) overlay (ViewOptions::show_contact_surface): drawn where the placed
// object's lattice bottom is, nowhere else, cached per FfdBinding. Writes <build>/gpu_contact_surface.png.
#include <epoxy/gl.h>

#include <cmath>

#include "core/image/image_io.h"
#include "gl_test.h"
#include "gpu/view/overlay_geometry.h"

namespace trispline::gpu::test {
namespace {

// A lattice whose bottom layer is a gently curved sheet under a sphere of radius 0.6 at the origin.
std::shared_ptr<const core::FfdBinding> sheet_binding(double bend = 0.25) {
  using core::KnotVector;
  const glm::ivec3 n(6, 4, 3);
  std::vector<glm::dvec3> cps;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const double x = -1.6 + 3.2 * i / (n.x - 1), z = -0.9 + 1.8 * j / (n.y - 1);
        cps.push_back({x, -0.65 + bend * (x * x / 2.56 - 0.5) + 0.6 * k, z});
      }
  core::TrivariateBSpline<glm::dvec3> lattice(KnotVector::clamped_uniform(4, n.x), KnotVector::clamped_uniform(3, n.y),
                                              KnotVector::clamped_uniform(2, n.z), cps);
  return std::make_shared<const core::FfdBinding>(core::FfdBinding{lattice, core::Embedding{}, {}});
}

core::Scene placed_scene(std::shared_ptr<const core::FfdBinding> ffd) {
  core::Scene scene;
  core::SceneObject o = make_object("placed", uv_sphere({0, 0, 0}, 0.6), {0.9f, 0.55f, 0.2f});
  auto rec = std::make_shared<core::PlacementRecord>();
  rec->samples_u = 3;
  rec->samples_v = 1;
  for (double u : {0.2, 0.5, 0.8}) rec->contact_points.push_back(ffd->lattice.eval({u, 0.5, 0.0}));
  rec->contact_hit = {1, 1, 0};
  o.ffd = std::move(ffd);
  o.placement = rec;
  scene.insert(o);
  return scene;
}

core::Camera oblique_camera(int w = 160, int h = 120) {
  core::Camera cam = front_camera(w, h);
  cam.eye = {0.4, 2.2, 3.6};
  cam.target = {0.0, -0.45, 0.0};
  return cam;
}

bool same_block(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int w, int x0, int y0,
                int size) {
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) {
      const Rgba p = pixel(a, w, x, y), q = pixel(b, w, x, y);
      if (p.r != q.r || p.g != q.g || p.b != q.b || p.a != q.a) return false;
    }
  return true;
}

}  // namespace

TEST_F(GlTest, ContactSurfaceIsDrawnWhereFOfUV0IsAndNowhereElse) {
  const core::Scene scene = placed_scene(sheet_binding());
  const core::FfdBinding& ffd = *scene.objects()[0].ffd;
  const core::Camera cam = oblique_camera();
  ViewOptions off;
  off.show_grid = false;
  ViewOptions on = off;
  on.show_contact_surface = true;
  Renderer r;
  const std::vector<unsigned char> a = render(r, scene, cam, off), b = render(r, scene, cam, on);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  EXPECT_EQ(r.last_stats().contact_surfaces_drawn, 1);

  // Inside the projected sheet (its left part is beside the sphere) the image changes, towards the teal tint.
  int changed_inside = 0, inside = 0;
  const ContactSurfaceTessellation t = tessellate_contact_surface(ffd.lattice, 24, 8);
  for (const glm::dvec3& p : t.mesh.positions) {
    const glm::dvec3 s = cam.project(p);
    if (s.x < 1 || s.y < 1 || s.x >= 159 || s.y >= 119) continue;
    ++inside;
    const Rgba p0 = pixel(a, 160, int(s.x), int(s.y)), p1 = pixel(b, 160, int(s.x), int(s.y));
    changed_inside += (p0.r != p1.r || p0.g != p1.g || p0.b != p1.b) ? 1 : 0;
  }
  ASSERT_GT(inside, 100);
  EXPECT_GT(changed_inside, inside * 3 / 4) << changed_inside << " of " << inside;  // the rest: behind the sphere
  const glm::dvec3 left = cam.project(ffd.lattice.eval({0.08, 0.5, 0.0}));          // on the sheet, off the sphere
  const Rgba l0 = pixel(a, 160, int(left.x), int(left.y)), l1 = pixel(b, 160, int(left.x), int(left.y));
  EXPECT_GT((l1.g - l1.r) - (l0.g - l0.r), 25) << l0.r << "," << l0.g << " -> " << l1.r << "," << l1.g;
  EXPECT_GT(l1.g, l0.g + 25);

  // Far corners are untouched.
  for (auto [x, y] : {std::pair{0, 0}, {148, 0}, {0, 108}, {148, 108}})
    EXPECT_TRUE(same_block(a, b, 160, x, y, 12)) << "corner " << x << "," << y;

  // The samples are still drawn on top: the filled (red) one at S(0.8, 0.5).
  const glm::dvec3 red = cam.project(scene.objects()[0].placement->contact_points[2]);
  const Rgba rp = pixel(b, 160, int(red.x), int(red.y));
  EXPECT_TRUE(rp.r > 150 && rp.g < 120) << rp.r << " " << rp.g << " " << rp.b;

  // A larger picture to look at.
  const core::Camera big = oblique_camera(960, 720);
  on.selected = "placed";
  core::write_image_rgba8(TRISPLINE_BINARY_DIR "/gpu_contact_surface.png", 960, 720, render(r, scene, big, on));
}

TEST_F(GlTest, ContactSurfaceIsCachedPerFfdBinding) {
  core::Scene scene = placed_scene(sheet_binding());
  ViewOptions opt;
  opt.show_contact_surface = true;
  Renderer r;
  render(r, scene, oblique_camera(), opt);
  EXPECT_EQ(r.last_stats().contact_uploads, 1);
  EXPECT_EQ(r.last_stats().cached_contact_surfaces, 1);
  const std::vector<unsigned char> first = render(r, scene, oblique_camera(), opt);
  EXPECT_EQ(r.last_stats().contact_uploads, 0);

  core::SceneObject o = scene.objects()[0];
  o.ffd = sheet_binding(-0.4);  // a new binding (bent the other way)
  scene.replace(o);
  const std::vector<unsigned char> bent = render(r, scene, oblique_camera(), opt);
  EXPECT_EQ(r.last_stats().contact_uploads, 1);
  EXPECT_EQ(r.last_stats().cached_contact_surfaces, 1);  // the old one was released
  EXPECT_NE(bent, first);

  opt.style.contact_cells_u = 12;  // new tessellation settings rebuild
  render(r, scene, oblique_camera(), opt);
  EXPECT_EQ(r.last_stats().contact_uploads, 1);

  scene.clear();
  render(r, scene, oblique_camera(), opt);
  EXPECT_EQ(r.last_stats().cached_contact_surfaces, 0);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace trispline::gpu::test
