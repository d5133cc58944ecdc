#include <epoxy/gl.h>

#include <cstdio>

#include "gl_test.h"

namespace trispline::gpu::test {

TEST_F(GlTest, ContextIsCoreProfile43OrNewer) {
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 43);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_FALSE(context().renderer().empty());
  EXPECT_EQ(context().renderer(), current_gl_renderer());
  EXPECT_NE(context().version().find(std::to_string(major) + "." + std::to_string(minor)), std::string::npos);
  EXPECT_FALSE(context().platform().empty());
  std::printf("GL_RENDERER: %s\nGL_VERSION: %s\nEGL platform: %s\nsoftware: %d\n", context().renderer().c_str(),
              context().version().c_str(), context().platform().c_str(), int(is_software_renderer()));
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, SecondContextCanComeAndGo) {
  {
    HeadlessContext second;
    EXPECT_FALSE(second.renderer().empty());
  }
  // The first context (same EGL display) must still work after the second is destroyed.
  context().make_current();
  OffscreenTarget t(8, 8, 1);
  t.bind();
  glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  EXPECT_EQ(pixel(t.read_rgba(), 8, 3, 3).g, 255);
}

TEST_F(GlTest, SoftwareRendererDetection) {
  const std::string r = current_gl_renderer();
  if (r.find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(is_software_renderer());
  }
  if (r.find("NVIDIA") != std::string::npos) {
    EXPECT_FALSE(is_software_renderer());
  }
}

}  // namespace trispline::gpu::test
