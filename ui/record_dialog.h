// trispline::ui Record dialog and progress — the Timeline's Record button and File > Record animation...: a modal
// asking where and what to record (output folder, PNG/EXR, frame range, size, GLB and MP4), which returns the
// logged anim.record line for the editor to execute (editor/replay/record.h does the rendering), and the modal progress
// bar shown while the editor's Recorder renders one frame per UI frame.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/scene/scene.h"

namespace trispline::ui {

struct RecordDialogState {
  bool open = false;          // set to ask; cleared when the dialog closes
  std::string out_dir;        // output folder (the editor presets <state dir or cwd>/render)
  int format = 0;             // 0 png, 1 exr
  int frames[2] = {1, 120};   // inclusive timeline frames (preset to the whole timeline when opened)
  int size[2] = {1280, 720};  // pixels (preset to the viewport when opened)
  bool glb = true, mp4 = true;
  // The camera recorded: kSceneCamera (the scene's camera.set, else one framing the scene; no "camera" field) or
  // kCurrentView (the viewport's view, written into the line's "camera"). First preset: the scene camera when the
  // scene has one, else the current view; then the user's choice stays.
  int camera = -1;  // -1 = not chosen yet
  bool scene_camera_set = false;
  core::Camera view;  // the current view when the dialog opened
};
inline constexpr int kSceneCamera = 0, kCurrentView = 1;

// Presets the range to the whole timeline and the size to `viewport` (pixels), takes the current `view` and whether
// `scene` has a camera, and opens the dialog.
void open_record_dialog(RecordDialogState& state, const core::Timeline& timeline, int viewport_w, int viewport_h,
                        const core::Scene& scene, const core::Camera& view);

// {"cmd":"anim.record","out":DIR,"format":"png","frames":[A,B],"glb":true,"mp4":true,"width":W,"height":H}, with
// "camera" (camera.set's fields) when state.camera is kCurrentView.
nlohmann::json record_line(const RecordDialogState& state);

// Draws the modal while state.open; returns the anim.record line when the user presses Record.
std::optional<nlohmann::json> draw_record_dialog(RecordDialogState& state, const core::Timeline& timeline);

struct RecordProgress {
  int done = 0, total = 0;     // frames
  double seconds_left = -1.0;  // < 0: unknown yet
  int frame = 0;               // the frame being rendered
  std::string out_dir;
  bool close = false;  // the recording ended: close the modal this frame
};

// Draws the modal "Recording…" progress bar; returns true when Cancel was pressed.
bool draw_record_progress(const RecordProgress& progress);

}  // namespace trispline::ui
