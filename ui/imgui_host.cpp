#include "ui/imgui_host.h"

#include "ui/theme.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace trispline::ui {

namespace {
std::vector<KeyPress> g_pending, g_frame;  // one editor window per process
std::vector<int> g_forced;                 // keys held down artificially for one frame (see new_frame)

bool g_input = false;                             // input since the last take_input()
bool (*g_ends_batch)(const KeyPress&) = nullptr;  // ImGuiHost::set_batch_end
bool g_hold = false;                              // ImGuiHost::hold_batches

// Installed before ImGui's own callbacks, which chain to them (the backend of ImGui 1.86 polls the pointer position,
// so the cursor-position callback is ours alone).
// Left presses in a row: a press within max(0.3 s, 2.5 frame periods) of the one before continues it (a double-click
// at 2 fps still counts, whether its two presses arrive in one frame or in two). A period of a second or more is an
// idle editor waiting for events, not a frame: it is not counted.
int g_click_run = 0;
double g_last_press = -1e9, g_last_frame = -1e9, g_frame_seconds = 0.0;
double click_window() { return std::max(0.3, 2.5 * g_frame_seconds); }
void note_button(GLFWwindow*, int button, int action, int) {
  g_input = true;
  if (button != GLFW_MOUSE_BUTTON_LEFT || action != GLFW_PRESS) return;
  const double now = glfwGetTime();
  g_click_run = now - g_last_press <= click_window() ? g_click_run + 1 : 1;
  g_last_press = now;
}
void note_scroll(GLFWwindow*, double, double) { g_input = true; }
void note_char(GLFWwindow*, unsigned) { g_input = true; }
void note_focus(GLFWwindow*, int) { g_input = true; }
void note_cursor(GLFWwindow*, double, double) { g_input = true; }

void record_key(GLFWwindow*, int key, int, int action, int mods) {
  g_input = true;
  // Held Left / Right repeat (stepping frames, as in Blender); every other shortcut fires once per press.
  const bool repeats = action == GLFW_REPEAT && (key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT);
  // A repeat of the key already waiting is dropped: a key held through slow frames must not leave a backlog.
  if (repeats && !g_pending.empty() && g_pending.back().key == key) return;
  if (action == GLFW_PRESS || repeats) g_pending.push_back({key, mods});
}

// The default font (ProggyClean, 13 px) holds ASCII and Latin-1 only; labels also use dashes, ellipses, arrows, math
// signs and Greek letters ("Record frames 1-1 — not written again", "Working…", the α keys). Those glyphs are merged
// from DejaVu Sans Mono (Debian's fonts-dejavu-core) at the same size; without it they show as '?'.
void load_fonts(ImGuiIO& io) {
  io.Fonts->AddFontDefault();
  static const ImWchar extra[] = {0x0370, 0x03FF, 0x2010, 0x205E, 0x2190, 0x21FF, 0x2200, 0x22FF, 0x25A0, 0x25FF, 0};
  const char* path = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    std::fprintf(stderr, "trispline: %s not found (package fonts-dejavu-core): dashes and arrows show as '?'\n", path);
    return;
  }
  ImFontConfig merge;
  merge.MergeMode = true;
  merge.PixelSnapH = true;
  io.Fonts->AddFontFromFileTTF(path, 13.0f, &merge, extra);
}
}  // namespace

const std::vector<KeyPress>& ImGuiHost::key_presses() { return g_frame; }

int ImGuiHost::click_count() { return glfwGetTime() - g_last_press <= click_window() ? g_click_run : 0; }

void ImGuiHost::set_batch_end(bool (*ends_batch)(const KeyPress&)) { g_ends_batch = ends_batch; }
void ImGuiHost::hold_batches(bool hold) { g_hold = hold; }

bool ImGuiHost::take_input() { return std::exchange(g_input, false) || !g_forced.empty() || !g_pending.empty(); }

ImGuiHost::ImGuiHost(GLFWwindow* window, const std::string& ini_path, float ui_scale)
    : window_(window), ini_path_(ini_path) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = ini_path_.empty() ? nullptr : ini_path_.c_str();
  io.ConfigWindowsMoveFromTitleBarOnly = true;
  load_fonts(io);
  apply_dark_theme(ui_scale);
  glfwSetKeyCallback(window, record_key);
  glfwSetMouseButtonCallback(window, note_button);
  glfwSetScrollCallback(window, note_scroll);
  glfwSetCharCallback(window, note_char);
  glfwSetWindowFocusCallback(window, note_focus);
  glfwSetCursorEnterCallback(window, [](GLFWwindow*, int) { g_input = true; });
  glfwSetCursorPosCallback(window, note_cursor);
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) {
    ImGui::DestroyContext();
    throw std::runtime_error("Dear ImGui: GLFW backend failed to initialise");
  }
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    throw std::runtime_error("Dear ImGui: OpenGL3 backend failed to initialise");
  }
}

ImGuiHost::~ImGuiHost() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiHost::new_frame() {
  const double now = glfwGetTime();
  if (now - g_last_frame < 1.0) g_frame_seconds = now - g_last_frame;
  g_last_frame = now;
  std::size_t take = g_pending.size();
  // A widget still held from a click (on a slow frame a click's press and release arrive together, and the widget
  // stays active into the next frame) makes ImGui capture the keyboard: presses made meanwhile wait for its release
  // instead of being lost. Both answers are the last frame's; a text field typing takes its keys at once.
  if (ImGui::IsAnyItemActive() && !ImGui::GetIO().WantTextInput)
    take = 0;
  else if (g_ends_batch && !ImGui::GetIO().WantTextInput)  // the last frame's answer: whether a text field types
    for (std::size_t i = 0; i < g_pending.size(); ++i)
      if (g_ends_batch(g_pending[i])) {
        take = g_hold ? i : i + 1;
        break;
      }
  g_frame.assign(g_pending.begin(), g_pending.begin() + std::ptrdiff_t(take));
  g_pending.erase(g_pending.begin(), g_pending.begin() + std::ptrdiff_t(take));
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  // ImGui 1.86 reads io.KeysDown once per frame: a key pressed and released since the last frame (a quick tap on a
  // slow frame, e.g. Enter in a text field on llvmpipe) would never be seen. Hold such keys down for one frame.
  ImGuiIO& io = ImGui::GetIO();
  const int n_keys = int(sizeof io.KeysDown / sizeof io.KeysDown[0]);
  for (int key : g_forced) io.KeysDown[key] = glfwGetKey(window_, key) == GLFW_PRESS;
  g_forced.clear();
  int mods = 0;  // modifiers held with the keys pressed since the last frame
  for (const KeyPress& k : g_frame) {
    if (k.key < 0 || k.key >= n_keys) continue;
    if (!io.KeysDown[k.key]) {
      io.KeysDown[k.key] = true;
      g_forced.push_back(k.key);
    }
    mods |= k.mods;
  }
  // The backend sets the modifier flags in its key callback, so a Ctrl+A tapped between two frames reaches ImGui
  // with Ctrl already released: take them from the keys held this frame and the modifiers the presses came with.
  io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL] || (mods & GLFW_MOD_CONTROL);
  io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT] || (mods & GLFW_MOD_SHIFT);
  io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT] || (mods & GLFW_MOD_ALT);
  io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER] || (mods & GLFW_MOD_SUPER);
  ImGui::NewFrame();
}

void ImGuiHost::render() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace trispline::ui
