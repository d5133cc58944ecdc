// Material shading (ViewOptions::shading, gpu/render/material_textures.h) against Solid on llvmpipe: a textured quad
// shows its texture's colours, an alpha-MASK cut-out shows the background, BLEND mixes with what is behind, an
// unreadable image shows the magenta placeholder, textures follow the FFD on every backend; and the selection outline
// stays a ring round the selected object's visible silhouette (objects in front of it keep their colour).
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

#include "core/ffd/ffd.h"
#include "gl_test.h"
#include "gpu/render/material_textures.h"

namespace trispline::gpu::test {
namespace {

using core::AlphaMode;

// An n×n RGBA image, `color(x, y)` per pixel (rows top to bottom).
template <class F>
std::shared_ptr<core::MaterialImage> image(int n, F color) {
  auto im = std::make_shared<core::MaterialImage>();
  im->name = "generated";
  im->width = im->height = n;
  im->rgba8.resize(std::size_t(n) * std::size_t(n) * 4);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::u8vec4 c = color(x, y);
      for (int k = 0; k < 4; ++k)
        im->rgba8[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4 + std::size_t(k)] = c[k];
    }
  return im;
}

// Quadrants: top-left red, top-right green, bottom-left blue, bottom-right yellow; alpha 0 in the left half when
// `cut_left`.
std::shared_ptr<core::MaterialImage> quadrants(bool cut_left = false) {
  return image(4, [&](int x, int y) {
    const glm::u8vec4 c = y < 2 ? (x < 2 ? glm::u8vec4(230, 20, 20, 255) : glm::u8vec4(20, 210, 20, 255))
                                : (x < 2 ? glm::u8vec4(20, 40, 230, 255) : glm::u8vec4(230, 210, 20, 255));
    return cut_left && x < 2 ? glm::u8vec4(c.x, c.y, c.z, 0) : c;
  });
}

// A dielectric material sampling image 0 with nearest filtering.
core::Material textured(AlphaMode mode = AlphaMode::Opaque) {
  core::Material m;
  m.name = "checker";
  m.metallic = 0.0;
  m.roughness = 0.6;
  m.base_color_texture.image = 0;
  m.base_color_texture.sampler.mag_filter = core::TextureFilter::Nearest;
  m.base_color_texture.sampler.min_filter = core::TextureFilter::Nearest;
  m.alpha_mode = mode;
  return m;
}

// The square [-s, s]² at depth z facing +z (the camera), glTF uvs ((0,0) at its top-left corner).
core::TriMesh quad(double s = 1.0, double z = 0.0) {
  core::TriMesh m;
  m.positions = {{-s, -s, z}, {s, -s, z}, {s, s, z}, {-s, s, z}};
  m.normals.assign(4, {0, 0, 1});
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

core::SceneObject with_material(core::SceneObject o, const core::Material& m,
                                std::shared_ptr<const core::MaterialImage> im) {
  auto set = std::make_shared<core::MaterialSet>();
  set->materials.push_back(m);
  set->images.push_back(std::move(im));
  o.materials = set;
  return o;
}

ViewOptions shading(Shading s) {
  ViewOptions o;
  o.show_grid = false;
  o.shading = s;
  return o;
}

bool dominant(const Rgba& p, int channel) {
  const int c[3] = {p.r, p.g, p.b};
  for (int k = 0; k < 3; ++k)
    if (k != channel && c[channel] < c[k] + 60) return false;
  return true;
}
bool red(const Rgba& p) { return dominant(p, 0); }
bool green(const Rgba& p) { return dominant(p, 1); }
bool blue(const Rgba& p) { return dominant(p, 2); }
bool yellow(const Rgba& p) { return p.r > p.b + 60 && p.g > p.b + 60; }
bool magenta(const Rgba& p) { return p.r > p.g + 80 && p.b > p.g + 80; }
bool grey(const Rgba& p) { return std::abs(p.r - p.g) < 10 && std::abs(p.g - p.b) < 14 && p.r < 90; }
bool orange(const Rgba& p) { return p.r > 200 && p.g > 120 && p.g < 190 && p.b < 90; }

int count(const std::vector<unsigned char>& img, int w, int h, bool (*pred)(const Rgba&)) {
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) n += pred(pixel(img, w, x, y)) ? 1 : 0;
  return n;
}

}  // namespace

// The quad spans about x, y ∈ [44, 116] px; quadrant centres at (62|98, 42|78).
TEST_F(GlTest, MaterialShadingShowsTheTextureAndSolidTheObjectColour) {
  core::Scene scene;
  scene.insert(with_material(make_object("quad", quad(), {0.5f, 0.5f, 0.5f}), textured(), quadrants()));
  EXPECT_TRUE(material_shading(scene, Shading::automatic));
  EXPECT_FALSE(material_shading(scene, Shading::solid));
  Renderer r;
  const std::vector<unsigned char> mat = render(r, scene, front_camera(), shading(Shading::material));
  EXPECT_TRUE(red(pixel(mat, 160, 62, 42)));
  EXPECT_TRUE(green(pixel(mat, 160, 98, 42)));
  EXPECT_TRUE(blue(pixel(mat, 160, 62, 78)));
  EXPECT_TRUE(yellow(pixel(mat, 160, 98, 78)));
  const std::vector<unsigned char> solid = render(r, scene, front_camera(), shading(Shading::solid));
  for (const glm::ivec2 at : {glm::ivec2(62, 42), glm::ivec2(98, 42), glm::ivec2(62, 78), glm::ivec2(98, 78)}) {
    const Rgba p = pixel(solid, 160, at.x, at.y);
    EXPECT_FALSE(red(p) || green(p) || blue(p) || yellow(p)) << at.x << "," << at.y;
    EXPECT_LT(std::abs(p.r - p.g) + std::abs(p.g - p.b), 24) << at.x << "," << at.y;  // the grey object colour
  }
  // Automatic picks Material for a textured scene.
  EXPECT_EQ(render(r, scene, front_camera(), shading(Shading::automatic)), mat);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, MaterialAlphaMaskCutsOutAndBlendMixes) {
  Renderer r;
  core::Scene masked;
  core::Material mask = textured(AlphaMode::Mask);
  masked.insert(with_material(make_object("leaf", quad(), {0.1f, 0.6f, 0.1f}), mask, quadrants(true)));
  const std::vector<unsigned char> cut = render(r, masked, front_camera(), shading(Shading::material));
  EXPECT_TRUE(grey(pixel(cut, 160, 62, 42))) << "left half is cut out";
  EXPECT_TRUE(grey(pixel(cut, 160, 62, 78)));
  EXPECT_TRUE(green(pixel(cut, 160, 98, 42)));
  EXPECT_TRUE(yellow(pixel(cut, 160, 98, 78)));
  const std::vector<unsigned char> solid = render(r, masked, front_camera(), shading(Shading::solid));
  EXPECT_TRUE(green(pixel(solid, 160, 62, 42))) << "Solid ignores alpha";

  // BLEND: a half-transparent red sheet in front of a blue quad shows both.
  core::Scene blended;
  core::Material sheet;
  sheet.metallic = 0.0;
  sheet.base_color = {1.0, 0.0, 0.0, 0.5};
  sheet.alpha_mode = AlphaMode::Blend;
  sheet.double_sided = true;
  auto set = std::make_shared<core::MaterialSet>();
  set->materials.push_back(sheet);
  core::SceneObject front = make_object("sheet", quad(0.6, 1.0), {0.5f, 0.5f, 0.5f});
  front.materials = set;
  blended.insert(std::move(front));
  blended.insert(make_object("back", quad(1.0, 0.0), {0.05f, 0.1f, 0.9f}));
  const std::vector<unsigned char> mix = render(r, blended, front_camera(), shading(Shading::material));
  const Rgba c = pixel(mix, 160, 80, 60);
  EXPECT_GT(c.r, 110) << c.r << " " << c.g << " " << c.b;
  EXPECT_GT(c.b, 110) << c.r << " " << c.g << " " << c.b;
  EXPECT_LT(c.g, std::min(c.r, c.b) - 20);
  EXPECT_TRUE(blue(pixel(mix, 160, 47, 60))) << "outside the sheet";
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, UnreadableTextureShowsTheMagentaPlaceholder) {
  auto missing = std::make_shared<core::MaterialImage>();
  missing->uri = "textures/missing.png";
  missing->error = "cannot open textures/missing.png";
  core::Scene scene;
  scene.insert(with_material(make_object("quad", quad(), {0.5f, 0.5f, 0.5f}), textured(), missing));
  Renderer r;
  const std::vector<unsigned char> img = render(r, scene, front_camera(), shading(Shading::material));
  for (const glm::ivec2 at : {glm::ivec2(62, 42), glm::ivec2(98, 78), glm::ivec2(80, 60)})
    EXPECT_TRUE(magenta(pixel(img, 160, at.x, at.y))) << at.x << "," << at.y;
  EXPECT_EQ(count(render(r, scene, front_camera(), shading(Shading::solid)), 160, 120, magenta), 0);
}

// One object, three slots: the per-material ranges each draw their own material; cut surfaces the inside colour.
TEST_F(GlTest, EachMaterialSlotDrawsItsOwnMaterial) {
  core::TriMesh m = quad();
  // Split into left and right halves of two triangles each, plus a kMaterialInside strip at the bottom.
  m.positions = {{-1, -1, 0}, {0, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {0, 1, 0}, {1, 1, 0}, {-1, -1.4, 0}, {1, -1.4, 0}};
  m.normals.assign(8, {0, 0, 1});
  m.uvs.assign(8, {0.5, 0.5});
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {6, 7, 2}, {6, 2, 0}};
  m.face_material = {1, 1, 0, 0, core::kMaterialInside, core::kMaterialInside};
  core::SceneObject o = make_object("two", m, {0.5f, 0.5f, 0.5f});
  o.inside_color = {0.9f, 0.8f, 0.1f};
  auto set = std::make_shared<core::MaterialSet>();
  core::Material left, right;
  left.metallic = right.metallic = 0.0;
  right.base_color = {0.9, 0.05, 0.05, 1.0};
  left.base_color = {0.05, 0.05, 0.9, 1.0};
  set->materials = {right, left};
  o.materials = set;
  core::Scene scene;
  scene.insert(std::move(o));
  Renderer r;
  const std::vector<unsigned char> img = render(r, scene, front_camera(), shading(Shading::material));
  EXPECT_TRUE(blue(pixel(img, 160, 62, 60)));
  EXPECT_TRUE(red(pixel(img, 160, 98, 60)));
  EXPECT_TRUE(yellow(pixel(img, 160, 80, 100))) << "the cut surface in the inside colour";
}

// A textured sphere bent by an FFD: every backend shows the texture (uvs ride along) and the same picture.
TEST_F(GlTest, TexturesFollowTheFfdOnEveryBackend) {
  core::TriMesh ball = uv_sphere({0, 0, 0}, 0.8, 40, 20);
  for (const glm::dvec3& p : ball.positions)
    ball.uvs.push_back({std::atan2(p.z, p.x) / (2.0 * M_PI) + 0.5, std::acos(std::clamp(p.y / 0.8, -1.0, 1.0)) / M_PI});
  // Four vertical stripes over u: red, green, blue, yellow; the front (z > 0) shows blue (x > 0) and yellow.
  const auto stripes = image(8, [](int x, int) {
    const glm::u8vec4 c[4] = {{230, 20, 20, 255}, {20, 210, 20, 255}, {20, 40, 230, 255}, {230, 210, 20, 255}};
    return c[x / 2];
  });
  core::SceneObject o = with_material(make_object("blob", ball, {0.5f, 0.5f, 0.5f}), textured(), stripes);
  const std::vector<glm::dvec3> rest = o.world_rest_mesh().positions;
  core::FfdBinding b{core::TrivariateBSpline<glm::dvec3>(
                         core::KnotVector::clamped_uniform(3, 4), core::KnotVector::clamped_uniform(3, 4),
                         core::KnotVector::clamped_uniform(3, 4), std::vector<glm::dvec3>(64)),
                     core::embed_bounding_box(rest, {0, 1}),
                     {}};
  b.params = core::embed_points(b.embedding, rest);
  const glm::dmat3 inv = glm::inverse(b.embedding.linear);
  const auto g = b.lattice.knots(0).greville();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        glm::dvec3 p = inv * (glm::dvec3(g[i], g[j], g[k]) - b.embedding.offset);
        p.x += 0.5 * (g[j] - 0.5);  // shear sideways with height
        b.lattice.control_point(i, j, k) = p;
      }
  o.ffd = std::make_shared<const core::FfdBinding>(std::move(b));
  o.refresh();
  ASSERT_EQ(o.world_mesh->uvs.size(), o.world_mesh->positions.size()) << "the CPU reference keeps the uvs";
  core::Scene scene;
  scene.insert(std::move(o));
  Renderer r;
  std::vector<unsigned char> reference;
  for (const core::FfdBackend backend : {core::FfdBackend::cpu_ref, core::FfdBackend::cpu_fast,
                                         core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex}) {
    ViewOptions opt = shading(Shading::material);
    opt.ffd_backend = backend;
    const std::vector<unsigned char> img = render(r, scene, front_camera(), opt);
    EXPECT_GT(count(img, 160, 120, blue), 150) << int(backend);
    EXPECT_GT(count(img, 160, 120, yellow), 150) << int(backend);
    if (reference.empty()) {
      reference = img;
      continue;
    }
    int differing = 0;
    for (std::size_t i = 0; i < img.size(); i += 4)
      differing += std::abs(int(img[i]) - int(reference[i])) + std::abs(int(img[i + 2]) - int(reference[i + 2])) > 60;
    EXPECT_LT(differing, 40) << int(backend);
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The selected ball is behind a blue ball that overlaps it: the outline rings the selected ball's visible silhouette
// and never paints the ball in front (the old x-ray outline filled it orange wherever it covered the selection).
TEST_F(GlTest, SelectionOutlineLeavesObjectsInFrontUnpainted) {
  core::Scene scene;
  scene.insert(make_object("back", uv_sphere({0, 0, 0}, 1.0), {0.8f, 0.03f, 0.02f}));
  scene.insert(make_object("front", uv_sphere({0.6, 0, 1.5}, 0.5), {0.05f, 0.15f, 0.85f}));
  Renderer r;
  ViewOptions opt = shading(Shading::solid);
  const std::vector<unsigned char> plain = render(r, scene, front_camera(), opt);
  opt.selected = "back";
  const std::vector<unsigned char> selected = render(r, scene, front_camera(), opt);
  EXPECT_GT(count(selected, 160, 120, orange), 150) << "an outline is drawn";
  // The front ball's disk: centre ≈ (115, 60), radius ≈ 29 px. Its pixels well inside are unchanged.
  int inside = 0, painted = 0, changed = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      if (std::hypot(x - 115.0, y - 60.0) > 24.0) continue;
      ++inside;
      painted += orange(pixel(selected, 160, x, y)) ? 1 : 0;
      const Rgba a = pixel(selected, 160, x, y), b = pixel(plain, 160, x, y);
      changed += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b) > 6 ? 1 : 0;
    }
  EXPECT_GT(inside, 1500);
  EXPECT_EQ(painted, 0);
  EXPECT_EQ(changed, 0);
  EXPECT_TRUE(blue(pixel(selected, 160, 100, 60)));  // over the selected ball's silhouette area

  // Material shading with a MASK cut-out: the outline does not fill the selected leaf's holes.
  core::Scene leaf;
  leaf.insert(
      with_material(make_object("leaf", quad(), {0.1f, 0.6f, 0.1f}), textured(AlphaMode::Mask), quadrants(true)));
  ViewOptions lo = shading(Shading::material);
  lo.selected = "leaf";
  const std::vector<unsigned char> img = render(r, leaf, front_camera(), lo);
  EXPECT_TRUE(grey(pixel(img, 160, 62, 42)));
  EXPECT_TRUE(grey(pixel(img, 160, 62, 78)));
  EXPECT_GT(count(img, 160, 120, orange), 60);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The texture cache keys on the image's identity and drops images no object uses.
TEST_F(GlTest, MaterialTexturesAreCachedPerImage) {
  MaterialTextures t;
  const std::shared_ptr<const core::MaterialImage> a = quadrants();
  const GLuint first = t.texture(a, TextureColorSpace::srgb);
  EXPECT_NE(first, 0u);
  EXPECT_EQ(t.texture(a, TextureColorSpace::srgb), first);
  EXPECT_NE(t.texture(a, TextureColorSpace::linear), first);
  EXPECT_EQ(t.uploads(), 2);
  EXPECT_EQ(t.texture(nullptr, TextureColorSpace::srgb), t.placeholder());
  t.release_unused(core::Scene{});
  EXPECT_EQ(t.cached(), 0u);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace trispline::gpu::test
