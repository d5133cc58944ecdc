// trispline::ui main menu bar — File / Edit / View / Help. Returns what was picked; the editor acts on it.
// The View toggles are edited in place (they are view state, not document changes).
#pragma once

#include <string>

#include "core/ffd/ffd_evaluator.h"
#include "gpu/render/renderer.h"

namespace trispline::ui {

// The View menu's state: the renderer's display switches (View > Lattice, Contact surface, Grid, Wireframe,
// Discontinuities, FFD evaluator: they change live) and the editor's own.
struct ViewToggles : gpu::DisplaySwitches {
  bool timing_overlay = true;   // View > Timing overlay, F7
  bool play_animation = false;  // View > Play animation, Space: the timeline plays (Blender starts paused)
  bool show_timeline = true;    // View > Timeline panel
  bool show_tool_panel = true;
  bool show_side_panels = true;  // Scene + History
  bool show_log_panel = true;
  bool show_error_bounds = false;      // View > Error bounds: the certified deformation-error heat map
  bool show_fold_certificate = false;  // View > Fold certificate: the lattice's cells by their det J certificate
  // View > Fast tiles: cull tile instances out of view or facing away, thin them while the view moves
  // (gpu::DdmViewOptions; the editor fills the motion budget)
  bool fast_tiles = true;
};

// The renderer's options for these toggles (selection and stroke are filled in by the editor).
gpu::ViewOptions view_options(const ViewToggles& toggles);

enum class MenuAction {
  None,
  New,
  Open,
  Save,
  SaveAs,
  Quit,
  Undo,
  Redo,
  FrameSelected,
  FrameAll,
  About,
  Keys,
  Screenshot,  // File > Save Screenshot (F12): the whole window as a PNG in the current folder
  SelectTool,  // keyboard only (ui/shortcuts.h) from here on
  SketchTool,
  PressTool,
  Delete,
  ToggleTimingOverlay,  // F7 (View > Timing overlay is a checkbox edited in place)
  TogglePlayback,       // Space, as Blender's Play (View > Play animation)
  InsertKeyframe,       // I: key the selected object's offset at the current frame (anim.keyframe)
  DeleteKeyframe,       // Alt+I: delete its key at the current frame
  FramePrev,            // Left / Right: one frame back / forward
  FrameNext,
  FrameStart,  // Shift+Left / Shift+Right: first / last frame of the timeline
  FrameEnd,
  RecordAnimation  // File > Record animation..., Ctrl+F12 (Blender's Render Animation)
};

struct MenuState {
  bool can_undo = false, can_redo = false;
  std::string undo_label, redo_label;  // label of the command undo/redo would affect
  bool has_document_path = false;      // Save writes without asking
  bool material_shading = false;       // the viewport draws Material shading (View > Shading shows it checked)
};

// Draws the main menu bar; height via ImGui::GetFrameHeight().
MenuAction draw_main_menu(ViewToggles& view, const MenuState& state);

// Applies an action that only changes view state (ToggleTimingOverlay, TogglePlayback) to `view`; true if it was
// one.
bool apply_view_action(ViewToggles& view, MenuAction action);

// The "FFD evaluator" combo (View menu): GLSL compute / GLSL vertex shader / CPU fast / CPU reference, with a
// tooltip per entry. True when the user picked another backend.
bool ffd_backend_combo(core::FfdBackend& backend);

}  // namespace trispline::ui
