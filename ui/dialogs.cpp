#include "ui/dialogs.h"

#include <imgui.h>

#include "ui/theme.h"

namespace trispline::ui {

namespace {
void center_next_window() {
  const ImVec2 d = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(d.x * 0.5f, d.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
}

// Two-column table of key bindings.
void key_rows(const char* const (*rows)[2], int n) {
  if (!ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) return;
  for (int i = 0; i < n; ++i) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextColored(colors::accent, "%s", rows[i][0]);
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(rows[i][1]);
  }
  ImGui::EndTable();
}
}  // namespace

void draw_about_window(bool* open, const std::string& gl_renderer) {
  if (!*open) return;
  center_next_window();
  if (ImGui::Begin("About trispline", open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("trispline");
    ImGui::TextColored(colors::dim, "Interactive modeling with trivariate tensor-product B-spline functions");
    ImGui::Separator();
    ImGui::TextUnformatted("Sketch placement: objects deformed along a stroke over the scene");
    ImGui::TextUnformatted("(free-form deformation with a lattice fitted to ray hits).");
    ImGui::Spacing();
    ImGui::TextColored(colors::dim, "Dear ImGui %s", ImGui::GetVersion());
    ImGui::TextColored(colors::dim, "OpenGL: %s", gl_renderer.c_str());
  }
  ImGui::End();
}

void draw_keys_window(bool* open) {
  if (!*open) return;
  static const char* const rows[][2] = {
      {"Middle drag", "orbit around the pivot"},
      {"Shift + middle drag", "pan"},
      {"Wheel", "zoom toward the cursor"},
      {"Alt + left drag", "orbit (trackpads)"},
      {"Alt + Shift + left drag", "pan (trackpads)"},
      {"F / Numpad .", "frame the selected object"},
      {"Home", "frame all"},
      {"Left click", "Select tool: pick an object"},
      {"Left drag", "Sketch tool: draw a placement stroke"},
      {"Q / W / E", "Select tool / Sketch placement tool / Press tool"},
      {"K", "Incision tool (like Blender's Knife): drag on a surface to cut it (seed §6.4)"},
      {"G / R / S", "grab / rotate / scale the selected object (then X/Y/Z axis, typed value, Enter / Esc)"},
      {"X / Delete", "remove the selected object (during G / R / S: X is the x axis)"},
      {"Ctrl+Z", "undo"},
      {"Ctrl+Shift+Z / Ctrl+Y", "redo"},
      {"Ctrl+N / Ctrl+O / Ctrl+S", "new / open / save"},
      {"Ctrl+Shift+S", "save as"},
      {"Ctrl+Q", "quit"},
      {"F7", "timing overlay on/off (FPS, FFD / render / UI times, graph)"},
      {"Space", "play / pause the timeline (loops at its end frame)"},
      {"Left / Right", "previous / next frame"},
      {"Shift+Left / Shift+Right", "first / last frame of the timeline"},
      {"I / Alt+I", "insert / delete a keyframe of the selected object's offset"},
      {"Ctrl+F12", "record the animation (images, GLB, MP4)"},
      {"F12", "save a screenshot of the window (PNG, current folder)"},
  };
  center_next_window();
  if (ImGui::Begin("Keys and mouse", open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
    key_rows(rows, int(sizeof rows / sizeof rows[0]));
  ImGui::End();
}

RecoverChoice draw_recover_prompt(std::size_t command_count, const std::string& log_path) {
  RecoverChoice choice = RecoverChoice::Pending;
  const char* id = "Recover unfinished session?";
  if (!ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  center_next_window();
  if (ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("The previous session did not end cleanly.");
    ImGui::Text("Recover it by replaying its %zu command%s?", command_count, command_count == 1 ? "" : "s");
    ImGui::TextColored(colors::dim, "%s", log_path.c_str());
    ImGui::Spacing();
    if (ImGui::Button("Recover", ImVec2(120, 0))) choice = RecoverChoice::Recover;
    ImGui::SetItemDefaultFocus();
    ImGui::SameLine();
    if (ImGui::Button("Discard", ImVec2(120, 0))) choice = RecoverChoice::Discard;
    if (choice != RecoverChoice::Pending) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return choice;
}

QuitChoice draw_quit_prompt(const std::string& document, const char* doing) {
  QuitChoice choice = QuitChoice::Pending;
  const char* id = "Save changes?";
  if (!ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  center_next_window();
  if (ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("Save changes to %s before %s?", document.c_str(), doing);
    ImGui::TextColored(colors::dim, "Don't save discards the commands since the last save.");
    ImGui::Spacing();
    if (ImGui::Button("Save", ImVec2(100, 0))) choice = QuitChoice::SaveAndQuit;
    ImGui::SameLine();
    if (ImGui::Button("Don't save", ImVec2(100, 0))) choice = QuitChoice::Quit;
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(100, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
      choice = QuitChoice::Cancel;
    if (choice != QuitChoice::Pending) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return choice;
}

}  // namespace trispline::ui
