// display: two materials (cut surfaces in SceneObject::inside_color, flat-shaded), DFFD lattices with their
// discontinuity planes F⁻ / F⁺ and fold-over points, and the incision tool's preview (generator curve, mesh).
#include <epoxy/gl.h>

#include <cstdint>

#include "core/dffd/dffd.h"
#include "core/dffd/dffd_rig.h"
#include "gl_test.h"
#include "gpu/eval/ffd_gl.h"

namespace trispline::gpu::test {
namespace {

int count_if(const std::vector<unsigned char>& img, int w, int h, const auto& pred) {
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) n += pred(pixel(img, w, x, y)) ? 1 : 0;
  return n;
}

// Clearly green (the inside colour used below): g > 90 and g > 2·r and g > 2·b.
bool greenish(const Rgba& p) { return p.g > 90 && p.g > 2 * p.r && p.g > 2 * p.b; }

constexpr glm::vec3 kBlue{0.05f, 0.1f, 0.8f};
constexpr glm::vec3 kGreen{0.05f, 0.8f, 0.05f};

// Unit sphere with the triangles facing the camera (centroid z > 0.6) marked as inside material.
core::TriMesh sphere_with_front_cap() {
  core::TriMesh m = uv_sphere({0, 0, 0}, 1.0, 40, 20);
  m.face_material.resize(m.triangle_count(), core::kMaterialSurface);
  for (std::size_t f = 0; f < m.triangle_count(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    if ((m.positions[t.x].z + m.positions[t.y].z + m.positions[t.z].z) / 3.0 > 0.6)
      m.face_material[f] = core::kMaterialInside;
  }
  return m;
}

core::SceneObject two_material_object(core::TriMesh mesh) {
  core::SceneObject o = make_object("cut", std::move(mesh), kBlue);
  o.inside_color = kGreen;
  return o;
}

// Identity lattice of `e`'s box (control points at E⁻¹ of the Greville abscissae), clamped, order 3, 4 controls.
core::TrivariateBSpline<glm::dvec3> identity_lattice(const core::Embedding& e) {
  const core::KnotVector k = core::KnotVector::clamped_uniform(3, 4);
  const auto g = k.greville();
  const glm::dmat3 inv = glm::inverse(e.linear);
  std::vector<glm::dvec3> cps;
  for (double w : g)
    for (double v : g)
      for (double u : g) cps.push_back(inv * (glm::dvec3(u, v, w) - e.offset));
  return core::TrivariateBSpline<glm::dvec3>(k, k, k, std::move(cps));
}

// A sphere of radius 0.6 cut at u = 0.5 (x = 0) by a DFFD whose F⁻ / F⁺ planes are opened by ∓`open` along x;
// one fold point at (0, 0.9, 0.9).
core::SceneObject dffd_ball(core::DffdOpenings openings = core::DffdOpenings::open, double open = 0.25) {
  core::SceneObject o = make_object("split", uv_sphere({0, 0, 0}, 0.6, 40, 20), {0.5f, 0.5f, 0.5f});
  const std::vector<glm::dvec3> rest = o.world_rest_mesh().positions;
  const core::Embedding e = core::embed_bounding_box(rest, {0, 1});
  core::TrivariateBSpline<glm::dvec3> F = identity_lattice(e);
  const core::Discontinuity d = core::insert_discontinuity(F, 0, 0.5);
  core::open_discontinuity(F, d, {-open, 0, 0}, {open, 0, 0});
  o.dffd = std::make_shared<const core::DffdRig>(
      core::DffdRig{std::move(F), e, core::embed_points(e, rest), {d}, openings, 1e-6, true, {}, {{0.0, 0.9, 0.9}}});
  o.refresh();
  return o;
}

// Display colours (ViewOptions defaults) of F⁻ (warm red-orange), F⁺ (cyan) and fold points (red).
bool minus_coloured(const Rgba& p) { return p.r > 200 && p.g > 70 && p.g < 150 && p.b < 90; }
bool plus_coloured(const Rgba& p) { return p.r < 90 && p.g > 180 && p.b > 200; }
bool fold_red(const Rgba& p) { return p.r > 200 && p.g < 50 && p.b < 50; }

}  // namespace

TEST_F(GlTest, MeshBuffersOrderTrianglesByMaterialStably) {
  core::TriMesh m = uv_sphere({0, 0, 0}, 1.0, 6, 3);  // 36 triangles
  m.face_material.assign(m.triangle_count(), core::kMaterialSurface);
  for (std::size_t f = 0; f < m.triangle_count(); f += 3) m.face_material[f] = core::kMaterialInside;
  MeshBuffers b;
  b.upload(m);
  ASSERT_EQ(b.triangle_count(), 36u);
  EXPECT_EQ(b.surface_range().first, 0u);
  EXPECT_EQ(b.surface_range().count, 24u);
  EXPECT_EQ(b.inside_range().first, 24u);
  EXPECT_EQ(b.inside_range().count, 12u);
  std::vector<glm::uvec3> gpu(36);
  glBindBuffer(GL_COPY_READ_BUFFER, b.index_buffer());
  glGetBufferSubData(GL_COPY_READ_BUFFER, 0, GLsizeiptr(gpu.size() * sizeof(glm::uvec3)), gpu.data());
  std::vector<glm::uvec3> expected;
  for (std::size_t f = 0; f < 36; ++f)
    if (f % 3 != 0) expected.push_back(m.triangles[f]);
  for (std::size_t f = 0; f < 36; f += 3) expected.push_back(m.triangles[f]);
  EXPECT_EQ(gpu, expected);
  // Vertices keep their order (update_vertices writes by mesh index).
  std::vector<glm::vec3> pos(b.vertex_count(), glm::vec3(2.0f));
  b.update_vertices(pos, {});
  std::vector<float> back(b.vertex_count() * 3);
  glBindBuffer(GL_COPY_READ_BUFFER, b.position_buffer());
  glGetBufferSubData(GL_COPY_READ_BUFFER, 0, GLsizeiptr(back.size() * sizeof(float)), back.data());
  EXPECT_EQ(back, std::vector<float>(back.size(), 2.0f));
  // No inside faces: the mesh's own order, an empty inside range.
  m.face_material.assign(m.triangle_count(), core::kMaterialSurface);
  b.upload(m);
  EXPECT_EQ(b.surface_range().count, 36u);
  EXPECT_EQ(b.inside_range().count, 0u);
  glBindBuffer(GL_COPY_READ_BUFFER, b.index_buffer());
  glGetBufferSubData(GL_COPY_READ_BUFFER, 0, GLsizeiptr(gpu.size() * sizeof(glm::uvec3)), gpu.data());
  EXPECT_EQ(gpu, m.triangles);
  glBindBuffer(GL_COPY_READ_BUFFER, 0);
  m.face_material.resize(5);
  EXPECT_THROW(b.upload(m), std::invalid_argument);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, InsideFacesAreDrawnInTheInsideColour) {
  Renderer r;
  ViewOptions opt;
  opt.show_grid = false;
  core::Scene scene;
  scene.insert(two_material_object(sphere_with_front_cap()));
  const std::vector<unsigned char> img = render(r, scene, front_camera(), opt);
  EXPECT_GT(count_if(img, 160, 120, greenish), 300);
  EXPECT_TRUE(greenish(pixel(img, 160, 80, 60)));  // the cap faces the camera
  // Outline and wireframe still cover the whole mesh, without GL errors.
  opt.selected = "cut";
  opt.wireframe = true;
  const auto green_dominant = [](const Rgba& p) { return p.g > p.r + 30 && p.g > p.b + 30; };  // tinted by selection
  const std::vector<unsigned char> img_sel = render(r, scene, front_camera(), opt);
  EXPECT_GT(count_if(img_sel, 160, 120, green_dominant), 300);
  EXPECT_NE(img_sel, img);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  // The same mesh without materials: surface colour only, exactly the plain mesh's picture.
  core::TriMesh plain = sphere_with_front_cap();
  plain.face_material.clear();
  core::Scene plain_scene;
  plain_scene.insert(two_material_object(plain));
  opt = ViewOptions{};
  opt.show_grid = false;
  const std::vector<unsigned char> img_plain = render(r, plain_scene, front_camera(), opt);
  EXPECT_EQ(count_if(img_plain, 160, 120, greenish), 0);
  core::TriMesh all_surface = sphere_with_front_cap();
  all_surface.face_material.assign(all_surface.triangle_count(), core::kMaterialSurface);
  core::Scene surface_scene;
  surface_scene.insert(two_material_object(all_surface));
  EXPECT_EQ(render(r, surface_scene, front_camera(), opt), img_plain);
}

// Cut surfaces share the surface's vertices and normals: the inside material is shaded with the face normal. A
// quad facing the camera whose vertex normals point sideways is dark when smooth-shaded, lit when flat.
TEST_F(GlTest, InsideFacesAreShadedWithTheirFaceNormal) {
  core::TriMesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.normals.assign(4, glm::dvec3(1, 0, 0));
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  core::SceneObject o = two_material_object(quad);
  o.color = kGreen;
  core::Scene smooth;
  smooth.insert(o);
  quad.face_material = {core::kMaterialInside, core::kMaterialInside};
  o.world_mesh = std::make_shared<const core::TriMesh>(quad);
  core::Scene flat;
  flat.insert(o);
  Renderer r;
  ViewOptions opt;
  opt.show_grid = false;
  const Rgba s = pixel(render(r, smooth, front_camera(), opt), 160, 80, 60);
  const Rgba f = pixel(render(r, flat, front_camera(), opt), 160, 80, 60);
  EXPECT_GT(f.g, s.g + 40) << "flat " << f.g << " smooth " << s.g;
}

// The GLSL vertex FFD path draws both ranges too (and every backend shows the inside colour).
TEST_F(GlTest, DeformedObjectsDrawTheirInsideFacesUnderEveryBackend) {
  core::SceneObject o = two_material_object(sphere_with_front_cap());
  const std::vector<glm::dvec3> rest = o.world_rest_mesh().positions;
  core::FfdBinding b{
      identity_lattice(core::embed_bounding_box(rest, {0, 1})), core::embed_bounding_box(rest, {0, 1}), {}};
  b.params = core::embed_points(b.embedding, rest);
  o.ffd = std::make_shared<const core::FfdBinding>(std::move(b));
  o.offset_velocity = {0.01, 0.0, 0.0};  // glsl_compute falls back to the vertex path
  o.refresh();
  core::Scene scene;
  scene.insert(o);
  for (core::FfdBackend backend : {core::FfdBackend::cpu_ref, core::FfdBackend::cpu_fast,
                                   core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex}) {
    Renderer r;
    ViewOptions opt;
    opt.show_grid = false;
    opt.ffd_backend = backend;
    opt.time_s = 0.5;
    const std::vector<unsigned char> img = render(r, scene, front_camera(), opt);
    EXPECT_GT(count_if(img, 160, 120, greenish), 300) << core::to_string(backend);
    EXPECT_EQ(r.last_stats().ffd_objects, 1);
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, DffdObjectShowsItsLatticeAndDiscontinuityPlanes) {
  const core::SceneObject o = dffd_ball();
  ASSERT_GT(o.world_mesh->vertex_count(), o.rest_mesh->vertex_count());  // split at u = 0.5
  core::Scene scene;
  scene.insert(o);
  Renderer r;
  ViewOptions opt;
  opt.show_grid = false;
  opt.style.selection_color = {0.2f, 0.2f, 1.0f};  // keep the outline out of the predicates
  const auto img_off = render(r, scene, front_camera(), opt);
  EXPECT_EQ(count_if(img_off, 160, 120, minus_coloured), 0);
  EXPECT_EQ(count_if(img_off, 160, 120, plus_coloured), 0);
  EXPECT_EQ(count_if(img_off, 160, 120, fold_red), 0);
  EXPECT_EQ(r.last_stats().ffd_objects, 0);  // world_mesh drawn as it is
  EXPECT_EQ(r.last_stats().triangles, o.world_mesh->triangle_count());

  opt.show_lattice = true;
  const auto img = render(r, scene, front_camera(), opt);
  EXPECT_GT(count_if(img, 160, 120, minus_coloured), 20);
  EXPECT_GT(count_if(img, 160, 120, plus_coloured), 20);
  EXPECT_GT(count_if(img, 160, 120, fold_red), 20);  // show_lattice shows the fold points too
  // F⁻ is drawn where its control points are (x = −0.25 after opening), F⁺ at x = +0.25: a front corner of each.
  const core::Discontinuity d = o.dffd->discontinuities[0];
  const glm::dvec3 pm = front_camera().project(o.dffd->lattice.control_point(d.minus_plane, 0, 3));
  const glm::dvec3 pp = front_camera().project(o.dffd->lattice.control_point(d.plus_plane, 0, 3));
  EXPECT_LT(pm.x, pp.x);
  EXPECT_TRUE(minus_coloured(pixel(img, 160, int(pm.x), int(pm.y))));
  EXPECT_TRUE(plus_coloured(pixel(img, 160, int(pp.x), int(pp.y))));

  opt.show_discontinuities = false;  // the lattice alone
  const auto img_lattice = render(r, scene, front_camera(), opt);
  EXPECT_EQ(count_if(img_lattice, 160, 120, minus_coloured), 0);
  EXPECT_EQ(count_if(img_lattice, 160, 120, plus_coloured), 0);
  EXPECT_NE(img_lattice, img_off);

  // Selected without show_lattice: its discontinuity planes and fold points.
  opt.show_lattice = false;
  opt.show_discontinuities = true;
  opt.selected = "split";
  const auto img_sel = render(r, scene, front_camera(), opt);
  EXPECT_GT(count_if(img_sel, 160, 120, minus_coloured), 20);
  EXPECT_GT(count_if(img_sel, 160, 120, plus_coloured), 20);
  const glm::dvec3 pf = front_camera().project(o.dffd->fold_points[0]);
  EXPECT_TRUE(fold_red(pixel(img_sel, 160, int(pf.x), int(pf.y))));
  EXPECT_FALSE(fold_red(pixel(img_off, 160, int(pf.x), int(pf.y))));
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, CappedDffdObjectShowsItsCapsInTheInsideColour) {
  core::SceneObject o = dffd_ball(core::DffdOpenings::cap, 0.45);
  ASSERT_TRUE(o.world_mesh->has_inside_faces());
  o.inside_color = kGreen;
  o.color = kBlue;
  core::Scene scene;
  scene.insert(o);
  core::Camera cam = front_camera();
  cam.eye = {2.5, 0.0, 3.0};  // sees into the opened gap, onto the cap of the x < 0 half
  Renderer r;
  ViewOptions opt;
  opt.show_grid = false;
  EXPECT_GT(count_if(render(r, scene, cam, opt), 160, 120, greenish), 30);
}

TEST_F(GlTest, IncisionPreviewMeshReplacesTheObjectsMesh) {
  core::Scene scene;
  scene.insert(make_object("ball", uv_sphere({-1.2, 0, 0}, 0.4), {0.8f, 0.03f, 0.02f}));
  const core::Camera cam = front_camera();
  const glm::dvec3 left = cam.project({-1.2, 0, 0}), right = cam.project({1.2, 0, 0});
  Renderer r;
  ViewOptions opt;
  opt.show_grid = false;
  auto img = render(r, scene, cam, opt);
  EXPECT_TRUE(reddish(pixel(img, 160, int(left.x), int(left.y))));
  EXPECT_FALSE(reddish(pixel(img, 160, int(right.x), int(right.y))));

  opt.overlays.meshes.push_back({"ball", std::make_shared<const core::TriMesh>(uv_sphere({1.2, 0, 0}, 0.4))});
  img = render(r, scene, cam, opt);
  EXPECT_FALSE(reddish(pixel(img, 160, int(left.x), int(left.y))));
  EXPECT_TRUE(reddish(pixel(img, 160, int(right.x), int(right.y))));
  EXPECT_EQ(r.last_stats().uploads, 1);
  render(r, scene, cam, opt);
  EXPECT_EQ(r.last_stats().uploads, 0);  // the preview stays cached while it is shown
  EXPECT_EQ(r.last_stats().cached_meshes, 2);
  opt.overlays.meshes[0].object = "other";  // names no object: nothing replaced
  img = render(r, scene, cam, opt);
  EXPECT_TRUE(reddish(pixel(img, 160, int(left.x), int(left.y))));

  // The generator curve: a bright line on top of the object, where its points project.
  opt = ViewOptions{};
  opt.show_grid = false;
  opt.overlays.curves.push_back({{{-1.6, 0.0, 0.5}, {-0.8, 0.0, 0.5}}, {0.4f, 1.0f, 0.3f, 1.0f}, 3.0f});
  img = render(r, scene, cam, opt);
  const glm::dvec3 mid = cam.project({-1.2, 0.0, 0.5});
  const Rgba c = pixel(img, 160, int(mid.x), int(mid.y));
  EXPECT_TRUE(c.g > 200 && c.r > 70 && c.r < 140 && c.b < 110) << c.r << " " << c.g << " " << c.b;
  EXPECT_EQ(r.last_stats().cached_meshes, 1);

  // The preview's cut lattice: its F⁻ / F⁺ planes (the C⁻¹ break at u = 1/2) where their points project; off
  // with show_discontinuities, and nothing without a lattice.
  opt = ViewOptions{};
  opt.show_grid = false;
  const auto none = render(r, scene, cam, opt);
  core::TrivariateBSpline<glm::dvec3> cut(core::KnotVector::clamped_uniform(3, 4),
                                          core::KnotVector::clamped_uniform(2, 2),
                                          core::KnotVector::clamped_uniform(2, 2), std::vector<glm::dvec3>(16));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) cut.control_point(i, j, k) = {0.3 + 0.2 * i, -0.3 + 0.6 * j, -0.3 + 0.6 * k};
  const core::Discontinuity d = core::insert_discontinuity(cut, 0, 0.5);  // order (3) knots at u = 1/2
  gpu::LatticeOverlay overlay;
  overlay.lattice = std::make_shared<const core::TrivariateBSpline<glm::dvec3>>(cut);
  overlay.discontinuities = {d};
  opt.overlays.lattices.push_back(overlay);
  img = render(r, scene, cam, opt);
  const long red_ball = count_if(none, 160, 120, minus_coloured);  // the red ball's highlights match too
  EXPECT_GT(count_if(img, 160, 120, minus_coloured), red_ball + 10);
  EXPECT_GT(count_if(img, 160, 120, plus_coloured), count_if(none, 160, 120, plus_coloured) + 10);
  const glm::dvec3 pp = cam.project(cut.control_point(d.plus_plane, 1, 1));
  EXPECT_TRUE(plus_coloured(pixel(img, 160, int(pp.x), int(pp.y))));
  opt.show_discontinuities = false;
  img = render(r, scene, cam, opt);
  EXPECT_LE(count_if(img, 160, 120, minus_coloured), red_ball);
  EXPECT_NE(img, none) << "the lattice net is still drawn";
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace trispline::gpu::test
