#include "ui/main_menu.h"

#include <imgui.h>

namespace trispline::ui {

gpu::ViewOptions view_options(const ViewToggles& t) {
  gpu::ViewOptions o;
  o.show_lattice = t.show_lattice;
  o.show_contact_surface = t.show_contact_surface;
  o.show_grid = t.show_grid;
  o.wireframe = t.wireframe;
  return o;
}

MenuAction draw_main_menu(ViewToggles& view, const MenuState& state) {
  MenuAction action = MenuAction::None;
  if (!ImGui::BeginMainMenuBar()) return action;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) action = MenuAction::New;
    if (ImGui::MenuItem("Open...", "Ctrl+O")) action = MenuAction::Open;
    ImGui::Separator();
    if (ImGui::MenuItem("Save", "Ctrl+S")) action = MenuAction::Save;
    if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S")) action = MenuAction::SaveAs;
    ImGui::Separator();
    if (ImGui::MenuItem("Save Screenshot", "F12")) action = MenuAction::Screenshot;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) action = MenuAction::Quit;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo = state.can_undo ? "Undo " + state.undo_label : std::string("Undo");
    const std::string redo = state.can_redo ? "Redo " + state.redo_label : std::string("Redo");
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, state.can_undo)) action = MenuAction::Undo;
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Shift+Z", false, state.can_redo)) action = MenuAction::Redo;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Lattice", nullptr, &view.show_lattice);
    ImGui::MenuItem("Contact surface", nullptr, &view.show_contact_surface);
    ImGui::MenuItem("Grid", nullptr, &view.show_grid);
    ImGui::MenuItem("Wireframe", nullptr, &view.wireframe);
    ImGui::Separator();
    ImGui::MenuItem("Timing overlay", nullptr, &view.timing_overlay);
    ImGui::MenuItem("Tool panel", nullptr, &view.show_tool_panel);
    ImGui::MenuItem("Scene && History panels", nullptr, &view.show_side_panels);
    ImGui::MenuItem("Log panel", nullptr, &view.show_log_panel);
    ImGui::Separator();
    if (ImGui::MenuItem("Frame selected", "F / Numpad .")) action = MenuAction::FrameSelected;
    if (ImGui::MenuItem("Frame all", "Home")) action = MenuAction::FrameAll;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Keys and mouse")) action = MenuAction::Keys;
    if (ImGui::MenuItem("About trispline")) action = MenuAction::About;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
  return action;
}

}  // namespace trispline::ui
