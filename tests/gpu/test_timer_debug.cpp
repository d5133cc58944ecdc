#include <epoxy/gl.h>

#include "gl_test.h"
#include "gpu/gl_debug.h"
#include "gpu/timer.h"

namespace trispline::gpu::test {

TEST_F(GlTest, TimerReportsTimeInTheRightMode) {
  GpuTimer t;
  EXPECT_EQ(t.mode() == GpuTimer::Mode::wall_clock_finish, is_software_renderer()) << t.mode_description();
  EXPECT_LT(t.last_ms(), 0.0);
  OffscreenTarget target(256, 256);
  Renderer r;
  core::Scene scene;
  scene.insert(make_object("ball", uv_sphere({0, 0, 0}, 1.0), {0.5f, 0.5f, 0.5f}));
  // Query results arrive a frame or more later on GPUs; never waited for.
  for (int frame = 0; frame < 200 && t.last_ms() < 0.0; ++frame) {
    GpuTimer::Scope scope(t);
    target.bind();
    r.draw(scene, front_camera(256, 256), {});
  }
  EXPECT_GE(t.last_ms(), 0.0) << t.mode_description();
  std::printf("timer mode: %s, last %.3f ms\n", t.mode_description(), t.last_ms());

  GpuTimer wall(true);
  EXPECT_EQ(wall.mode(), GpuTimer::Mode::wall_clock_finish);
  wall.begin();
  wall.end();
  EXPECT_GE(wall.last_ms(), 0.0);
}

TEST_F(GlTest, DebugOutputRoutesErrorsToTheSink) {
  std::vector<GlDebugMessage> got;
  {
    GlDebugOutput out([&](const GlDebugMessage& m) { got.push_back(m); }, GlDebugMessage::Severity::low);
    ASSERT_TRUE(out.active());
    glEnable(0x1234);  // not a capability: GL_INVALID_ENUM
    EXPECT_EQ(glGetError(), GLenum(GL_INVALID_ENUM));
  }
  ASSERT_FALSE(got.empty()) << "no KHR_debug message for GL_INVALID_ENUM";
  EXPECT_EQ(got.front().type, "error");
  EXPECT_FALSE(format_gl_debug_message(got.front()).empty());
  std::printf("%s\n", format_gl_debug_message(got.front()).c_str());
  // After the GlDebugOutput is gone, nothing more arrives.
  const std::size_t n = got.size();
  glEnable(0x1234);
  glGetError();
  EXPECT_EQ(got.size(), n);
}

}  // namespace trispline::gpu::test
