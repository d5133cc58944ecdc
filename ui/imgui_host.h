// trispline::ui::ImGuiHost — owns the Dear ImGui context on a GLFW window with the OpenGL 3 backend (Debian's
// libimgui.a ships both backends). One per window; the window's GL context must be current.
#pragma once

#include <string>
#include <vector>

struct GLFWwindow;

namespace trispline::ui {

// A key press with the modifiers held at that moment (GLFW key code, GLFW_MOD_* bits).
struct KeyPress {
  int key = 0;
  int mods = 0;
};

class ImGuiHost {
 public:
  // ini_path empty: no imgui.ini is read or written (fixed layout, e.g. for screenshots).
  // Throws std::runtime_error if a backend fails to initialise.
  ImGuiHost(GLFWwindow* window, const std::string& ini_path, float ui_scale = 1.0f);
  ~ImGuiHost();
  ImGuiHost(const ImGuiHost&) = delete;
  ImGuiHost& operator=(const ImGuiHost&) = delete;

  void new_frame();  // backends + ImGui::NewFrame()
  void render();     // ImGui::Render() + draw into the bound default framebuffer

  // Key presses since the previous new_frame(). ImGui 1.86 samples key state once per frame, so a press and
  // release between two frames (a quick tap on a slow frame) never shows in ImGui::IsKeyPressed; these do.
  static const std::vector<KeyPress>& key_presses();
  // Presses for which `ends_batch` is true end a frame's share of the queued presses: the presses after one wait for
  // the next frame (which follows at once), never dropped. So a shortcut pressed many times during a slow frame runs
  // as many times, in order, each on the state the one before left. Not while a text field has the keyboard (its
  // characters arrive apart from the key queue). Held-key repeats coalesce instead of queueing. While a widget is held
  // by the mouse (ImGui then captures the keyboard), every press waits for its release.
  static void set_batch_end(bool (*ends_batch)(const KeyPress&));
  // While held, new_frame() hands out only the presses before the first batch-ending one: the rest wait, in order.
  static void hold_batches(bool hold);
  // True once after input arrived (keys, characters, mouse buttons, motion, wheel, focus, the pointer entering or
  // leaving), or while a key tapped between two frames is still held down for ImGui: the next frame has input to
  // handle. An editor that draws only on change asks this after waiting for events.
  static bool take_input();
  // The left button's presses in a row, while the last one is recent (2: a double-click): a press within
  // max(0.3 s, 2.5 frame periods) of the one before continues the row, and the count holds for that long after it (the
  // widget reports its click a frame or two after the presses). ImGui 1.86 measures double-clicks in frame time and
  // sees one press per frame, so at software-GL frame rates it never reports one; this does. 0 without a recent press.
  static int click_count();

 private:
  GLFWwindow* window_;
  std::string ini_path_;  // ImGui keeps the char* we give it: must outlive the context
};

}  // namespace trispline::ui
