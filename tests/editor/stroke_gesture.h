// Mouse gestures for Sketch placement tool tests: press, drag along a shallow arc, release (viewport pixels).
#pragma once

#include "editor/tools/sketch_tool.h"

namespace trispline::test {

// Left button down at (330, 330).
inline void press_stroke(editor::SketchTool& tool, editor::ToolContext& ctx, editor::ToolInput& in) {
  in.mouse_px = {330, 330};
  in.left_pressed = in.left_down = true;
  tool.handle_input(in, ctx);
  in.left_pressed = false;
}

// Drags along a shallow arc from x = 340 to 470 (over the middle of an 800×600 view).
inline void drag_stroke(editor::SketchTool& tool, editor::ToolContext& ctx, editor::ToolInput& in) {
  for (double x = 340; x <= 470; x += 10) {
    in.mouse_px = {x, 330 + 0.1 * (x - 400) * (x - 400) / 40};
    tool.handle_input(in, ctx);
  }
}

// Left button up: the tool executes its place.sketch.
inline void release_stroke(editor::SketchTool& tool, editor::ToolContext& ctx, editor::ToolInput& in) {
  in.left_down = false;
  in.left_released = true;
  tool.handle_input(in, ctx);
  in.left_released = false;
}

}  // namespace trispline::test
