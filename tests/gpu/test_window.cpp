// The GLFW window needs a display: without one it must throw GlContextError (with GLFW's reason); with one
// (e.g. under `xvfb-run -a`) it must give a ≥ 4.3 core context.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "gpu/gl/window.h"

namespace trispline::gpu {

TEST(Window, OpensWithADisplayAndThrowsWithout) {
  const bool have_display = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
  WindowOptions opt;
  opt.visible = false;
  if (!have_display) {
    try {
      Window w("trispline test", 320, 200, opt);
      FAIL() << "a window opened without a display";
    } catch (const GlContextError& e) {
      EXPECT_NE(std::string(e.what()).find("glfwInit"), std::string::npos) << e.what();
    }
    return;
  }
  Window w("trispline test", 320, 200, opt);
  w.make_current();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 43);
  EXPECT_GT(w.framebuffer_size().x, 0);
  EXPECT_FALSE(w.should_close());
  w.set_should_close(true);
  EXPECT_TRUE(w.should_close());
  EXPECT_NE(w.native(), nullptr);
  w.swap();
  Window::poll_events();
}

TEST(Window, RejectsBadSize) { EXPECT_THROW(Window("x", 0, 10), std::invalid_argument); }

}  // namespace trispline::gpu
