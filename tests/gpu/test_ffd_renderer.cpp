// The renderer's FFD display (gpu/render/renderer_ffd.h): evaluate_into writes the buffers the renderer draws, the four
// backends give the same picture (only speed differs), and nothing is re-evaluated when nothing changed.
#include <epoxy/gl.h>

#include <cstdio>

#include "core/image/image_io.h"
#include "ffd_gl_test_util.h"
#include "gl_test.h"
#include "gpu/eval/ffd_gl.h"

namespace trispline::gpu::test {
namespace {

constexpr core::FfdBackend kBackends[] = {core::FfdBackend::cpu_ref, core::FfdBackend::cpu_fast,
                                          core::FfdBackend::glsl_compute, core::FfdBackend::glsl_vertex};

// A sphere of radius 0.8 embedded in its bounding box and bent by a clamped (4,3,3) lattice with 5×4×4 controls.
core::SceneObject deformed_ball(const glm::dvec3& param_offset = glm::dvec3(0.0)) {
  core::SceneObject o = make_object("blob", uv_sphere({0, 0, 0}, 0.8, 40, 20), {0.8f, 0.1f, 0.05f});
  const std::vector<glm::dvec3> rest = o.world_rest_mesh().positions;
  core::FfdBinding b{core::TrivariateBSpline<glm::dvec3>(
                         core::KnotVector::clamped_uniform(4, 5), core::KnotVector::clamped_uniform(3, 4),
                         core::KnotVector::clamped_uniform(3, 4), std::vector<glm::dvec3>(80)),
                     core::embed_bounding_box(rest, {0, 1}),
                     {}};
  b.params = core::embed_points(b.embedding, rest);
  const glm::dmat3 inv = glm::inverse(b.embedding.linear);
  const auto gu = b.lattice.knots(0).greville(), gv = b.lattice.knots(1).greville(), gw = b.lattice.knots(2).greville();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i) {
        glm::dvec3 p = inv * (glm::dvec3(gu[i], gv[j], gw[k]) - b.embedding.offset);
        p.y += 0.5 * (gu[i] - 0.5) * (gu[i] - 0.5) - 0.1;  // bend
        p.z += 0.3 * gu[i] * gw[k];                        // shear
        p.x *= 1.0 + 0.3 * gw[k];                          // flare upwards
        b.lattice.control_point(i, j, k) = p;
      }
  o.ffd = std::make_shared<const core::FfdBinding>(std::move(b));
  o.param_offset = param_offset;
  o.refresh();
  return o;
}

struct ImageDiff {
  double mean = 0.0;       // mean absolute channel difference
  double frac_over = 0.0;  // fraction of pixels with a channel differing by more than 24
};
ImageDiff diff(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  ImageDiff d;
  std::size_t over = 0;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int x = std::abs(int(a[i + c]) - int(b[i + c]));
      d.mean += x;
      worst = std::max(worst, x);
    }
    over += worst > 24 ? 1 : 0;
  }
  d.mean /= double(a.size() / 4 * 3);
  d.frac_over = double(over) / double(a.size() / 4);
  return d;
}

}  // namespace

// evaluate_into writes the renderer's own MeshBuffers (no CPU round trip): read the GL buffer back.
TEST_F(GlTest, FfdEvaluateIntoWritesTheBuffersTheRendererDraws) {
  const glm::dvec3 offset(0.05, -0.03, 0.02);
  const core::SceneObject o = deformed_ball(offset);  // world_mesh = CPU reference at param_offset
  Renderer r;
  MeshBuffers& buffers = r.buffers_for(o.world_mesh);
  GlslComputeFfdEvaluator ev;
  ev.bind_vertices(o.ffd->params, o.world_rest_mesh().normals);
  ev.set_lattice(o.ffd->lattice, o.ffd->embedding);
  // Scribble over the buffers first so a missing write cannot pass.
  std::vector<float> junk(buffers.vertex_count() * 3, 1e6f);
  glBindBuffer(GL_ARRAY_BUFFER, buffers.position_buffer());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(junk.size() * 4), junk.data());
  ev.evaluate_into(buffers, offset);
  std::vector<float> pos(junk.size()), nrm(junk.size());
  glBindBuffer(GL_ARRAY_BUFFER, buffers.position_buffer());
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(pos.size() * 4), pos.data());
  glBindBuffer(GL_ARRAY_BUFFER, buffers.normal_buffer());
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(nrm.size() * 4), nrm.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  std::vector<glm::dvec3> p(buffers.vertex_count()), n(buffers.vertex_count());
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
    n[i] = {nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]};
  }
  const FfdErrors err = ffd_errors(o.world_mesh->positions, o.world_mesh->normals, p, n);
  EXPECT_LE(err.position, 1e-5 * lattice_diagonal(o.ffd->lattice));
  EXPECT_LE(err.normal_rad, 1e-4);
  // The same dispatch into the evaluator's own buffers gives the same bits.
  ev.evaluate(offset);
  std::vector<glm::dvec3> p2, n2;
  ev.read_results(p2, n2);
  EXPECT_EQ(p2, p);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// Nothing visible changes between backends: at rest offset, at another offset, animated, selected + wireframe.
TEST_F(GlTest, FfdRendererImagesAgreeAcrossBackends) {
  core::Scene undeformed;
  undeformed.insert(make_object("blob", uv_sphere({0, 0, 0}, 0.8, 40, 20), {0.8f, 0.1f, 0.05f}));
  Renderer r;
  const core::Camera cam = front_camera(160, 120);
  ViewOptions opt;
  opt.show_grid = false;
  const std::vector<unsigned char> plain = render(r, undeformed, cam, opt);

  struct Case {
    const char* name;
    glm::dvec3 offset, velocity;
    double time_s;
    bool selected_wireframe;
  };
  const Case cases[] = {{"rest", glm::dvec3(0.0), glm::dvec3(0.0), 0.0, false},
                        {"offset", {0.06, 0.0, -0.04}, glm::dvec3(0.0), 2.0, false},
                        {"animated", {0.02, 0.0, 0.0}, {0.04, 0.01, 0.0}, 1.5, false},
                        {"selected+wireframe", {0.02, 0.0, 0.0}, {0.04, 0.0, 0.0}, 0.5, true}};
  for (const Case& c : cases) {
    core::Scene scene;
    core::SceneObject o = deformed_ball(c.offset);
    o.offset_velocity = c.velocity;
    scene.insert(o);
    opt.time_s = c.time_s;
    opt.selected = c.selected_wireframe ? "blob" : "";
    opt.wireframe = c.selected_wireframe;
    opt.ffd_backend = core::FfdBackend::cpu_ref;
    const std::vector<unsigned char> ref = render(r, scene, cam, opt);
    EXPECT_GT(diff(ref, plain).frac_over, 0.02) << c.name << ": the deformation should show";
    for (core::FfdBackend b : kBackends) {
      opt.ffd_backend = b;
      const std::vector<unsigned char> img = render(r, scene, cam, opt);
      const ImageDiff d = diff(img, ref);
      EXPECT_LT(d.mean, 0.5) << c.name << " " << core::to_string(b);
      EXPECT_LT(d.frac_over, 0.002) << c.name << " " << core::to_string(b);
      EXPECT_EQ(r.last_stats().ffd_objects, 1) << c.name << " " << core::to_string(b);
      if (c.selected_wireframe && b == core::FfdBackend::glsl_vertex)  // for eyeballing
        core::write_image_rgba8(TRISPLINE_BINARY_DIR "/gpu_ffd_glsl_vertex.png", 160, 120, img);
    }
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The Press tool's drag preview (Overlays::lattices_in_place): drawing an object with an override lattice looks like
// the object after the command (lattice replaced, world_mesh re-evaluated), on every backend, and dropping the
// override shows the object's own lattice again.
TEST_F(GlTest, FfdRendererDrawsALiveLatticeOverrideLikeTheCommittedLattice) {
  Renderer r;
  const core::Camera cam = front_camera(160, 120);
  ViewOptions opt;
  opt.show_grid = false;
  core::Scene scene;
  const core::SceneObject ball = deformed_ball();
  scene.insert(ball);
  auto pressed = std::make_shared<core::TrivariateBSpline<glm::dvec3>>(ball.ffd->lattice);
  for (glm::dvec3& p : pressed->control_points()) p.y -= 0.3 * std::max(0.0, p.x);  // push the right half down
  core::Scene committed;
  core::SceneObject after = ball;
  auto b = std::make_shared<core::FfdBinding>(*ball.ffd);
  b->lattice = *pressed;
  after.ffd = std::move(b);
  after.refresh();
  committed.insert(after);
  for (core::FfdBackend backend : kBackends) {
    opt.ffd_backend = backend;
    opt.overlays.lattices_in_place.clear();
    const std::vector<unsigned char> own = render(r, scene, cam, opt);
    opt.ffd_backend = core::FfdBackend::cpu_ref;
    const std::vector<unsigned char> ref = render(r, committed, cam, opt);
    opt.ffd_backend = backend;
    opt.overlays.lattices_in_place.push_back({"blob", pressed});
    const std::vector<unsigned char> live = render(r, scene, cam, opt);
    EXPECT_GT(diff(live, own).frac_over, 0.02) << core::to_string(backend) << ": the preview should show";
    EXPECT_LT(diff(live, ref).mean, 0.5) << core::to_string(backend);
    EXPECT_LT(diff(live, ref).frac_over, 0.002) << core::to_string(backend);
    opt.overlays.lattices_in_place.clear();
    EXPECT_LT(diff(render(r, scene, cam, opt), own).frac_over, 0.002) << core::to_string(backend) << ": own again";
  }
}

// Per-binding caching: an unchanged object is not re-evaluated; a press (new binding, same parameters) or a new time
// on an animated object is.
TEST_F(GlTest, FfdRendererEvaluatesOnlyWhatChanged) {
  core::Scene scene;
  scene.insert(deformed_ball());
  const std::size_t nv = scene.objects()[0].world_mesh->positions.size();
  Renderer r;
  ViewOptions opt;
  const core::Camera cam = front_camera(64, 48);
  OffscreenTarget target(64, 48, 1);
  target.bind();
  auto draw = [&] {
    r.draw(scene, cam, opt);
    return r.last_stats();
  };
  for (core::FfdBackend b : {core::FfdBackend::glsl_compute, core::FfdBackend::cpu_fast}) {
    opt.ffd_backend = b;
    EXPECT_EQ(draw().ffd_vertices, nv) << core::to_string(b);
    const RenderStats again = draw();
    EXPECT_EQ(again.ffd_vertices, 0u) << core::to_string(b);
    EXPECT_EQ(again.ffd_objects, 1);
    EXPECT_EQ(again.uploads, 0);
    opt.time_s += 1.0;  // not animated: time does not matter
    EXPECT_EQ(draw().ffd_vertices, 0u) << core::to_string(b);
  }
  // A press: same parameters, moved control points.
  core::SceneObject pressed = scene.objects()[0];
  core::FfdBinding b2 = *pressed.ffd;
  b2.lattice.control_points()[7] += glm::dvec3(0.0, 0.2, 0.0);
  pressed.ffd = std::make_shared<const core::FfdBinding>(std::move(b2));
  scene.replace(pressed);
  EXPECT_EQ(draw().ffd_vertices, nv);
  EXPECT_EQ(draw().ffd_vertices, 0u);
  // Back to the CPU reference at the rest offset: world_mesh is drawn, re-uploaded once because it was overwritten.
  opt.ffd_backend = core::FfdBackend::cpu_ref;
  RenderStats s = draw();
  EXPECT_EQ(s.ffd_vertices, 0u);
  EXPECT_EQ(s.uploads, 1);
  EXPECT_EQ(draw().uploads, 0);
  // Animated under glsl_compute: the vertex path evaluates every draw.
  pressed.offset_velocity = {0.1, 0.0, 0.0};
  scene.replace(pressed);
  opt.ffd_backend = core::FfdBackend::glsl_compute;
  EXPECT_EQ(draw().ffd_vertices, nv);
  opt.time_s += 0.1;
  s = draw();
  EXPECT_EQ(s.ffd_vertices, nv);
  EXPECT_STRNE(s.timer_mode, "");
  EXPECT_GE(s.draw_ms, 0.0);
  EXPECT_GE(s.ffd_ms, 0.0);
  std::printf("timer: %s; ffd %.3f ms, draw %.3f ms\n", s.timer_mode, s.ffd_ms, s.draw_ms);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// A lattice the float backends cannot take (order 5 along u) is shown through the CPU reference, not an exception.
TEST_F(GlTest, FfdRendererFallsBackToTheCpuReferenceForOtherOrders) {
  core::SceneObject o = deformed_ball();
  core::FfdBinding b = *o.ffd;
  b.lattice = core::TrivariateBSpline<glm::dvec3>(core::KnotVector::clamped_uniform(5, 5), b.lattice.knots(1),
                                                  b.lattice.knots(2), b.lattice.control_points());
  o.ffd = std::make_shared<const core::FfdBinding>(std::move(b));
  o.refresh();
  core::Scene scene;
  scene.insert(o);
  Renderer r;
  ViewOptions opt;
  opt.ffd_backend = core::FfdBackend::cpu_ref;
  const std::vector<unsigned char> ref = render(r, scene, front_camera(), opt);
  for (core::FfdBackend backend : kBackends) {
    opt.ffd_backend = backend;
    std::vector<unsigned char> img;
    ASSERT_NO_THROW(img = render(r, scene, front_camera(), opt)) << core::to_string(backend);
    EXPECT_EQ(img, ref) << core::to_string(backend);
  }
}

}  // namespace trispline::gpu::test
