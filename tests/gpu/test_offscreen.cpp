#include <epoxy/gl.h>

#include "gl_test.h"

namespace trispline::gpu::test {

class OffscreenSamples : public GlTest, public ::testing::WithParamInterface<int> {};

TEST_P(OffscreenSamples, ClearReadsBackExactly) {
  OffscreenTarget t(64, 32, GetParam());
  EXPECT_EQ(t.width(), 64);
  EXPECT_EQ(t.height(), 32);
  EXPECT_GE(t.samples(), 1);
  t.bind();
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.2f, 0.4f, 0.6f, 1.0f);  // 51, 102, 153 exactly after rounding
  glClear(GL_COLOR_BUFFER_BIT);
  const std::vector<unsigned char> img = t.read_rgba();
  ASSERT_EQ(img.size(), 64u * 32u * 4u);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const Rgba p = pixel(img, 64, x, y);
      ASSERT_EQ(p.r, 51);
      ASSERT_EQ(p.g, 102);
      ASSERT_EQ(p.b, 153);
      ASSERT_EQ(p.a, 255);
    }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_P(OffscreenSamples, RowsComeTopFirst) {
  OffscreenTarget t(16, 10, GetParam());
  t.bind();
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 5, 16, 5);  // GL's origin is bottom-left: this is the top half
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const std::vector<unsigned char> img = t.read_rgba();
  for (int y = 0; y < 10; ++y) {
    const Rgba p = pixel(img, 16, 7, y);
    EXPECT_EQ(p.r, y < 5 ? 255 : 0) << "row " << y;
    EXPECT_EQ(p.b, y < 5 ? 0 : 255) << "row " << y;
  }
  EXPECT_NE(t.resolve(), 0u);
}

INSTANTIATE_TEST_SUITE_P(SingleAndMsaa, OffscreenSamples, ::testing::Values(1, 4));

TEST_F(GlTest, OffscreenRejectsBadSize) { EXPECT_THROW(OffscreenTarget(0, 10), std::invalid_argument); }

}  // namespace trispline::gpu::test
