#include "ui/shortcuts.h"

#include <imgui.h>

#include "ui/imgui_host.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace trispline::ui {

MenuAction shortcut_action(const KeyPress& k) {
  using A = MenuAction;
  const bool ctrl = k.mods & GLFW_MOD_CONTROL, shift = k.mods & GLFW_MOD_SHIFT, alt = k.mods & GLFW_MOD_ALT;
  const int key = k.key;
  if (ctrl) {
    if (key == GLFW_KEY_Z) return shift ? A::Redo : A::Undo;
    if (key == GLFW_KEY_Y) return A::Redo;
    if (key == GLFW_KEY_N) return A::New;
    if (key == GLFW_KEY_O) return A::Open;
    if (key == GLFW_KEY_S) return shift ? A::SaveAs : A::Save;
    if (key == GLFW_KEY_Q) return A::Quit;
    if (key == GLFW_KEY_F12) return A::RecordAnimation;  // Blender: Render Animation
    return A::None;
  }
  if (alt) return key == GLFW_KEY_I && !shift ? A::DeleteKeyframe : A::None;  // Blender: Alt+I deletes a key
  if (key == GLFW_KEY_F || key == GLFW_KEY_KP_DECIMAL) return A::FrameSelected;
  if (key == GLFW_KEY_HOME) return A::FrameAll;
  if (key == GLFW_KEY_Q) return A::SelectTool;
  if (key == GLFW_KEY_W) return A::SketchTool;
  if (key == GLFW_KEY_E) return A::PressTool;
  if (key == GLFW_KEY_DELETE || key == GLFW_KEY_X) return A::Delete;
  // F7: Blender leaves F5-F8 to the user, so it clashes with nothing a Blender user knows.
  if (key == GLFW_KEY_F7 && !shift) return A::ToggleTimingOverlay;
  if (key == GLFW_KEY_SPACE && !shift) return A::TogglePlayback;  // Blender: Space plays the animation
  // Blender's timeline keys: I inserts a keyframe, arrows step frames, Shift+arrows jump to the ends.
  if (key == GLFW_KEY_I && !shift) return A::InsertKeyframe;
  if (key == GLFW_KEY_LEFT) return shift ? A::FrameStart : A::FramePrev;
  if (key == GLFW_KEY_RIGHT) return shift ? A::FrameEnd : A::FrameNext;
  return A::None;
}

std::string tool_key(const KeyPress& k) {
  if (k.mods & (GLFW_MOD_CONTROL | GLFW_MOD_SHIFT | GLFW_MOD_ALT | GLFW_MOD_SUPER)) return {};
  if (k.key < GLFW_KEY_A || k.key > GLFW_KEY_Z || shortcut_action(k) != MenuAction::None) return {};
  return std::string(1, char('A' + (k.key - GLFW_KEY_A)));
}

std::string poll_tool_key() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureKeyboard || io.WantTextInput) return {};
  for (const KeyPress& k : ImGuiHost::key_presses())
    if (std::string letter = tool_key(k); !letter.empty()) return letter;
  return {};
}

bool ends_key_batch(const KeyPress& k) {
  return k.key == GLFW_KEY_F12 || shortcut_action(k) != MenuAction::None || !tool_key(k).empty();
}

MenuAction poll_shortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  const bool typing = io.WantCaptureKeyboard || io.WantTextInput;
  for (const KeyPress& k : ImGuiHost::key_presses()) {
    // F12 works over dialogs too: harmless, and handy for bug reports.
    if (k.key == GLFW_KEY_F12 && !(k.mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT))) return MenuAction::Screenshot;
    if (typing) continue;
    if (const MenuAction a = shortcut_action(k); a != MenuAction::None) return a;
  }
  return MenuAction::None;
}

}  // namespace trispline::ui
