// The Sketch placement tool in an editor session, as the session tests drive it: the tool over a view, placing the
// crate, and the stroke they draw (viewport pixels of an 800×600 view; gestures: tools/tool_test.h).
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "editor/tools/sketch_tool.h"
#include "tests/editor/tools/tool_test.h"

namespace trispline::test {

// A shallow arc over the middle of the view, every 10 px from x = `from` to 470.
inline std::vector<glm::dvec2> shallow_arc(double from) {
  std::vector<glm::dvec2> px;
  for (double x = from; x <= 470; x += 10) px.push_back({x, 330 + 0.1 * (x - 400) * (x - 400) / 40});
  return px;
}

// The Sketch tool, active in `s` over `view` (held by reference: a test may move it mid-stroke), placing the crate;
// deferred work runs at once.
struct SketchToolRig {
  SketchToolRig(editor::EditorSession& s, core::Camera& view)
      : ctx{s, view, selected, [](std::string, std::function<void()> work) { work(); }, nullptr} {
    tool.activate(ctx);
  }
  // Left button down at (330, 330).
  void press_stroke() { press(tool, ctx, in, {330, 330}); }
  // A drag along shallow_arc(340).
  void drag_stroke() { move_through(tool, ctx, in, shallow_arc(340)); }
  // Left button up: the tool executes its place.sketch.
  void release_stroke() { release(tool, ctx, in); }

  std::string selected = "crate";
  editor::ToolContext ctx;
  editor::SketchTool tool;
  editor::ToolInput in;
};

}  // namespace trispline::test
