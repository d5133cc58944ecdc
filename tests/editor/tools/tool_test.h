// The fixture every tool test drives a tool through: an editor session with its Log, the view and selection, the
// ToolContext over them (deferred work runs at once), the tool, and what a test asks afterwards; and the
// mouse gestures (press, move, release, drag) every tool test makes.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/tool.h"

namespace trispline::test {

// Mouse gestures in viewport pixels; `in` keeps the button state between the calls of one gesture.
// Left button down at `px`.
inline void press(editor::Tool& tool, editor::ToolContext& ctx, editor::ToolInput& in, glm::dvec2 px) {
  in.mouse_px = px;
  in.left_pressed = in.left_down = true;
  tool.handle_input(in, ctx);
  in.left_pressed = false;
}

// Moves over `px` in turn (with the button as `in` has it).
inline void move_through(editor::Tool& tool, editor::ToolContext& ctx, editor::ToolInput& in,
                         const std::vector<glm::dvec2>& px) {
  for (const glm::dvec2& p : px) {
    in.mouse_px = p;
    tool.handle_input(in, ctx);
  }
}

// Left button up where the mouse is.
inline void release(editor::Tool& tool, editor::ToolContext& ctx, editor::ToolInput& in) {
  in.left_down = false;
  in.left_released = true;
  tool.handle_input(in, ctx);
  in.left_released = false;
}

// Button down at the first pixel, moves over the others, up at the last one.
inline void drag(editor::Tool& tool, editor::ToolContext& ctx, editor::ToolInput& in,
                 const std::vector<glm::dvec2>& px) {
  press(tool, ctx, in, px.front());
  move_through(tool, ctx, in, {px.begin() + 1, px.end()});
  release(tool, ctx, in);
}

// A view of 800 × 600 pixels framing `object` of `scene`, as F does.
inline core::Camera framed_view(const core::Scene& scene, const std::string& object) {
  editor::Navigator nav;
  nav.frame(core::mesh_bounds(*scene.find(object)->world_mesh), {800, 600});
  return nav.camera({800, 600});
}

template <class T>
class ToolTest : public ::testing::Test {
 protected:
  // How many applied history entries are `cmd` commands.
  std::size_t count(const std::string& cmd) const {
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.history().applied(); ++i) n += s.history().at(i).id() == cmd;
    return n;
  }
  // Whether the Log holds an error containing `part`.
  bool logged_error(const std::string& part) const {
    for (const auto& m : messages.messages())
      if (m.severity == ui::Severity::Error && m.text.find(part) != std::string::npos) return true;
    return false;
  }
  std::string last_message() const { return messages.messages().empty() ? "" : messages.messages().back().text; }

  // Frames `object` in an 800 × 600 view, as F does.
  void frame_view_on(const std::string& object) { view = framed_view(s.scene(), object); }
  // The gestures with the fixture's tool and `in` (a fresh one at each press; `ctrl` held through a drag).
  void press(glm::dvec2 px) {
    in = {};
    test::press(tool, ctx, in, px);
  }
  void move_through(const std::vector<glm::dvec2>& px) { test::move_through(tool, ctx, in, px); }
  void release() { test::release(tool, ctx, in); }
  void drag(const std::vector<glm::dvec2>& px, bool ctrl = false) {
    in = {};
    in.ctrl = ctrl;
    test::drag(tool, ctx, in, px);
  }
  // The pixels (x, 300 + slope·(x − 400)), x every 4 px, whose x on row 300 hits an object (viewport pixels).
  std::vector<glm::dvec2> row_hits(double slope = 0.0) const {
    std::vector<glm::dvec2> hits;
    for (double x = 0; x < 800; x += 4)
      if (editor::pick_object(s.scene(), view, {x, 300})) hits.push_back({x, 300 + slope * (x - 400)});
    return hits;
  }
  // The middle half of `px` (a stroke well inside the silhouette).
  static std::vector<glm::dvec2> middle_half(const std::vector<glm::dvec2>& px) {
    return {px.begin() + std::ptrdiff_t(px.size() / 4), px.end() - std::ptrdiff_t(px.size() / 4)};
  }

  ui::MessageLog messages;
  editor::EditorSession s{messages};
  core::Camera view;
  std::string selected;
  editor::ToolContext ctx{s, view, selected, [](std::string, std::function<void()> work) { work(); },
                          nullptr};  // no background builds: Fill and Bake run through defer
  T tool;
  editor::ToolInput in;
};

}  // namespace trispline::test
