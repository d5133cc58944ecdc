// The editor application's state (editor::App) and what its two source files share: app.cpp runs the frame loop
// (input, view, panels, probe, screenshots); app_requests.cpp answers the user's requests (menu, Scene panel, file
// dialog, "Save changes?"). Internal to editor/: only run_editor() (editor/app.h) is public.
#pragma once

#include <epoxy/gl.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <memory>
#include <thread>
#include <utility>

#include "core/commands/object_transform.h"
#include "core/commands/scene_load.h"
#include "core/commands/scene_primitive.h"
#include "core/commands/scene_remove.h"
#include "core/commands/scene_text.h"
#include "core/image/image_io.h"
#include "core/volume/volume_io.h"
#include "editor/animation_ui.h"
#include "editor/app.h"
#include "editor/guarantees_view.h"
#include "editor/gui_probe.h"
#include "editor/session/background_command.h"
#include "editor/session/navigation.h"
#include "editor/session/session.h"
#include "editor/tools/toolbox.h"
#include "editor/tools/transform_modal.h"
#include "editor/tools/work_queue.h"
#include "editor/volume_ui.h"
#include "gpu/gl/timer.h"
#include "gpu/gl/window.h"
#include "gpu/render/renderer.h"
#include "ui/dialogs.h"
#include "ui/file_dialog.h"
#include "ui/frame_timings.h"
#include "ui/gui_probe.h"
#include "ui/history_panel.h"
#include "ui/imgui_host.h"
#include "ui/log_panel.h"
#include "ui/main_menu.h"
#include "ui/overlays.h"
#include "ui/scene_panel.h"
#include "ui/shortcuts.h"
#include "ui/status_bar.h"
#include "ui/timeline_panel.h"
#include "ui/tool_panel.h"
#include "ui/window_capture.h"

namespace trispline::editor {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

inline const std::vector<std::string> kMeshExtensions = {".obj", ".ply", ".off", ".stl", ".gltf", ".glb"};
inline const std::vector<std::string> kLogExtensions = {".jsonl"};
inline const std::vector<std::string> kVolumeExtensions = {".nii", ".nii.gz", ".inv3", ".dcm"};  // and folders
// Milliseconds a frame may spend ray casting volumes; longer casts show a preview refined over the next frames.
inline constexpr double kVolumeBudgetMs = 150.0;
// How long after the last camera change the view still counts as moving (the tile layers' motion LOD,
// gpu::DdmViewOptions; its budgets are gpu::kDdmMotionBudgetVertices*).
inline constexpr double kMotionHoldSeconds = 0.25;
inline constexpr int kScreenshotFrames = 5;
// How long after the last input (or the window's damage) frames still come without further events, at most 10 a
// second: hover highlights and tooltips (ImGui's hover delays, ≤ 0.4 s) appear. Then an idle editor draws nothing.
inline constexpr double kSettleSeconds = 1.0;  // frames rendered after the start-up work before the capture

enum class FilePurpose { None, LoadMesh, OpenLog, SaveLog, ExportVolume, ToolSave };
// What waits for the "Save changes?" answer (the document was modified).
enum class Pending { None, Quit, New, Open };

// "starting a new scene" / "opening another log" / "quitting".
const char* doing(Pending p);

class App {
 public:
  explicit App(const AppOptions& options);
  int run();

 private:
  void frame();
  void handle_menu(ui::MenuAction action);
  void handle_scene(const ui::SceneRequest& request);
  void handle_file(const fs::path& path);
  void viewport_input();
  bool transform_input();  // G / R / S: starts or feeds the modal transform; true while it has the keyboard
  void render_view();
  bool animating() const;     // the timeline is playing
  void draw_control_point();  // the "Control point" section appended to the Tool panel
  void render_ui();           // ImGui's draw data into the window, timed by ui_timer_
  void record_frame_timings(Clock::time_point start, Clock::time_point end, Clock::time_point last);
  // Handles the window's events: polls while `busy` (work, playback, loads, a drag), waits up to 0.1 s within
  // kSettleSeconds of the last input, then sleeps until an event (or AppOptions::idle_fps).
  void wait_for_change(bool busy);
  void frame_selected();
  void open_later(const fs::path& log);  // replays `log` on a worker (BackgroundCommand::start_open)
  void showcase();                       // screenshot mode: select the placed (or tiled) object, show its tool
  void request(Pending what);            // Quit / New / Open: asks "Save changes?" first when the document is modified
  void go_on(Pending what);              // does it (the question, if any, is answered)
  bool save_or_ask();
  void ask_file(FilePurpose purpose);  // opens the file dialog for `purpose`
  int write_screenshot(const fs::path& path);
  void write_probe();  // --gui-probe: this frame's state for GUI tests (editor/gui_probe.h)
  // Bench mode (AppOptions::bench_out, app_bench.cpp): before a frame, orbits the view when the orbit phase runs;
  // after it, counts settling frames or keeps the frame's time. bench_after_frame returns the exit code once the
  // figures are written, else −1.
  void bench_before_frame();
  int bench_after_frame(Clock::time_point start);

  const AppOptions options_;
  std::unique_ptr<gpu::Window> window_;
  ui::ImGuiHost host_;
  std::unique_ptr<gpu::Renderer> renderer_;
  std::unique_ptr<gpu::GpuTimer> ui_timer_;  // the UI pass (ImGui render) for the timing overlay
  std::string gl_renderer_;
  ui::MessageLog messages_;
  EditorSession session_;
  BackgroundCommand background_{session_};  // Fill / Bake on a worker thread (destroyed before the session)
  Navigator nav_;
  core::Camera view_;
  core::Camera moved_view_;       // the view when it last changed
  Clock::time_point moved_at_{};  // when it last changed (the tile layers' motion LOD)

  std::string selected_;
  ui::ViewToggles toggles_;
  ToolContext tool_ctx_;
  Toolbox tools_;
  TransformModal transform_;
  core::SceneTextParams text_params_{.text = "Text"};  // the Scene panel's Add ▸ Text… dialog
  ui::TransformFields transform_fields_;               // the Scene panel's Location / Rotation / Scale while edited
  GuaranteesView guarantees_;                          // View > Error bounds / Fold certificate
  std::optional<Tool::LivePreview> live_preview_;      // this frame's tool preview (the Press tool's lattice)
  bool transform_frame_ = false;  // the modal transform had the input this frame (the viewport ignores it)

  ui::LogPanel log_panel_;
  ui::FileDialog file_dialog_;
  bool load_ignore_loose_ = false;  // the Load dialog's "Leave out points and lines", kept between loads
  FilePurpose file_purpose_ = FilePurpose::None;
  // The folders of the last file (or folder) a file dialog chose this session, for reading (Load, Open) and for
  // writing (Save As, exports): where the next dialog of that kind starts. Empty until then: the document's folder
  // when the user opened or saved it, else the folder the editor started in (never the shipped scenes' folder of a
  // document given on the command line, nor the folder a mesh was loaded from).
  std::filesystem::path last_read_folder_, last_write_folder_;
  bool document_chosen_ = false;  // the document was opened or saved through a dialog (not given at start)
  ui::TimingOverlay timing_;
  ui::DockLayout layout_;                  // this frame's panel rectangles
  AnimationUi anim_{session_, messages_};  // timeline, playback clock, keys, recording
  ui::ControlPointState control_point_;
  std::array<std::size_t, 6> overlay_counts_{};  // the last drawn frame's overlays, by kind (for the GUI probe)
  WorkQueue work_;
  VolumeUi volumes_{session_, messages_, [this](std::string what, std::function<void()> work) {
                      work_.push(std::move(what), std::move(work));
                    }};
  struct {
    std::string volume;
    const ui::VolumeExportKind* kind = nullptr;
  } export_request_;  // the Volume panel's Export button waiting for the Save dialog
  struct {
    std::string title, extension, name;
    std::function<void(const fs::path&)> chosen;
  } tool_save_;  // a tool's export waiting for the Save dialog (ToolContext::save_file)
  std::optional<RecoveryOffer> recovery_;
  Pending prompt_for_ = Pending::None;  // the "Save changes?" question is open for this
  bool show_about_ = false, show_keys_ = false, quit_ = false;
  bool screenshot_requested_ = false;            // F12: written after this frame is drawn
  int screenshots_ = 0, idle_frames_ = 0;        // F12 count; frames since the last deferred work (screenshot mode)
  std::uint64_t frames_ = 0;                     // frames drawn (the probe's "frame")
  Clock::time_point last_input_ = Clock::now();  // the last input event or window damage (wait_for_change)
  struct Bench {
    int settled = 0;  // quiet frames in a row before the idle phase
    std::vector<double> idle_ms, orbit_ms, silhouette_ms;
    std::size_t silhouettes_seen = 0;  // VolumeUi::finished() when the orbit began
  };
  std::optional<Bench> bench_;
};

}  // namespace trispline::editor
