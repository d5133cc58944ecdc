#include "ui/main_menu.h"

#include "ui/frame_timings.h"

#include <imgui.h>

namespace trispline::ui {

gpu::ViewOptions view_options(const ViewToggles& t) {
  gpu::ViewOptions o;
  o.show_lattice = t.show_lattice;
  o.show_discontinuities = t.show_discontinuities;
  o.show_contact_surface = t.show_contact_surface;
  o.show_grid = t.show_grid;
  o.wireframe = t.wireframe;
  o.ffd_backend = t.ffd_backend;
  return o;
}

bool apply_view_action(ViewToggles& view, MenuAction action) {
  if (action == MenuAction::ToggleTimingOverlay) {
    view.timing_overlay = !view.timing_overlay;
    return true;
  }
  if (action == MenuAction::TogglePlayback) {
    view.play_animation = !view.play_animation;
    return true;
  }
  return false;
}

bool ffd_backend_combo(core::FfdBackend& backend) {
  bool changed = false;
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("GLSL vertex shader").x + ImGui::GetFrameHeight() * 2);
  if (ImGui::BeginCombo("FFD evaluator", ffd_backend_label(backend))) {
    for (const core::FfdBackend b : kFfdBackendsShown) {
      if (ImGui::Selectable(ffd_backend_label(b), b == backend) && b != backend) {
        backend = b;
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", ffd_backend_tooltip(b));
      if (b == backend) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Which backend evaluates the deformed objects in the viewport. Nothing visible changes\n"
        "between backends except speed (see the timing overlay, F7).\n\n%s",
        ffd_backend_tooltip(backend));
  return changed;
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
    if (ImGui::MenuItem("Record animation...", "Ctrl+F12")) action = MenuAction::RecordAnimation;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Render the timeline's frames to PNG/EXR images, an animated GLB and an MP4 (anim.record)");
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
    ImGui::MenuItem("Discontinuities", nullptr, &view.show_discontinuities);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("C-1 breaks of discontinuous FFD lattices and of the incision preview's cut lattice:\n"
                        "the F- plane's control points in red-orange, F+ in cyan (coincident until opened),\n"
                        "for every DFFD object with Lattice on, else for the selected one.");
    ImGui::MenuItem("Contact surface", nullptr, &view.show_contact_surface);
    ImGui::MenuItem("Grid", nullptr, &view.show_grid);
    ImGui::MenuItem("Wireframe", nullptr, &view.wireframe);
    ImGui::Separator();
    ImGui::MenuItem("Timing overlay", "F7", &view.timing_overlay);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Frame time and FPS, FFD / render / UI pass times, FFD vertices per second, a 5 s graph\n"
                        "and the last command's time per stage, in the viewport's corner.");
    ffd_backend_combo(view.ffd_backend);
    ImGui::MenuItem("Play animation", "Space", &view.play_animation);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Play the timeline: the frame advances at the timeline's fps and loops at its end frame;\n"
                        "animated objects (keys, lattice.animate_offset, glTF clips) move.");
    ImGui::MenuItem("Tool panel", nullptr, &view.show_tool_panel);
    ImGui::MenuItem("Scene && History panels", nullptr, &view.show_side_panels);
    ImGui::MenuItem("Log panel", nullptr, &view.show_log_panel);
    ImGui::MenuItem("Timeline panel", nullptr, &view.show_timeline);
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
