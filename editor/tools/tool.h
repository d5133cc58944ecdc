// trispline::editor::Tool — an interactive viewport tool (Select, Sketch placement, later pressing, incisions…).
// A tool reads mouse input over the viewport, draws its parameters in the Tool panel, decorates the view
// (e.g. the stroke being sketched) and changes the document only by executing commands through the session.
#pragma once

#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "core/scene/camera.h"
#include "gpu/render/renderer.h"
#include "ui/tool_panel.h"

namespace trispline::editor {

class EditorSession;

// Mouse state for the active tool; only filled when ImGui does not want the mouse and navigation does not own
// the left button.
struct ToolInput {
  glm::dvec2 mouse_px{0};     // viewport pixels, top-left origin (framebuffer pixels)
  bool left_pressed = false;  // went down this frame
  bool left_down = false;
  bool left_released = false;  // went up this frame
  bool shift = false, ctrl = false;
};

struct ToolContext {
  EditorSession& session;
  const core::Camera& view;  // the current view; viewport = window framebuffer size
  std::string& selected;     // selected object name ("" = none)
  // Runs `work` after one frame showing "Working… <what>" (long synchronous commands).
  std::function<void(std::string what, std::function<void()> work)> defer;
  // Builds a long command (`line`: ddm.fill, ddm.bake) on a worker thread behind a progress bar with Cancel
  // (editor/session/background_command.h); `what` is the bar's text, `verb` the Log's "<verb> cancelled". Unset (tool
  // tests): the tools run the line through defer.
  std::function<void(const nlohmann::json& line, std::string what, std::string verb)> background;
  // Asks for a file to write in the editor's Save dialog: `title`, one `extension` (".png"), the proposed `name`;
  // `chosen` runs with the absolute path (the extension added when missing) after the user confirms, nothing on
  // Cancel. Unset (tool tests without the app): the tool's export buttons are disabled.
  std::function<void(std::string title, std::string extension, std::string name,
                     std::function<void(const std::filesystem::path&)> chosen)>
      save_file;

  // Executes `line` after one frame showing "Working… <what>": one undoable step; a refused line leaves the scene as
  // it was and the Log panel says why.
  void execute_deferred(std::string what, nlohmann::json line) const;
  // A long line (ddm.fill, ddm.bake) behind `background`'s progress bar, or execute_deferred when there is none.
  void execute_long(nlohmann::json line, std::string what, const std::string& verb) const;
};

class Tool {
 public:
  virtual ~Tool() = default;
  virtual ui::ToolEntry entry() const = 0;  // name, shortcut, tooltip for the selector
  virtual void activate(ToolContext&) {}    // became the active tool
  virtual void deactivate(ToolContext&) {}  // another tool was chosen: drop transient state
  virtual void handle_input(const ToolInput& in, ToolContext& ctx) = 0;
  virtual void mouse_away() {}  // the viewport does not get the mouse this frame (over a panel, navigating)
  virtual void draw_panel(ToolContext& ctx) = 0;     // inside the Tool window, below the selector
  virtual void decorate(gpu::ViewOptions&) const {}  // view overlays (stroke being drawn)
  virtual std::string hint() const { return {}; }    // status-bar hint
  // True while a drag of this tool is under way (a stroke being drawn): the editor then leaves the camera alone.
  virtual bool owns_mouse() const { return false; }
  // A lattice to show instead of an object's own while the tool edits it live (the Press tool's drag preview):
  // the app draws that object with it (gpu::Overlays::lattices_in_place). Called once per frame.
  struct LivePreview {
    std::string object;
    std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice;  // same counts, orders, knots as the object's
  };
  virtual std::optional<LivePreview> live_preview(const ToolContext&) { return std::nullopt; }
};

}  // namespace trispline::editor
