// The GLSL iso-surface ray caster (gpu/eval/volume_gl.h, shaders/volume_iso.frag.glsl) against the CPU reference
// core::render_iso_hits_cpu (core/volume/iso_raycast.h), for real on llvmpipe, pixel by pixel on the same rays: a
// sphere and a torus signed distance field on oblique anisotropic grids (tests/core/volume/iso_test_volumes.h), orders
// 4, 3 and 2, an eye inside the grid box, and the Cranium CT (assets/data) from the skull scene's three views. Hit/miss
// masks agree but on the silhouette (mismatches ≤ 0.5 % of the pixels, each next to a CPU mask edge); world points
// within 1e-3 × the volume's size, normals and window depths close. Brick size and the fast march (GL_LINEAR values,
// slope skipping) change no bit of the hits. Then depth: meshes drawn before and after the volume are occluded by it
// and occlude it where they should.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "core/volume/iso_raycast.h"
#include "core/volume/volume_dvr.h"
#include "core/volume/volume_io.h"
#include "core/volume/volume_spline.h"
#include "gl_test.h"
#include "gpu/eval/volume_gl.h"
#include "gpu/gl/mesh_buffers.h"
#include "gpu/gl/shader_program.h"
#include "tests/core/volume/iso_test_volumes.h"

namespace trispline::gpu::test {
namespace {

using trispline::test::sphere_volume;
using trispline::test::torus_volume;

// Largest world extent of the volume's grid box (millimetres): the "volume size" of the position bar.
double volume_size(const core::VolumeSpline& s) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 ijk((c & 1) * (s.dims()[0] - 1), ((c >> 1) & 1) * (s.dims()[1] - 1),
                         ((c >> 2) & 1) * (s.dims()[2] - 1));
    const glm::dvec3 w = glm::dvec3(s.index_to_world() * glm::dvec4(ijk, 1.0));
    lo = glm::min(lo, w), hi = glm::max(hi, w);
  }
  const glm::dvec3 e = hi - lo;
  return std::max(e.x, std::max(e.y, e.z));
}

struct View {
  glm::dmat4 view, projection;
};

View look_at(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg = 30.0) {
  return {glm::lookAt(eye, target, glm::dvec3(0.0, 1.0, 0.0)),
          glm::perspective(glm::radians(fov_deg), 1.0, 1.0, 500.0)};
}

struct Parity {
  std::size_t hits = 0, mismatches = 0;
};

// GPU read_hits against render_iso_hits_cpu on a width × height image (square when height is 0) at `iso`; asserts
// the bars of the header comment.
Parity expect_parity(VolumeIsoRenderer& gpu, const core::VolumeSpline& spline, const View& v, int width,
                     const char* what, int height = 0, double iso = 0.0) {
  const int w = width, h = height > 0 ? height : width;
  const auto t0 = std::chrono::steady_clock::now();
  const IsoHitReadback g = gpu.read_hits(v.view, v.projection, w, h, iso);
  const auto t1 = std::chrono::steady_clock::now();
  const core::VolumeRangeGrid grid = core::build_volume_range_grid(spline);
  const core::IsoHitImage c = core::render_iso_hits_cpu(spline, iso, v.view, v.projection, w, h, 0.25, &grid);
  const auto t2 = std::chrono::steady_clock::now();
  EXPECT_EQ(g.width, w);
  EXPECT_EQ(g.hit.size(), std::size_t(w) * h);
  Parity r;
  double worst_p = 0.0, worst_n = 0.0, worst_d = 0.0;
  auto cpu_hit = [&](int x, int y) { return c.hits[std::size_t(x + w * y)].hit; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(x + w * y);
      const core::IsoHit& ch = c.hits[i];
      if (bool(g.hit[i]) != ch.hit) {
        ++r.mismatches;
        // Only on the silhouette: a 4-neighbour of the pixel has the other CPU status.
        bool edge = false;
        for (glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
          const int xx = x + d.x, yy = y + d.y;
          if (xx >= 0 && yy >= 0 && xx < w && yy < h && cpu_hit(xx, yy) != ch.hit) edge = true;
        }
        EXPECT_TRUE(edge) << what << ": pixel (" << x << ", " << y << ") disagrees away from the silhouette";
        continue;
      }
      if (!ch.hit) {
        EXPECT_EQ(g.depth[i], 1.0f);
        continue;
      }
      ++r.hits;
      worst_p = std::max(worst_p, glm::length(glm::dvec3(g.world_point[i]) - ch.world_point));
      worst_n = std::max(worst_n, glm::length(glm::dvec3(g.world_normal[i]) - ch.world_normal));
      worst_d = std::max(worst_d, std::abs(double(g.depth[i]) - c.depth[i]));
    }
  const double size = volume_size(spline);
  std::printf(
      "[volume iso] %-30s %dx%d: %zu hits, %zu mask mismatches (%.2f %%), max |Δp| = %.3g mm (%.2g × size %.1f mm), "
      "max |Δn| = %.3g, max |Δdepth| = %.3g; GPU %.0f ms, CPU %.0f ms\n",
      what, w, h, r.hits, r.mismatches, 100.0 * double(r.mismatches) / (w * h), worst_p, worst_p / size, size, worst_n,
      worst_d, std::chrono::duration<double, std::milli>(t1 - t0).count(),
      std::chrono::duration<double, std::milli>(t2 - t1).count());
  EXPECT_LE(double(r.mismatches), 0.005 * w * h) << what;
  EXPECT_LE(worst_p, 1e-3 * size) << what;
  EXPECT_LE(worst_n, 1e-2) << what;
  EXPECT_LE(worst_d, 1e-5) << what;
  return r;
}

// The hits of the fast march equal, bit for bit, those with every sample of the bricks holding the iso-level
// evaluated exactly (a filter error bound so large that no fast value is trusted): GL_LINEAR values and slope skipping
// only decide signs the exact evaluation would give.
void expect_fast_march_exact(VolumeIsoRenderer& gpu, const View& v, int w, int h, double iso, const char* what) {
  const double kept = gpu.filter_error();
  const IsoHitReadback fast = gpu.read_hits(v.view, v.projection, w, h, iso);
  gpu.set_filter_error(1e6);
  const IsoHitReadback exact = gpu.read_hits(v.view, v.projection, w, h, iso);
  gpu.set_filter_error(kept);
  EXPECT_GT(fast.hit_count(), 0u) << what;
  EXPECT_EQ(fast.hit, exact.hit) << what;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < fast.hit.size(); ++i)
    differ += fast.world_point[i] != exact.world_point[i] || fast.world_normal[i] != exact.world_normal[i] ||
              fast.depth[i] != exact.depth[i];
  EXPECT_EQ(differ, 0u) << what;
}

// Direct volume rendering: GPU read_dvr against core::render_dvr_cpu on the same rays. Per pixel the largest channel
// difference; `exact` (ORDER³ fetches, float vs double) must stay within 0.01 but for ≤ 0.5 % of the pixels (those
// whose float and double samples fall on two sides of a brick skip or a transfer-function kink) and within 0.05 on
// all; the fast path (2³ GL_LINEAR fetches) within 0.02 on average.
struct DvrParity {
  double mean = 0.0, worst = 0.0;
  std::size_t over = 0, seen = 0;
};
DvrParity expect_dvr_parity(VolumeIsoRenderer& gpu, const core::VolumeSpline& spline, const core::TransferFunction& tf,
                            const View& v, int w, int h, bool exact, const char* what) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<glm::vec4> g = gpu.read_dvr(v.view, v.projection, w, h, tf, 0.5, exact);
  const auto t1 = std::chrono::steady_clock::now();
  const core::VolumeRangeGrid grid = core::build_volume_range_grid(spline);
  const core::DvrImage c = core::render_dvr_cpu(spline, tf, v.view, v.projection, w, h, 0.5, &grid);
  const auto t2 = std::chrono::steady_clock::now();
  EXPECT_EQ(g.size(), c.rgba.size()) << what;
  DvrParity r;
  for (std::size_t i = 0; i < g.size() && i < c.rgba.size(); ++i) {
    double d = 0.0;
    for (int k = 0; k < 4; ++k) d = std::max(d, double(std::abs(g[i][k] - c.rgba[i][k])));
    r.mean += d;
    r.worst = std::max(r.worst, d);
    r.over += d > 0.01;
    r.seen += c.rgba[i].w > 0.05f;
  }
  r.mean /= double(std::max<std::size_t>(g.size(), 1));
  std::printf(
      "[volume dvr] %-34s %dx%d: %zu pixels seen, mean |Δ| %.2g, max |Δ| %.3g, %zu pixels over 0.01; GPU %.0f "
      "ms, CPU %.0f ms\n",
      what, w, h, r.seen, r.mean, r.worst, r.over, std::chrono::duration<double, std::milli>(t1 - t0).count(),
      std::chrono::duration<double, std::milli>(t2 - t1).count());
  if (exact) {
    EXPECT_LE(double(r.over), 0.005 * w * h) << what;
    EXPECT_LE(r.worst, 0.05) << what;
  } else {
    EXPECT_LE(r.mean, 0.02) << what;
  }
  EXPECT_GT(r.seen, std::size_t(w * h / 20)) << what;
  return r;
}

class VolumeGlTest : public GlTest {};

TEST_F(VolumeGlTest, DvrMatchesTheCpuReference) {
  const auto sphere = sphere_volume({30, 30, 30});
  const core::VolumeSpline spline(sphere.volume, 4, false);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  const core::TransferFunction tf{{{-1.0, {0, 0, 0, 0}}, {0.0, {1.0, 0.5, 0.1, 0.3}}, {4.0, {0.1, 0.3, 1.0, 0.8}}}};
  const glm::dvec3 c = sphere.field.center;
  const View v = look_at(c + glm::dvec3(10.0, 20.0, 45.0), c, 35.0);
  expect_dvr_parity(gpu, spline, tf, v, 96, 96, true, "sphere, exact");
  expect_dvr_parity(gpu, spline, tf, v, 96, 96, false, "sphere, fast");
  // The sphere's inside seen from within the box.
  expect_dvr_parity(gpu, spline, tf, look_at(c + glm::dvec3(2.0, 1.0, 6.0), c, 70.0), 64, 64, true,
                    "sphere, eye inside");
}

TEST_F(VolumeGlTest, DvrOfTheCraniumMatchesTheCpuReference) {
  const std::filesystem::path path = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/Cranium.inv3";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing: run scripts/fetch_assets.sh";
  const core::VolumeSpline spline(core::load_volume(path), 4, false);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  const glm::dvec3 target(122.0, 122.0, 80.0), eye(-330.0, 572.0, 140.0);
  const double d = glm::length(eye - target);
  const View v{glm::lookAt(eye, target, glm::dvec3(0.0, 0.0, 1.0)),
               glm::perspective(glm::radians(30.0), 4.0 / 3.0, 0.01 * d, 10.0 * d)};
  expect_dvr_parity(gpu, spline, core::ct_transfer_function(), v, 80, 60, true, "Cranium, CT preset, exact");
  expect_dvr_parity(gpu, spline, core::ct_transfer_function(), v, 80, 60, false, "Cranium, CT preset, fast");
  EXPECT_THROW(gpu.read_dvr(v.view, v.projection, 8, 8, core::TransferFunction{}, 0.5), std::invalid_argument);
  EXPECT_THROW(gpu.read_dvr(v.view, v.projection, 8, 8, core::ct_transfer_function(), 0.0), std::invalid_argument);
}

TEST_F(VolumeGlTest, SphereHitsMatchTheCpuReference) {
  const auto s = sphere_volume();
  const core::VolumeSpline spline(s.volume, 4, true);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  EXPECT_TRUE(gpu.has_volume());
  const Parity p = expect_parity(gpu, spline, look_at(s.field.center + glm::dvec3(25.0, 30.0, 65.0), s.field.center),
                                 96, "sphere, order 4");
  EXPECT_GT(p.hits, std::size_t(96 * 96 / 8));  // the sphere fills a good part of the image
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(VolumeGlTest, TorusHitsMatchTheCpuReference) {
  const auto t = torus_volume();
  const core::VolumeSpline spline(t.volume, 3, true);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  // Oblique, so the hole and both sides of the tube show.
  const glm::dvec3 eye = t.field.center + 70.0 * glm::normalize(t.field.axis + glm::dvec3(0.4, 0.5, 0.2));
  const Parity p = expect_parity(gpu, spline, look_at(eye, t.field.center), 96, "torus, order 3");
  EXPECT_GT(p.hits, std::size_t(96 * 96 / 10));
  // Through the hole along the axis: the centre pixel misses on both.
  const View axial = look_at(t.field.center + 80.0 * t.field.axis, t.field.center);
  const IsoHitReadback g = gpu.read_hits(axial.view, axial.projection, 33, 33, 0.0);
  EXPECT_EQ(g.hit[16 + 33 * 16], 0);
  EXPECT_GT(g.hit_count(), std::size_t(33 * 33 / 8));
}

// Trilinear (order 2) on a smaller image, and an eye inside the grid box (outside the sphere): the box's back faces
// still give every pixel its ray.
TEST_F(VolumeGlTest, TrilinearAndEyeInsideTheBox) {
  const auto s = sphere_volume();
  const core::VolumeSpline spline(s.volume, 2);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  expect_parity(gpu, spline, look_at(s.field.center + glm::dvec3(-20.0, 35.0, 60.0), s.field.center), 48,
                "sphere, order 2");
  const core::VolumeSpline cubic(s.volume, 4, true);
  gpu.set_volume(cubic);
  EXPECT_EQ(gpu.uploads(), 2);
  const glm::dvec3 eye = glm::dvec3(cubic.index_to_world() * glm::dvec4(3.0, 4.0, 5.0, 1.0));  // in the box
  const Parity p = expect_parity(gpu, cubic, look_at(eye, s.field.center, 70.0), 48, "sphere, eye inside the box");
  EXPECT_GT(p.hits, std::size_t(48 * 48 / 8));
}

// Brick size only changes how much is skipped: the same pixels, bit for bit.
TEST_F(VolumeGlTest, BrickSizeDoesNotChangeTheImage) {
  const auto s = sphere_volume();
  const core::VolumeSpline spline(s.volume, 4, true);
  VolumeIsoRenderer gpu;
  const View v = look_at(s.field.center + glm::dvec3(0.0, -40.0, 60.0), s.field.center);
  gpu.set_volume(spline, 3);
  const IsoHitReadback a = gpu.read_hits(v.view, v.projection, 40, 40, 0.0);
  ASSERT_GT(a.hit_count(), 100u);
  for (int brick : {1, 16}) {
    gpu.set_volume(spline, brick);
    const IsoHitReadback b = gpu.read_hits(v.view, v.projection, 40, 40, 0.0);
    EXPECT_EQ(a.hit, b.hit) << brick;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.hit.size(); ++i) differ += a.world_point[i] != b.world_point[i];
    EXPECT_EQ(differ, 0u) << brick;
  }
}

TEST_F(VolumeGlTest, FastMarchChangesNothing) {
  const auto s = sphere_volume();
  const auto t = torus_volume();
  const glm::dvec3 eye = t.field.center + 70.0 * glm::normalize(t.field.axis + glm::dvec3(0.4, 0.5, 0.2));
  VolumeIsoRenderer gpu;
  for (int order : {4, 3, 2}) {
    const core::VolumeSpline sphere(s.volume, order, order > 2), torus(t.volume, order, order > 2);
    gpu.set_volume(sphere);
    expect_fast_march_exact(gpu, look_at(s.field.center + glm::dvec3(25.0, 30.0, 65.0), s.field.center), 48, 48, 0.0,
                            "sphere");
    gpu.set_volume(torus);
    expect_fast_march_exact(gpu, look_at(eye, t.field.center), 48, 48, 0.0, "torus");
  }
  EXPECT_THROW(gpu.set_filter_error(0.0), std::invalid_argument);
  EXPECT_THROW(gpu.set_filter_error(INFINITY), std::invalid_argument);
}

// The real CT: InVesalius' Cranium (256 × 256 × 108, HU) as the skull scene loads it (tri-cubic, approximating, bone
// at 226 HU), from its three views (assets/scenes/seed/skull.jsonl) on 4:3 images: thin bone, noise, a head rest.
TEST_F(VolumeGlTest, CraniumMatchesTheCpuReference) {
  const std::filesystem::path path = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data/Cranium.inv3";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing: run scripts/fetch_assets.sh";
  const core::VolumeSpline spline(core::load_volume(path), 4, false);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  const glm::dvec3 target(122.0, 122.0, 80.0);
  auto view_from = [&](const glm::dvec3& eye) {  // z up, near and far planes as the editor's replay sets them
    const double d = glm::length(eye - target);
    return View{glm::lookAt(eye, target, glm::dvec3(0.0, 0.0, 1.0)),
                glm::perspective(glm::radians(30.0), 4.0 / 3.0, 0.01 * d, 10.0 * d)};
  };
  struct Case {
    const char* name;
    glm::dvec3 eye;
  };
  for (const Case& c :
       {Case{"Cranium, front", {122.0, 760.0, 80.0}}, Case{"Cranium, three-quarter", {-330.0, 572.0, 140.0}},
        Case{"Cranium, side", {-518.0, 122.0, 80.0}}}) {
    const View v = view_from(c.eye);
    const Parity p = expect_parity(gpu, spline, v, 160, c.name, 120, 226.0);
    EXPECT_GT(p.hits, std::size_t(160 * 120 / 10)) << c.name;
  }
  expect_fast_march_exact(gpu, view_from({-330.0, 572.0, 140.0}), 160, 120, 226.0, "Cranium, three-quarter");
}

// Camera-facing quad at distance d from the eye covering screen x ∈ [x0, x1], y ∈ [y0, y1] (NDC).
core::TriMesh screen_quad(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg, double d, glm::dvec2 lo,
                          glm::dvec2 hi) {
  const glm::dvec3 f = glm::normalize(target - eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0.0, 1.0, 0.0)));
  const glm::dvec3 u = glm::cross(r, f);
  const double h = d * std::tan(glm::radians(fov_deg) / 2.0);
  core::TriMesh m;
  for (glm::dvec2 c : {glm::dvec2(lo.x, lo.y), glm::dvec2(hi.x, lo.y), glm::dvec2(hi.x, hi.y), glm::dvec2(lo.x, hi.y)})
    m.positions.push_back(eye + d * f + c.x * h * r + c.y * h * u);
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Meshes and the volume share the depth buffer: a far yellow backdrop drawn first, a near red quad (left half) drawn
// before the volume, then the volume (green), then a blue quad (bottom half) at the sphere's centre plane — behind
// the sphere's front surface but in front of the grid box's back faces, so it only shows if gl_FragDepth is the hit's.
TEST_F(VolumeGlTest, DepthCombinesWithMeshes) {
  const auto s = sphere_volume();
  const core::VolumeSpline spline(s.volume, 4, true);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  const int n = 64;
  const double fov = 30.0, dist = 75.0;
  const glm::dvec3 eye = s.field.center + dist * glm::normalize(glm::dvec3(0.3, 0.4, 1.0));
  const View v = look_at(eye, s.field.center, fov);
  const glm::dmat4 view_proj = v.projection * v.view;

  MeshBuffers backdrop, near_quad, mid_quad;
  backdrop.upload(screen_quad(eye, s.field.center, fov, 200.0, {-2.0, -2.0}, {2.0, 2.0}));
  near_quad.upload(screen_quad(eye, s.field.center, fov, 40.0, {-2.0, -2.0}, {0.0, 2.0}));
  mid_quad.upload(screen_quad(eye, s.field.center, fov, dist, {-2.0, -2.0}, {2.0, 0.0}));
  ShaderProgram flat({"mesh.vert.glsl", "mesh.frag.glsl"}, {{"FLAT_COLOR", ""}});

  OffscreenTarget target(n, n, 1);
  target.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  auto draw_quad = [&](const MeshBuffers& q, glm::vec4 color) {
    flat.use();
    flat.set("u_view_proj", glm::mat4(view_proj));
    flat.set("u_flat_color", color);
    q.draw_triangles();
  };
  draw_quad(backdrop, {1.0f, 1.0f, 0.0f, 1.0f});
  draw_quad(near_quad, {1.0f, 0.0f, 0.0f, 1.0f});
  IsoStyle style;
  style.color = {0.1f, 0.8f, 0.2f};
  gpu.draw(v.view, v.projection, {0, 0, n, n}, 0.0, style);
  EXPECT_FALSE(glIsEnabled(GL_CULL_FACE));  // restored
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  draw_quad(mid_quad, {0.0f, 0.0f, 1.0f, 1.0f});
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  const std::vector<unsigned char> img = target.read_rgba();  // top row first

  const core::IsoHitImage cpu = core::render_iso_hits_cpu(spline, 0.0, v.view, v.projection, n, n);
  int checked = 0, green = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (std::abs(x - n / 2) <= 1 || std::abs(y - n / 2) <= 1) continue;  // quad edges
      bool hit = cpu.hits[std::size_t(x + n * y)].hit, edge = false;
      for (glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
        const int xx = std::clamp(x + d.x, 0, n - 1), yy = std::clamp(y + d.y, 0, n - 1);
        edge |= cpu.hits[std::size_t(xx + n * yy)].hit != hit;
      }
      if (edge) continue;
      const Rgba p = pixel(img, n, x, n - 1 - y);
      const bool left = x < n / 2, bottom = y < n / 2;
      const char* expected = left ? "red" : hit ? "green" : bottom ? "blue" : "yellow";
      const bool ok = left     ? (p.r > 200 && p.g < 30 && p.b < 30)
                      : hit    ? (p.g > 40 && p.g > p.r + 20 && p.g > p.b + 20)
                      : bottom ? (p.b > 200 && p.r < 30 && p.g < 30)
                               : (p.r > 200 && p.g > 200 && p.b < 30);
      EXPECT_TRUE(ok) << "pixel (" << x << ", " << y << ") should be " << expected << ", is " << p.r << " " << p.g
                      << " " << p.b;
      ++checked;
      green += !left && hit;
    }
  EXPECT_GT(checked, n * n / 2);
  EXPECT_GT(green, 100);  // the volume shows over the blue and yellow quads
}

// Shading: a headlight, so the pixel facing the eye (the sphere's centre) is brighter than one near the silhouette.
TEST_F(VolumeGlTest, HeadlightShadesFacingPixelsBrightest) {
  const auto s = sphere_volume();
  const core::VolumeSpline spline(s.volume, 4, true);
  VolumeIsoRenderer gpu;
  gpu.set_volume(spline);
  const int n = 48;
  const View v = look_at(s.field.center + glm::dvec3(0.0, 0.0, 70.0), s.field.center);
  OffscreenTarget target(n, n, 1);
  target.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDepthFunc(GL_LESS);
  gpu.draw(v.view, v.projection, {0, 0, n, n}, 0.0);
  const std::vector<unsigned char> img = target.read_rgba();
  const Rgba centre = pixel(img, n, n / 2, n / 2);
  // The sphere (r = 12 at 70 mm, 30° field) spans ±0.64 of the half-width (±15 pixels): column n/2 + 12 sees it at
  // 0.8 of its radius, where the normal is ~53° from the view direction.
  const Rgba rim = pixel(img, n, n / 2 + 12, n / 2);
  const Rgba corner = pixel(img, n, 0, 0);
  std::printf("[volume iso] shaded: centre %d %d %d, rim %d %d %d\n", centre.r, centre.g, centre.b, rim.r, rim.g,
              rim.b);
  EXPECT_GT(centre.g, rim.g + 30);
  EXPECT_GT(rim.g, 20);
  EXPECT_EQ(corner.g, 0);  // a miss: discarded, the clear colour stays
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(VolumeGlTest, MisuseThrows) {
  VolumeIsoRenderer gpu;
  EXPECT_FALSE(gpu.has_volume());
  EXPECT_THROW(gpu.draw(glm::dmat4(1.0), glm::dmat4(1.0), {0, 0, 8, 8}, 0.0), std::logic_error);
  EXPECT_THROW(gpu.read_hits(glm::dmat4(1.0), glm::dmat4(1.0), 8, 8, 0.0), std::logic_error);
  EXPECT_THROW(gpu.set_step(0.0), std::invalid_argument);
  EXPECT_THROW(gpu.set_step(NAN), std::invalid_argument);
  EXPECT_THROW(gpu.set_step(1.5), std::invalid_argument);
  const auto s = sphere_volume({8, 8, 8});
  const core::VolumeSpline spline(s.volume, 4);
  EXPECT_THROW(gpu.set_volume(spline, 0), std::invalid_argument);
  EXPECT_FALSE(gpu.has_volume());
  gpu.set_volume(spline);
  EXPECT_THROW(gpu.read_hits(glm::dmat4(1.0), glm::dmat4(1.0), 0, 8, 0.0), std::invalid_argument);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace trispline::gpu::test
