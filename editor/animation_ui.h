// trispline::editor animation UI — the editor's side of the timeline (seed §2.4.3): the playback clock (current
// frame and playing state: view state, never logged), the Timeline panel and its keys (I, Alt+I, arrows), the
// Record dialog and the recording in progress (editor/replay/record.h's Recorder, one frame per UI frame, modal
// progress), and the scene as drawn at the current frame (glTF clips posed by core::scene_with_posed_clips, cached per
// frame). Document changes go through the session as commands: anim.timeline, anim.keyframe, anim.record.
//
// Split from editor/app.cpp so tests drive it with a session and a headless Dear ImGui frame (no window).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "editor/replay/record.h"
#include "editor/session/session.h"
#include "ui/main_menu.h"
#include "ui/record_dialog.h"
#include "ui/timeline_panel.h"

namespace trispline::editor {

class AnimationUi {
 public:
  AnimationUi(EditorSession& session, ui::MessageLog& messages) : session_(session), messages_(messages) {}

  // Start of a UI frame: clamps the frame into the timeline (its range may have changed), reads the selected
  // object's keys, and takes the playing state (the View menu / Space toggle).
  void begin_frame(const std::string& selected, bool playing);
  // Draws the Timeline panel in `rect` and executes what it asked for (commands; Record opens the dialog).
  void draw_timeline(const ui::Rect& rect, glm::ivec2 viewport);
  // Timeline actions of the menu and keyboard (InsertKeyframe, DeleteKeyframe, FramePrev/Next/Start/End,
  // RecordAnimation); false for any other action.
  bool handle_action(ui::MenuAction action, glm::ivec2 viewport);
  // Playback: advances by `dt_s` seconds of real time (whole frames at the timeline's fps, looping at its end).
  void advance(double dt_s);
  // Draws the Record dialog and, while recording, the progress modal, and renders the next recorded frame.
  // `restore_context` makes the window's GL context current again (the Recorder renders in its own).
  void draw_record_ui(const std::function<void()>& restore_context);

  // Executes an anim.record line and starts the Recorder; false (message logged) when either fails.
  bool start_recording(const nlohmann::json& line, const std::function<void()>& restore_context = {});
  // History's "Run again" of outputs()[k]: an anim.record replayed without recording (Open, recovery) is recorded
  // from the scene it ran on, no new log line; any other output goes to EditorSession::run_again_output.
  bool run_again(std::size_t k, const std::function<void()>& restore_context = {});
  // The current view (the Record dialog offers it as the recorded camera); set every frame by the editor.
  void set_view(const core::Camera& view) { view_ = view; }

  // The document as drawn at the current frame: itself, or with viewport-visible clip objects a posed copy that is
  // recomputed only when the frame or the document changed. Valid until the next call.
  const core::Scene& drawn_scene();

  ui::Playback& playback() { return playback_; }
  const ui::Playback& playback() const { return playback_; }
  double time_s() const;  // timeline.time_of_frame(current frame), seconds
  bool recording() const { return recorder_ != nullptr; }
  const ui::TimelineObject& timeline_object() const { return object_; }
  ui::TimelinePanelState& panel_state() { return panel_; }
  ui::RecordDialogState& record_dialog() { return dialog_; }
  std::uint64_t poses_computed() const { return poses_computed_; }  // scene_with_posed_clips calls (tests)

 private:
  EditorSession& session_;
  ui::MessageLog& messages_;
  ui::Playback playback_;
  ui::TimelinePanelState panel_;
  ui::TimelineObject object_;
  std::string selected_;
  ui::RecordDialogState dialog_;
  std::unique_ptr<Recorder> recorder_;
  std::string record_out_;
  std::string default_out_;                     // the Record dialog's last default output folder
  bool insert_key(const nlohmann::json& line);  // executes an anim.keyframe unless that key exists already
  void begin_recording(const core::Scene& scene, const RecordOptions& options);  // errors to the Log
  std::filesystem::path default_folder() const;  // <scene dir>/<scene stem>_frames, untitled: ./frames
  core::Camera view_;
  std::optional<core::Scene> drawn_;  // a posed copy when visible clip objects make one necessary
  int drawn_frame_ = 0;
  std::uint64_t drawn_changes_ = 0;
  std::uint64_t poses_computed_ = 0;
};

}  // namespace trispline::editor
