// The fixture every tool test drives a tool through: an editor session with its Log, the view, selection and hidden
// set, the ToolContext over them (deferred work runs at once), the tool, and what a test asks afterwards.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "editor/navigation.h"
#include "editor/session.h"
#include "editor/tools/select_tool.h"
#include "editor/tools/tool.h"

namespace trispline::test {

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
  void frame_view_on(const std::string& object) {
    editor::Navigator nav;
    nav.frame(editor::bounds_of(*s.scene().find(object)->world_mesh), {800, 600});
    view = nav.camera({800, 600});
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
  std::set<std::string> hidden;
  editor::ToolContext ctx{s, view, selected, hidden, [](std::string, std::function<void()> work) { work(); }};
  T tool;
};

}  // namespace trispline::test
