// StrokeGesture: the press / drag / release every stroke tool shares.
#include <gtest/gtest.h>

#include "editor/tools/stroke_gesture.h"

using namespace trispline;

namespace {

editor::ToolInput input(glm::dvec2 px, bool down, bool pressed = false, bool released = false) {
  editor::ToolInput in;
  in.mouse_px = px;
  in.left_down = down;
  in.left_pressed = pressed;
  in.left_released = released;
  return in;
}

TEST(StrokeGesture, CollectsSpacedPointsInTheViewAtMouseDown) {
  using E = editor::StrokeGesture::Event;
  editor::StrokeGesture g;
  core::Camera at_press;
  at_press.eye = {1, 2, 3};
  EXPECT_EQ(g.update(input({10, 10}, true, true), at_press), E::Began);
  EXPECT_TRUE(g.drawing());
  core::Camera later;
  later.eye = {9, 9, 9};
  EXPECT_EQ(g.update(input({11, 10}, true), later), E::None) << "closer than kMinSpacingPx: dropped";
  EXPECT_EQ(g.update(input({13, 10}, true), later), E::Moved);
  EXPECT_EQ(g.update(input({20, 12}, true), later), E::Moved);
  EXPECT_EQ(g.update(input({20, 12}, false, false, true), later), E::Ended);
  EXPECT_FALSE(g.drawing());
  EXPECT_EQ(g.view().eye, at_press.eye) << "the stroke's pixels belong to the view at mouse-down";
  const std::vector<glm::dvec2> stroke = g.take();
  ASSERT_EQ(stroke.size(), 3u);
  EXPECT_EQ(stroke[1], glm::dvec2(13, 10));
  EXPECT_TRUE(g.points().empty());
  EXPECT_EQ(g.update(input({30, 30}, false), later), E::None) << "no stroke without a press";
}

TEST(StrokeGesture, AClickWithinOneFrameEndsAtOnce) {
  editor::StrokeGesture g;
  EXPECT_EQ(g.update(input({5, 5}, false, true, true), core::Camera{}), editor::StrokeGesture::Event::Ended);
  EXPECT_FALSE(g.drawing());
  EXPECT_EQ(g.take().size(), 1u) << "one point: the tools treat it as a click";
}

TEST(StrokeGesture, LosingTheButtonEndsTheStroke) {
  editor::StrokeGesture g;
  g.update(input({5, 5}, true, true), core::Camera{});
  g.update(input({15, 5}, true), core::Camera{});
  EXPECT_EQ(g.update(input({25, 5}, false), core::Camera{}), editor::StrokeGesture::Event::Ended)
      << "the button is up without a release event (focus lost)";
  g.cancel();
  EXPECT_FALSE(g.drawing());
  EXPECT_TRUE(g.points().empty());
}

}  // namespace
