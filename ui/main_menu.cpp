#include "ui/main_menu.h"

#include <imgui.h>

#include "ui/frame_timings.h"
#include "ui/gui_probe.h"
#include "ui/param_widgets.h"

namespace trispline::ui {

gpu::ViewOptions view_options(const ViewToggles& t) {
  gpu::ViewOptions o;
  static_cast<gpu::DisplaySwitches&>(o) = t;
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
  const bool open = ImGui::BeginCombo("FFD evaluator", ffd_backend_label(backend));
  probe::item("menu.FFD evaluator");
  if (open) {
    for (const core::FfdBackend b : kFfdBackendsShown) {
      if (ImGui::Selectable(ffd_backend_label(b), b == backend) && b != backend) {
        backend = b;
        changed = true;
      }
      probe::item(std::string("menu.FFD evaluator.") + ffd_backend_label(b));
      tooltip(ffd_backend_tooltip(b));
      if (b == backend) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  tooltip((std::string("Which backend evaluates the deformed objects in the viewport. Nothing visible changes\n"
                       "between backends except speed (see the timing overlay, F7).\n\n") +
           ffd_backend_tooltip(backend))
              .c_str());
  return changed;
}

namespace {

// A menu item that the GUI tests can find ("menu.<label>").
bool menu_item(const char* label, const char* shortcut = nullptr, bool selected = false, bool enabled = true) {
  const bool clicked = ImGui::MenuItem(label, shortcut, selected, enabled);
  probe::item(std::string("menu.") + label);
  return clicked;
}
bool menu_item(const char* label, const char* shortcut, bool* value) {
  const bool clicked = ImGui::MenuItem(label, shortcut, value);
  probe::item(std::string("menu.") + label);
  return clicked;
}

// Opens a menu of the main menu bar ("menu.<label>" for the tests). A pick closes it, and so does Esc.
bool begin_menu(const char* label) {
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const bool open = ImGui::BeginMenu(label);
  if (!open) {
    probe::item(std::string("menu.") + label);
  } else if (probe::enabled()) {  // ImGui's last item is now inside the menu: the header's rectangle, as laid out
    const ImVec2 size(ImGui::CalcTextSize(label).x + ImGui::GetStyle().ItemSpacing.x, ImGui::GetFrameHeight());
    probe::rect(std::string("menu.") + label, at, ImVec2(at.x + size.x, at.y + size.y));
  }
  if (open && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) ImGui::CloseCurrentPopup();
  return open;
}

// Ends a menu; `picked`: an item was chosen this frame, so the menu closes (whatever ImGui decided).
void end_menu(bool picked) {
  if (picked) ImGui::CloseCurrentPopup();
  ImGui::EndMenu();
}

}  // namespace

MenuAction draw_main_menu(ViewToggles& view, const MenuState& state) {
  MenuAction action = MenuAction::None;
  bool picked = false;  // a View toggle or the FFD evaluator changed
  if (!ImGui::BeginMainMenuBar()) return action;
  if (begin_menu("File")) {
    if (menu_item("New", "Ctrl+N")) action = MenuAction::New;
    if (menu_item("Open...", "Ctrl+O")) action = MenuAction::Open;
    ImGui::Separator();
    if (menu_item("Save", "Ctrl+S")) action = MenuAction::Save;
    if (menu_item("Save As...", "Ctrl+Shift+S")) action = MenuAction::SaveAs;
    ImGui::Separator();
    if (menu_item("Save Screenshot", "F12")) action = MenuAction::Screenshot;
    if (menu_item("Record animation...", "Ctrl+F12")) action = MenuAction::RecordAnimation;
    tooltip("Render the timeline's frames to PNG/EXR images, an animated GLB and an MP4 (anim.record)");
    ImGui::Separator();
    if (menu_item("Quit", "Ctrl+Q")) action = MenuAction::Quit;
    end_menu(action != MenuAction::None || picked);
  }
  if (begin_menu("Edit")) {
    const std::string undo = state.can_undo ? "Undo " + state.undo_label : std::string("Undo");
    const std::string redo = state.can_redo ? "Redo " + state.redo_label : std::string("Redo");
    if (menu_item(undo.c_str(), "Ctrl+Z", false, state.can_undo)) action = MenuAction::Undo;
    if (menu_item(redo.c_str(), "Ctrl+Shift+Z", false, state.can_redo)) action = MenuAction::Redo;
    end_menu(action != MenuAction::None || picked);
  }
  if (begin_menu("View")) {
    if (begin_menu("Shading")) {
      // Blender's Solid / Material Preview; until picked, Material when the scene has textures (state says which).
      const bool material = state.material_shading;
      if (menu_item("Solid", nullptr, !material)) view.shading = gpu::Shading::solid, picked = true;
      tooltip("Every object in its colour, cut surfaces in its inside colour.");
      if (menu_item("Material", nullptr, material)) view.shading = gpu::Shading::material, picked = true;
      tooltip(
          "Objects with materials (glTF, OBJ/MTL, ...) drawn with their textures, alpha cut-outs,\n"
          "blending and normal maps; objects without one stay in their colour.");
      end_menu(picked);
    }
    picked |= menu_item("Lattice", nullptr, &view.show_lattice);
    picked |= menu_item("Discontinuities", nullptr, &view.show_discontinuities);
    tooltip(
        "C-1 breaks of discontinuous FFD lattices and of the incision preview's cut lattice:\n"
        "the F- plane's control points in red-orange, F+ in cyan (coincident until opened),\n"
        "for every DFFD object with Lattice on, else for the selected one.");
    picked |= menu_item("Contact surface", nullptr, &view.show_contact_surface);
    picked |= menu_item("Grid", nullptr, &view.show_grid);
    picked |= menu_item("Wireframe", nullptr, &view.wireframe);
    picked |= menu_item("Fast tiles", nullptr, &view.fast_tiles);
    tooltip(
        "Large tile layers: leave out the tiles outside the view or facing away, and while the view\n"
        "moves draw only a share of them (full detail within a quarter second of stopping).\n"
        "Off: every tile in every frame, as replay and recordings draw them.");
    picked |= menu_item("Error bounds", nullptr, &view.show_error_bounds);
    tooltip(
        "Colour the selected deformed object's triangles by their certified deformation-error bound\n"
        "(how far the true deformed surface can be from the drawn triangle, world units; seed ch. 3),\n"
        "with a legend; follows a Press drag live.");
    picked |= menu_item("Fold certificate", nullptr, &view.show_fold_certificate);
    tooltip(
        "Draw the selected deformed object's lattice cells by their fold-free certificate:\n"
        "green certified det J > 0, red folding (red points: where), grey undecided.");
    ImGui::Separator();
    picked |= menu_item("Timing overlay", "F7", &view.timing_overlay);
    tooltip(
        "Frame time and FPS, FFD / render / UI pass times, FFD vertices per second, a 5 s graph\n"
        "and the last command's time per stage, in the viewport's corner.");
    picked |= ffd_backend_combo(view.ffd_backend);
    picked |= menu_item("Play animation", "Space", &view.play_animation);
    tooltip(
        "Play the timeline: the frame advances at the timeline's fps and loops at its end frame;\n"
        "animated objects (keys, lattice.animate_offset, glTF clips) move.");
    picked |= menu_item("Tool panel", nullptr, &view.show_tool_panel);
    picked |= menu_item("Scene & History panels", nullptr, &view.show_side_panels);
    picked |= menu_item("Log panel", nullptr, &view.show_log_panel);
    picked |= menu_item("Timeline panel", nullptr, &view.show_timeline);
    ImGui::Separator();
    if (menu_item("Frame selected", "F / Numpad .")) action = MenuAction::FrameSelected;
    if (menu_item("Frame all", "Home")) action = MenuAction::FrameAll;
    end_menu(action != MenuAction::None || picked);
  }
  if (begin_menu("Help")) {
    if (menu_item("Keys and mouse")) action = MenuAction::Keys;
    if (menu_item("About trispline")) action = MenuAction::About;
    end_menu(action != MenuAction::None || picked);
  }
  ImGui::EndMainMenuBar();
  return action;
}

}  // namespace trispline::ui
