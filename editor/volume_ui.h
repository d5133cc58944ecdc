// trispline::editor::VolumeUi — the editor's CT/MRI volumes (seed ch. 7), kept out of app.cpp so tests drive it
// without a window:
//   loading      core::prepare_volume (read, spline, singleton table) on a worker thread with a progress bar and
//                Cancel (a ProgressSink with an atomic cancel flag); then volume.load on the UI thread, which finds the
//                prepared volume in the session cache and returns at once. A cancelled or failed load leaves the scene
//                untouched and says so in the Log.
//   Volume panel ui/volume_panel.h for the selected volume: its volume.iso / volume.silhouettes lines run through
//                the editor's deferred work ("Working…"); the iso field's live level is drawn until its line ran
//   live view    silhouettes of every visible volume whose silhouettes are on (every level), extracted for the
//                current view on a worker thread whenever the eye (the direction, for orthographic ones), the level
//                (the live preview included) or the settings changed and no extraction is running; the latest result is
//                drawn (a stale one until the next arrives), so the UI never waits for Newton
//   export       the Volume panel's Export buttons → the Save dialog → camera.set of the current view (when the scene
//                camera differs: volume.export writes the scene camera's silhouettes) and volume.export
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/scene/scene.h"
#include "gpu/view/view_options.h"
#include "ui/message_log.h"
#include "ui/volume_panel.h"

namespace trispline::editor {

class EditorSession;

class VolumeUi {
 public:
  // Runs `work` later on the UI thread, after a frame showing "Working… <what>" (ToolContext::defer); tests may run
  // it at once.
  using Defer = std::function<void(std::string what, std::function<void()> work)>;
  VolumeUi(EditorSession& session, ui::MessageLog& messages, Defer defer);
  ~VolumeUi();  // cancels a load and waits for the worker threads
  VolumeUi(const VolumeUi&) = delete;
  VolumeUi& operator=(const VolumeUi&) = delete;

  // ---- loading
  // Starts preparing the volume at `path` (a file, or a DICOM series folder) on a worker thread: spline order 4,
  // control points = samples (volume.load's defaults). False, with a Log warning, while another load runs.
  bool start_load(const std::filesystem::path& path);
  bool loading() const { return load_ != nullptr; }
  double load_progress() const;  // [0, 1]: the singleton table's progress (0 while the file is read)
  void cancel_load();            // the worker stops at its next progress check; finish_load() then reports it
  // UI thread, once per frame: when the worker is done, runs volume.load (or reports the failure or the cancel in
  // the Log). Returns the name of the volume loaded this frame, else "".
  std::string finish_load();
  // The progress window (modal: the scene must not change under a load): file, bar, Cancel. Between NewFrame and
  // Render. Probe items "volume.load.progress", "volume.load.cancel".
  void draw_load_progress();

  // ---- live view
  // UI thread, once per frame before drawing: takes a finished extraction and starts the next one that is due for
  // `view` over `shown` (the scene as drawn: hidden volumes invisible).
  void update(const core::Scene& shown, const core::Camera& view);
  // The live iso-level and silhouettes as ViewOptions::overlays.volumes_in_place.
  void decorate(gpu::ViewOptions& options) const;
  bool extracting() const { return job_ != nullptr; }
  bool busy() const { return loading() || extracting(); }  // the editor keeps drawing frames meanwhile
  // What the panel and the timing overlay show of `volume`'s live silhouettes.
  ui::VolumeLiveInfo live_info(const std::string& volume) const;
  double last_extract_ms() const { return last_ms_; }  // the last extraction's wall time, ms (< 0: none yet)
  std::size_t last_points() const { return last_points_; }
  std::size_t finished() const { return finished_; }  // extractions finished so far (bench mode counts them)
  // The live iso-level of `volume` while its field is dragged or its line has not run yet.
  std::optional<double> preview_iso(const std::string& volume) const;

  // ---- panel and export
  // Draws the Volume panel of `volume` (a volume of the scene) in `rect` and acts on it; returns the export the user
  // asked for (the caller opens the Save dialog, then calls export_volume), else null.
  const ui::VolumeExportKind* draw_panel(const ui::Rect& rect, const core::VolumeObject& volume);
  // Writes `kind` of `volume` to `path` (its extension added when missing): camera.set of `view` first for
  // silhouettes when the scene camera is another view, then volume.export. Errors go to the Log. Returns success.
  bool export_volume(const std::string& volume, const ui::VolumeExportKind& kind, std::filesystem::path path,
                     const core::Camera& view);

  // For the GUI probe: every volume with its iso, live silhouettes and the load in progress.
  nlohmann::json probe(const core::Scene& scene) const;

 private:
  // What a live extraction depends on (the pointers held, so their addresses cannot be reused meanwhile).
  struct LiveKey {
    std::shared_ptr<const core::VolumeSpline> spline;
    std::shared_ptr<const core::SingletonTable> table;
    double iso = 0.0;
    std::string hidden, projection;
    int subdivision = 0;
    double accuracy = 0.0;
    glm::dvec3 eye{0.0}, direction{0.0};  // perspective: eye only; orthographic: direction only
    double pixel_size = 0.0;              // core::SilhouetteView::pixel_size (the screen's density)
    std::vector<double> more_isos;        // the further levels' (VolumeObject::more_levels)
    bool operator==(const LiveKey& o) const {
      return spline == o.spline && table == o.table && iso == o.iso && more_isos == o.more_isos && hidden == o.hidden &&
             projection == o.projection && subdivision == o.subdivision && accuracy == o.accuracy && eye == o.eye &&
             pixel_size == o.pixel_size && direction == o.direction;
    }
  };
  using Results = std::vector<std::shared_ptr<const core::SilhouetteResult>>;
  struct Live {
    LiveKey key;
    std::shared_ptr<const core::SilhouetteResult> result;  // null after a failed extraction
    double ms = -1.0;
    Results more;  // one per further level
  };
  struct Extracted {
    std::shared_ptr<const core::SilhouetteResult> result;
    double ms = 0.0;
    Results more;
  };
  struct Job {
    std::string volume;
    LiveKey key;
    std::future<Extracted> future;
  };
  struct LoadJob {
    std::filesystem::path path;  // absolute, normalised (as volume.load resolves it)
    std::atomic<bool> cancel{false};
    std::atomic<double> progress{0.0};
    std::future<void> future;
  };
  LiveKey wanted_key(const core::VolumeObject& v, const core::Camera& view) const;

  EditorSession& session_;
  ui::MessageLog& messages_;
  Defer defer_;
  std::unique_ptr<LoadJob> load_;
  std::unique_ptr<Job> job_;
  std::map<std::string, Live> live_;
  // Per volume: the run of views the live silhouettes follow (seeded from the previous view's curves). Used by one
  // job at a time.
  std::map<std::string, std::shared_ptr<core::SilhouetteSequence>> sequences_;
  std::optional<std::pair<std::string, double>> preview_;  // (volume, level) of the iso field being dragged
  std::optional<std::pair<std::string, double>> held_;     // (volume, level) of a volume.iso line not run yet
  ui::VolumePanelState panel_;
  bool panel_drawn_ = false;  // draw_panel ran since the last update()
  core::Camera last_view_;    // the view of the last update()
  double last_ms_ = -1.0;
  std::size_t finished_ = 0;
  std::size_t last_points_ = 0;
};

}  // namespace trispline::editor
