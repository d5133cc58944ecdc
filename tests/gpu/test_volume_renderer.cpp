// Volumes in gpu::Renderer (gpu/render/renderer_volume.h) on llvmpipe: an analytic torus volume
// (core::make_analytic_volume) drawn offscreen covers exactly the pixels the CPU reference core::render_iso_hits_cpu
// hits (but for a band on its outline), combines by depth with meshes in front of and behind it, follows a live
// iso-level, keeps its ray caster and its layer between frames (a frame whose view did not change casts nothing),
// refines a budgeted preview into the same image as a whole cast; its silhouettes (core::extract_silhouettes for the
// camera) show as line pixels on the outline in the plain and hue styles. The CPU stroke geometry
// (gpu/view/silhouette_strokes.h) is checked without GL.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/volume/analytic_volumes.h"
#include "core/volume/iso_raycast.h"
#include "core/volume/silhouettes.h"
#include "gl_test.h"
#include "gpu/view/silhouette_strokes.h"

namespace trispline::gpu::test {
namespace {

constexpr int kW = 128, kH = 96;

core::VolumeObject torus_object() {
  static const auto spline =
      std::make_shared<const core::VolumeSpline>(core::make_analytic_volume(core::AnalyticVolume::torus, 36), 4);
  static const auto table = std::make_shared<const core::SingletonTable>(core::build_singleton_table(*spline));
  core::VolumeObject v;
  v.name = "torus";
  v.source = "analytic:torus";
  v.spline = spline;
  v.table = table;
  v.iso = 0.0;  // the torus of major radius 28 mm, minor 12 mm about z
  return v;
}

core::Camera torus_camera() {
  core::Camera c;
  c.eye = {0.0, -110.0, 70.0};  // oblique: the hole and both sides of the tube show
  c.target = {0.0, 0.0, 0.0};
  c.up = {0.0, 0.0, 1.0};
  c.fov_deg = 40.0;
  c.viewport = {kW, kH};
  c.near_plane = 1.0;
  c.far_plane = 400.0;
  return c;
}

core::Scene scene_with(const core::VolumeObject& v) {
  core::Scene s;
  s.insert_volume(v);
  return s;
}

ViewOptions plain_view() {
  ViewOptions o;
  o.show_grid = false;
  return o;
}

// RGBA of a single-sample offscreen frame, top row first.
std::vector<unsigned char> draw(Renderer& r, const core::Scene& s, const core::Camera& c, const ViewOptions& o) {
  OffscreenTarget target(c.viewport.x, c.viewport.y, 1);
  target.bind();
  r.draw(s, c, o);
  return target.read_rgba();
}

bool differs(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, std::size_t px) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(a[4 * px + c]) - int(b[4 * px + c])) > 6) return true;
  return false;
}

// CPU hit mask in the image's row order (top row first).
std::vector<char> cpu_mask(const core::VolumeObject& v, double iso, const core::Camera& c) {
  const core::VolumeRangeGrid grid = core::build_volume_range_grid(*v.spline);
  const core::IsoHitImage img =
      core::render_iso_hits_cpu(*v.spline, iso, c.view_matrix(), c.projection_matrix(), kW, kH, 0.25, &grid);
  std::vector<char> mask(std::size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) mask[std::size_t(kH - 1 - y) * kW + x] = img.hits[std::size_t(y) * kW + x].hit;
  return mask;
}

// A pixel whose 3×3 neighbourhood holds both values of the mask (the outline band).
bool on_edge(const std::vector<char>& mask, int x, int y) {
  const char m = mask[std::size_t(y) * kW + x];
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = std::clamp(x + dx, 0, kW - 1), w = std::clamp(y + dy, 0, kH - 1);
      if (mask[std::size_t(w) * kW + u] != m) return true;
    }
  return false;
}

class VolumeRendererTest : public GlTest {};

TEST_F(VolumeRendererTest, SurfacePixelsAreWhereTheCpuReferenceHits) {
  Renderer renderer;
  const core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  const auto empty = draw(renderer, core::Scene{}, cam, plain_view());
  const auto image = draw(renderer, scene_with(v), cam, plain_view());
  EXPECT_EQ(renderer.last_stats().volumes_drawn, 1);
  const std::vector<char> mask = cpu_mask(v, v.iso, cam);
  std::size_t hits = 0, covered = 0, off_edge_mismatch = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = std::size_t(y) * kW + x;
      const bool cov = differs(image, empty, i);
      hits += mask[i];
      covered += cov;
      if (cov != bool(mask[i]) && !on_edge(mask, x, y)) ++off_edge_mismatch;
    }
  EXPECT_GT(hits, std::size_t(kW * kH / 8)) << "the torus fills a good part of the image";
  EXPECT_EQ(off_edge_mismatch, 0u) << "covered pixels differ from the CPU hits away from the outline";
  EXPECT_NEAR(double(covered), double(hits), 0.05 * double(hits));
  // Through the hole: the image centre shows the background on both.
  EXPECT_FALSE(mask[std::size_t(kH / 2) * kW + kW / 2]);
  EXPECT_FALSE(differs(image, empty, std::size_t(kH / 2) * kW + kW / 2));
}

TEST_F(VolumeRendererTest, DepthCombinesWithMeshesInFrontAndBehind) {
  Renderer renderer;
  const core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  core::Scene s = scene_with(v);
  // Behind the torus, on the ray through the hole (63 mm from the tube), and in front of its near side.
  s.insert(make_object("behind", uv_sphere({0.0, 126.6, -80.6}, 55.0), {0.9f, 0.05f, 0.05f}));
  s.insert(make_object("front", uv_sphere({0.0, -40.0, 8.0}, 6.0), {0.9f, 0.05f, 0.05f}));
  const auto image = draw(renderer, s, cam, plain_view());
  const std::vector<char> mask = cpu_mask(v, v.iso, cam);
  const glm::dvec3 front_px = cam.project({0.0, -40.0, 8.0});
  const int fx = int(front_px.x), fy = int(front_px.y);
  ASSERT_TRUE(mask[std::size_t(fy) * kW + fx]) << "the front sphere's centre pixel also sees the torus behind it";
  EXPECT_TRUE(reddish(pixel(image, kW, fx, fy))) << "a mesh in front of the volume hides it";
  std::size_t torus_px = 0, red_over_torus = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!mask[std::size_t(y) * kW + x] || on_edge(mask, x, y)) continue;
      if (std::hypot(x - front_px.x, y - front_px.y) < 12.0) continue;  // the front sphere's disc
      ++torus_px;
      red_over_torus += reddish(pixel(image, kW, x, y));
    }
  EXPECT_GT(torus_px, std::size_t(500));
  EXPECT_EQ(red_over_torus, 0u) << "the volume hides the mesh behind it";
  const Rgba hole = pixel(image, kW, kW / 2, kH / 2);
  EXPECT_TRUE(reddish(hole)) << "the mesh behind shows through the hole";
}

TEST_F(VolumeRendererTest, RayCasterAndLayerAreKeptBetweenFrames) {
  Renderer renderer;
  core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  OffscreenTarget target(kW, kH, 1);
  target.bind();
  renderer.draw(scene_with(v), cam, plain_view());
  EXPECT_EQ(renderer.last_stats().volume_uploads, 1);
  EXPECT_EQ(renderer.last_stats().volume_cast_pixels, std::size_t(kW * kH));
  const auto first = target.read_rgba();
  target.bind();
  renderer.draw(scene_with(v), cam, plain_view());
  EXPECT_EQ(renderer.last_stats().volume_uploads, 0);
  EXPECT_EQ(renderer.last_stats().volume_cast_pixels, 0u) << "same view and volume: the layer is only composited";
  EXPECT_EQ(renderer.last_stats().cached_volumes, 1);
  EXPECT_EQ(target.read_rgba(), first);
  // Another level: cast again, no upload; another spline: one upload, the old ray caster dropped.
  v.iso = 4.0;
  target.bind();
  renderer.draw(scene_with(v), cam, plain_view());
  EXPECT_EQ(renderer.last_stats().volume_uploads, 0);
  EXPECT_EQ(renderer.last_stats().volume_cast_pixels, std::size_t(kW * kH));
  v.spline =
      std::make_shared<const core::VolumeSpline>(core::make_analytic_volume(core::AnalyticVolume::sphere, 24), 4);
  v.table = std::make_shared<const core::SingletonTable>(core::build_singleton_table(*v.spline));
  target.bind();
  renderer.draw(scene_with(v), cam, plain_view());
  EXPECT_EQ(renderer.last_stats().volume_uploads, 1);
  EXPECT_EQ(renderer.last_stats().cached_volumes, 1);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(VolumeRendererTest, LiveIsoLevelReplacesTheVolumesOwn) {
  Renderer renderer;
  const core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  const auto empty = draw(renderer, core::Scene{}, cam, plain_view());
  auto covered = [&](const std::vector<unsigned char>& img) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < std::size_t(kW) * kH; ++i) n += differs(img, empty, i);
    return n;
  };
  const std::size_t own = covered(draw(renderer, scene_with(v), cam, plain_view()));
  ViewOptions thin = plain_view();
  thin.overlays.volumes_in_place.push_back({"torus", 6.0, nullptr});  // D = 6: a tube of radius 6 mm
  const std::size_t live = covered(draw(renderer, scene_with(v), cam, thin));
  core::VolumeObject thin_volume = v;
  thin_volume.iso = 6.0;
  const std::size_t stored = covered(draw(renderer, scene_with(thin_volume), cam, plain_view()));
  EXPECT_LT(live, own * 3 / 4) << "a thinner tube covers fewer pixels";
  EXPECT_EQ(live, stored) << "the live level draws as the level itself would";
}

TEST_F(VolumeRendererTest, BudgetedPreviewRefinesIntoTheWholeCast) {
  Renderer renderer;
  const core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  const auto whole = draw(renderer, scene_with(v), cam, plain_view());
  Renderer budgeted;
  ViewOptions o = plain_view();
  o.volume_budget_ms = 1e-6;  // every cast "too long": a preview, then bands of at least 16 rows
  OffscreenTarget target(kW, kH, 1);
  target.bind();
  budgeted.draw(scene_with(v), cam, o);
  EXPECT_TRUE(budgeted.last_stats().volume_refining);
  EXPECT_LT(budgeted.last_stats().volume_scale, 1.0f);
  EXPECT_LT(budgeted.last_stats().volume_cast_pixels, std::size_t(kW * kH / 4));
  int frames = 1;
  while (budgeted.last_stats().volume_refining && frames < 50) {
    target.bind();
    budgeted.draw(scene_with(v), cam, o);
    ++frames;
  }
  EXPECT_FALSE(budgeted.last_stats().volume_refining);
  EXPECT_GE(frames, 1 + kH / 16) << "refined band by band";
  EXPECT_EQ(target.read_rgba(), whole) << "the refined layer is the whole cast, pixel for pixel";
}

TEST_F(VolumeRendererTest, SilhouettesShowAsLinesOnTheOutline) {
  Renderer renderer;
  core::VolumeObject v = torus_object();
  const core::Camera cam = torus_camera();
  const auto surface = draw(renderer, scene_with(v), cam, plain_view());
  v.silhouette.enabled = true;
  v.silhouette.style = "plain";
  v.silhouette.hidden = "remove";
  v.silhouettes = std::make_shared<const core::SilhouetteResult>(
      core::extract_silhouettes(*v.spline, *v.table, v.iso, v.silhouette_view(cam)));
  v.silhouette_camera = cam;
  ASSERT_GT(v.silhouettes->points, std::size_t(50));
  const auto lined = draw(renderer, scene_with(v), cam, plain_view());
  EXPECT_GT(renderer.last_stats().silhouette_points, std::size_t(0));
  // Dark pixels near every visible silhouette point (plain black strokes over a light surface or the background).
  auto dark = [](const Rgba& p) { return p.r < 40 && p.g < 40 && p.b < 40; };
  std::size_t visible = 0, found = 0, dark_px = 0;
  for (const core::SilhouettePolyline& pl : v.silhouettes->polylines)
    for (std::size_t k = 0; k < pl.points.size(); ++k) {
      if (!pl.visible[k]) continue;
      const glm::dvec3 p = cam.project(pl.points[k]);
      if (p.x < 2 || p.y < 2 || p.x > kW - 3 || p.y > kH - 3) continue;
      ++visible;
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dx = -1; dx <= 1 && !near; ++dx) near = dark(pixel(lined, kW, int(p.x) + dx, int(p.y) + dy));
      found += near;
    }
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) dark_px += dark(pixel(lined, kW, x, y)) && !dark(pixel(surface, kW, x, y));
  EXPECT_GT(visible, std::size_t(50));
  EXPECT_GE(found, visible * 95 / 100) << "line pixels on the visible silhouette points";
  EXPECT_GT(dark_px, std::size_t(100));
  // Hue: |∇D| is 1 everywhere in a distance field, so the whole ramp is its middle, green.
  v.silhouette.style = "hue";
  const auto hue = draw(renderer, scene_with(v), cam, plain_view());
  std::size_t green = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Rgba p = pixel(hue, kW, x, y);
      green += p.g > 150 && p.r < 100 && p.b < 100;
    }
  EXPECT_GT(green, std::size_t(100));
  // Off: no line pixels.
  v.silhouette.enabled = false;
  EXPECT_EQ(draw(renderer, scene_with(v), cam, plain_view()), surface);
  // A live result replaces the stored one (here: none at all).
  v.silhouette.enabled = true;
  ViewOptions none = plain_view();
  none.overlays.volumes_in_place.push_back({"torus", std::nullopt, std::make_shared<const core::SilhouetteResult>()});
  EXPECT_EQ(draw(renderer, scene_with(v), cam, none), surface);
}

// ---- gpu/view/silhouette_strokes.h, no GL

// A circle of n points in the plane z = 0, radius 20 mm, seen from above; the second half hidden.
core::SilhouettePolyline half_hidden_circle(int n = 64) {
  core::SilhouettePolyline pl;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    pl.points.push_back({20.0 * std::cos(a), 20.0 * std::sin(a), 0.0});
    pl.gradient_norm.push_back(float(1.0 + k));  // low to high |∇D| around the circle
    pl.visible.push_back(k < n / 2 ? 1 : 0);
  }
  pl.closed = true;
  return pl;
}

struct TopView {
  glm::dmat4 view_proj;
  glm::dvec3 eye{0.0, 0.0, 100.0};
  TopView() {
    view_proj = glm::perspective(glm::radians(40.0), 1.0, 1.0, 500.0) *
                glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  }
};

TEST(SilhouetteStrokes, HiddenModesSortRunsIntoTheirLists) {
  const TopView v;
  const std::vector<core::SilhouettePolyline> lines{half_hidden_circle()};
  SilhouetteStrokeStyle s;
  s.stroke = "plain";
  s.hidden = "remove";
  const SilhouetteStrokes removed = build_silhouette_strokes(lines, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_FALSE(removed.depth_tested.empty());
  EXPECT_TRUE(removed.on_top.empty());
  EXPECT_EQ(removed.points, 32u);
  for (const OverlayVertex& p : removed.depth_tested) {
    EXPECT_GE(p.position.x, 0.0f);
    EXPECT_LE(p.position.x, 200.0f);
    EXPECT_GT(p.position.z, -1.0f);
    EXPECT_LT(p.position.z, 1.0f);
  }
  s.hidden = "dashed";
  const SilhouetteStrokes dashed = build_silhouette_strokes(lines, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_EQ(dashed.depth_tested.size(), removed.depth_tested.size());
  ASSERT_FALSE(dashed.on_top.empty());
  for (const OverlayVertex& p : dashed.on_top) EXPECT_EQ(p.color, s.hidden_color);
  EXPECT_EQ(dashed.points, 64u);
  s.hidden = "show";
  const SilhouetteStrokes shown = build_silhouette_strokes(lines, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_TRUE(shown.depth_tested.empty());
  EXPECT_EQ(shown.on_top.size(), 6u * 64u) << "every segment of the closed polyline, on top";
  // Dashes (5 px on, 4 off) cover about 5/9 of the hidden half: a quarter or so of the whole circle.
  auto length = [](const std::vector<OverlayVertex>& quads) {
    double sum = 0.0;
    for (std::size_t q = 0; q + 2 < quads.size(); q += 6)
      sum += glm::length(glm::vec2(quads[q + 2].position) - glm::vec2(quads[q].position));
    return sum;
  };
  const double all = length(shown.on_top), dashes = length(dashed.on_top);
  EXPECT_GT(dashes, 0.18 * all);
  EXPECT_LT(dashes, 0.38 * all);
}

TEST(SilhouetteStrokes, DepthPullMovesTowardsTheEyeOnly) {
  const TopView v;
  const std::vector<core::SilhouettePolyline> lines{half_hidden_circle()};
  SilhouetteStrokeStyle s;
  const SilhouetteStrokes flat = build_silhouette_strokes(lines, v.view_proj, {200, 200}, v.eye, s);
  s.depth_pull_mm = 5.0;
  const SilhouetteStrokes pulled = build_silhouette_strokes(lines, v.view_proj, {200, 200}, v.eye, s);
  ASSERT_EQ(flat.depth_tested.size(), pulled.depth_tested.size());
  for (std::size_t i = 0; i < flat.depth_tested.size(); ++i) {
    EXPECT_NEAR(flat.depth_tested[i].position.x, pulled.depth_tested[i].position.x, 1e-4f);
    EXPECT_LT(pulled.depth_tested[i].position.z, flat.depth_tested[i].position.z);
  }
}

TEST(SilhouetteStrokes, StylesColourAndWidenByGradient) {
  EXPECT_EQ(silhouette_color("hue", 0.0), glm::vec4(0.9f, 0.0f, 0.0f, 1.0f));    // red: low |∇D|
  EXPECT_EQ(silhouette_color("hue", 1.0), glm::vec4(0.0f, 0.0f, 0.9f, 1.0f));    // blue: high
  EXPECT_EQ(silhouette_color("width", 1.0), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // dark: high
  EXPECT_GT(silhouette_color("width", 0.0).x, 0.7f);                             // pale: low
  const TopView v;
  core::SilhouettePolyline pl = half_hidden_circle();
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  SilhouetteStrokeStyle s;
  s.stroke = "width";
  s.width_px = 1.0f;
  s.max_width_px = 2.4f;  // below the round joins' threshold: the list is one quad per segment
  const SilhouetteStrokes w = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_DOUBLE_EQ(w.gradient_min, 1.0);
  EXPECT_DOUBLE_EQ(w.gradient_max, 64.0);
  ASSERT_EQ(w.depth_tested.size(), 64u * 6u);
  // Quad q starts at point q: as wide as its |∇D| says, thickest at the lowest (point 0), thinnest at the highest.
  auto start_width = [&](std::size_t q) {
    return glm::length(glm::vec2(w.depth_tested[q * 6].position) - glm::vec2(w.depth_tested[q * 6 + 1].position));
  };
  EXPECT_NEAR(start_width(0), 2.4f, 1e-3f);
  EXPECT_NEAR(start_width(63), 1.0f, 1e-3f);
  EXPECT_NEAR(start_width(31), 2.4f + (1.0f - 2.4f) * 31.0f / 63.0f, 1e-3f);
  EXPECT_GT(w.depth_tested[0].color.x, w.depth_tested[63 * 6].color.x) << "pale where low, dark where high";
}

// chromadepth: the hue ramp by distance from the eye instead of |∇D| — red nearest, blue farthest (ChromaDepth
// glasses, seed Figs. 7.8–7.9): a circle tilted towards the eye is red where it is near and blue where it is far,
// whatever its gradient.
TEST(SilhouetteStrokes, ChromaDepthColoursByDistanceFromTheEye) {
  const TopView v;
  core::SilhouettePolyline pl = half_hidden_circle();
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  for (glm::dvec3& p : pl.points) p.z = 0.5 * p.y;  // +y half nearer the eye (at z = 100)
  SilhouetteStrokeStyle s;
  s.stroke = "chromadepth";
  const SilhouetteStrokes c = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_LT(c.depth_min, c.depth_max);
  EXPECT_NEAR(c.depth_min, glm::length(v.eye - glm::dvec3(0.0, 20.0, 10.0)), 0.05);
  EXPECT_NEAR(c.depth_max, glm::length(v.eye - glm::dvec3(0.0, -20.0, -10.0)), 0.05);
  EXPECT_EQ(c.gradient_min, c.gradient_max) << "the gradient ramp is not used";
  ASSERT_EQ(c.depth_tested.size(), 64u * 6u);
  // Quad q starts at point q: point 16 (+y, nearest) is red, point 48 (−y, farthest) blue.
  const glm::vec4 near = c.depth_tested[16 * 6].color, far = c.depth_tested[48 * 6].color;
  EXPECT_GT(near.x, 0.8f);
  EXPECT_LT(near.z, 0.1f);
  EXPECT_GT(far.z, 0.8f);
  EXPECT_LT(far.x, 0.1f);
  s.stroke = "hue";  // the same circle by |∇D|: point 16 sits a quarter up the gradient ramp, yellow, not red
  const SilhouetteStrokes h = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_GT(h.depth_tested[16 * 6].color.y, near.y + 0.5f);
}

TEST(SilhouetteStrokes, GlyphsAreShortEdgesAlongTheSilhouetteLongerWhereTheGradientIs) {
  const TopView v;
  core::SilhouettePolyline pl = half_hidden_circle(16);  // sparse: one glyph per visible point
  SilhouetteStrokeStyle s;
  s.stroke = "glyphs";
  s.hidden = "dashed";
  s.glyph_mm = 4.0;  // 11 px projected: above the 6 px minimum
  const SilhouetteStrokes g = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  ASSERT_EQ(g.depth_tested.size(), 8u * 6u) << "one edge (a quad) per visible point";
  EXPECT_FALSE(g.on_top.empty()) << "the hidden half is drawn dashed";
  float first_len = 0.0f, last_len = 0.0f;
  for (std::size_t k = 0; k < 8; ++k) {
    // The edge runs along the circle's tangent: orthogonal to the radius through the point; black.
    auto at = [&](std::size_t i) { return glm::vec2(g.depth_tested[6 * k + i].position); };
    const glm::vec2 a = 0.5f * (at(0) + at(1)), b = 0.5f * (at(2) + at(5));  // the quad's end centres
    const glm::dvec4 clip = v.view_proj * glm::dvec4(pl.points[k], 1.0);
    const glm::dvec3 c = glm::dvec3(clip) / clip.w;
    const glm::vec2 centre(float((c.x * 0.5 + 0.5) * 200.0), float((0.5 - c.y * 0.5) * 200.0));
    const glm::vec2 radial = glm::normalize(centre - glm::vec2(100.0f)), edge = glm::normalize(b - a);
    EXPECT_LT(std::abs(glm::dot(radial, edge)), 0.05f) << "glyph " << k;
    EXPECT_LT(glm::length(0.5f * (a + b) - centre), 0.7f) << "centred on its point";
    EXPECT_EQ(g.depth_tested[6 * k].color, s.plain_color);
    (k == 0 ? first_len : last_len) = glm::length(b - a);
  }
  EXPECT_GT(last_len, 1.5f * first_len) << "|∇D| grows along the circle: so do the glyphs";
  // Dense points: glyphs stay at least 1.4 × their base apart.
  core::SilhouettePolyline dense = half_hidden_circle(512);
  std::fill(dense.visible.begin(), dense.visible.end(), 1);
  s.glyph_mm = 0.5;  // below the minimum: 6 px edges, centres ≥ 8.4 px apart
  const SilhouetteStrokes d = build_silhouette_strokes({dense}, v.view_proj, {200, 200}, v.eye, s);
  const std::size_t glyphs = d.depth_tested.size() / 6;
  EXPECT_GT(glyphs, 20u);
  EXPECT_LT(glyphs, 50u) << "about the circle's 345 px over 8.4 px";
}

// fans (seed Fig. 7.11): per glyph position a filled fan across the curve (its bisector along the circle's radius),
// 150° wide where |∇D| is lowest down to 20° where it is highest, on the hue ramp (red → blue).
TEST(SilhouetteStrokes, FansOpenWideWhereTheGradientIsLowAndNarrowWhereItIsHigh) {
  const TopView v;
  core::SilhouettePolyline pl = half_hidden_circle(16);
  SilhouetteStrokeStyle s;
  s.stroke = "fans";
  s.glyph_mm = 4.0;
  const SilhouetteStrokes f = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  constexpr std::size_t kPerFan = 6 * 3;  // six triangles
  ASSERT_EQ(f.depth_tested.size(), 8u * kPerFan) << "one fan per visible point";
  EXPECT_TRUE(f.on_top.empty()) << "hidden points removed";
  double first = 0.0, last = 0.0;
  for (std::size_t k = 0; k < 8; ++k) {
    const OverlayVertex* fan = &f.depth_tested[k * kPerFan];
    const glm::vec2 apex(fan[0].position), r0 = glm::vec2(fan[1].position) - apex,
                                           r6 = glm::vec2(fan[kPerFan - 1].position) - apex,
                                           mid = glm::vec2(fan[3 * 3 + 1].position) - apex;
    const double opening = glm::degrees(std::acos(glm::dot(r0, r6) / (glm::length(r0) * glm::length(r6))));
    const glm::vec2 radial = glm::normalize(apex - glm::vec2(100.0f));
    EXPECT_GT(std::abs(glm::dot(radial, glm::normalize(mid))), 0.99f) << "fan " << k << " opens across the curve";
    (k == 0 ? first : last) = opening;
  }
  EXPECT_NEAR(first, 150.0, 1.0);
  EXPECT_NEAR(last, 20.0, 1.0);
  EXPECT_GT(f.depth_tested.front().color.x, 0.8f) << "red at the lowest |∇D|";
  EXPECT_GT(f.depth_tested[7 * kPerFan].color.z, 0.8f) << "blue at the highest";
}

TEST(SilhouetteStrokes, PointsBehindTheEyeBreakTheLineAndBadInputThrows) {
  const TopView v;
  core::SilhouettePolyline pl;
  for (int k = 0; k < 5; ++k) {
    pl.points.push_back({double(k), 0.0, k == 2 ? 150.0 : 0.0});  // point 2 lies behind the eye (z > 100)
    pl.gradient_norm.push_back(1.0f);
    pl.visible.push_back(1);
  }
  SilhouetteStrokeStyle s;
  const SilhouetteStrokes st = build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s);
  EXPECT_EQ(st.points, 4u);
  EXPECT_EQ(st.depth_tested.size(), 2u * 6u) << "segments 0–1 and 3–4 only";
  s.stroke = "crayon";
  EXPECT_THROW(build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s), std::invalid_argument);
  s.stroke = "hue";
  pl.visible.pop_back();
  EXPECT_THROW(build_silhouette_strokes({pl}, v.view_proj, {200, 200}, v.eye, s), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::gpu::test
