#include <epoxy/gl.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "gl_test.h"
#include "gpu/gl/gl_debug.h"
#include "gpu/gl/timer.h"

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
  EXPECT_STREQ(wall.mode_description(),
               "GPU: glFinish + wall clock (software renderer: llvmpipe timer queries are unreliable)");
  EXPECT_STREQ(GpuTimer::describe(GpuTimer::Mode::timer_query), "GPU: GL_TIME_ELAPSED queries");
  wall.begin();
  wall.end();
  EXPECT_GE(wall.last_ms(), 0.0);
}

TEST_F(GlTest, WallClockTimerMeasuresTheTimeBetweenBeginAndEnd) {
  GpuTimer wall(GpuTimer::Mode::wall_clock_finish);
  wall.begin();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  wall.end();
  EXPECT_GE(wall.last_ms(), 19.0);
  EXPECT_LT(wall.last_ms(), 2000.0);
  EXPECT_EQ(wall.in_flight(), 0);
}

// The query ring's protocol, run on whatever context the tests have (on llvmpipe the values are meaningless, the
// bookkeeping is not): at most kQueriesInFlight queries pending, none read before it is available, every issued
// query eventually read, and no GL error (e.g. from beginning a query that is still active).
TEST_F(GlTest, QueryTimerKeepsAtMostThreeInFlightAndNeverWaits) {
  GpuTimer t(GpuTimer::Mode::timer_query);
  EXPECT_EQ(t.mode(), GpuTimer::Mode::timer_query);
  OffscreenTarget target(128, 128);
  Renderer r;
  core::Scene scene;
  scene.insert(make_object("ball", uv_sphere({0, 0, 0}, 1.0), {0.5f, 0.5f, 0.5f}));
  while (glGetError() != GL_NO_ERROR) {
  }
  for (int frame = 0; frame < 30; ++frame) {
    t.begin();
    EXPECT_LE(t.in_flight(), GpuTimer::kQueriesInFlight);
    target.bind();
    r.draw(scene, front_camera(128, 128), {});
    t.end();
    EXPECT_LE(t.in_flight(), GpuTimer::kQueriesInFlight);
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  glFinish();  // every query's result is available now; collect() reads them without waiting
  t.collect();
  EXPECT_EQ(t.in_flight(), 0);
  EXPECT_GE(t.last_ms(), 0.0);
  EXPECT_LE(t.skipped(), 30);
  // begin/end with no work in between still yields a (small) result once finished.
  GpuTimer empty(GpuTimer::Mode::timer_query);
  empty.begin();
  empty.end();
  glFinish();
  empty.collect();
  EXPECT_GE(empty.last_ms(), 0.0);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
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
