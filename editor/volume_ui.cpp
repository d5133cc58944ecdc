#include "editor/volume_ui.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <chrono>

#include "core/base/text.h"
#include "core/commands/volume_export.h"
#include "core/commands/volume_load.h"
#include "core/volume/prepared_volume.h"
#include "editor/session/session.h"
#include "ui/gui_probe.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace fs = std::filesystem;

namespace trispline::editor {

namespace {

template <class T>
bool ready(const std::future<T>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

// "brain" for brain.nii.gz, "Cranium" for Cranium.inv3, the folder's name for a DICOM folder.
std::string display_name(const fs::path& path) {
  fs::path p = path.filename().empty() ? path.parent_path().filename() : path.filename();
  return p.string();
}

std::string stem_of(const fs::path& path) {
  fs::path stem(display_name(path));
  while (stem.has_extension()) stem = stem.stem();
  return stem.string();
}

}  // namespace

VolumeUi::VolumeUi(EditorSession& session, ui::MessageLog& messages, Defer defer)
    : session_(session), messages_(messages), defer_(std::move(defer)) {}

VolumeUi::~VolumeUi() {
  if (load_) {
    load_->cancel = true;
    if (load_->future.valid()) load_->future.wait();
  }
  if (job_ && job_->future.valid()) job_->future.wait();
}

// ---- loading

bool VolumeUi::start_load(const fs::path& path) {
  if (load_) {
    messages_.warning("a volume is loading already (" + display_name(load_->path) + "): wait for it or cancel it");
    return false;
  }
  std::error_code ec;
  auto job = std::make_unique<LoadJob>();
  job->path = fs::absolute(path, ec).lexically_normal();  // as volume.load resolves its path: the cache key matches
  LoadJob* j = job.get();
  job->future = std::async(std::launch::async, [j] {
    core::ProgressSink sink;
    sink.report = [j](double f) { j->progress = std::clamp(f, 0.0, 1.0); };
    sink.cancel = &j->cancel;
    const core::VolumeLoadParams defaults;  // what the volume.load line after it asks for: the cache serves it
    core::prepare_volume(j->path, defaults.order, defaults.interpolate, sink, defaults.axes == "superior_up");
  });
  messages_.info("Loading " + display_name(job->path) + " (reading the file, making its spline and singletons)");
  load_ = std::move(job);
  return true;
}

double VolumeUi::load_progress() const { return load_ ? load_->progress.load() : 0.0; }

void VolumeUi::cancel_load() {
  if (load_) load_->cancel = true;
}

std::string VolumeUi::finish_load() {
  if (!load_ || !ready(load_->future)) return {};
  const std::unique_ptr<LoadJob> job = std::move(load_);
  const std::string file = display_name(job->path);
  try {
    job->future.get();
  } catch (const core::OperationCancelled&) {
    messages_.info("Loading " + file + " cancelled: the scene is unchanged");
    return {};
  } catch (const std::exception& e) {
    messages_.error("cannot load " + file + ": " + e.what() + " (the scene is unchanged)");
    return {};
  }
  core::VolumeLoadParams p;
  p.path = job->path.string();
  p.name = session_.scene().unique_name(core::sanitized_object_name(stem_of(job->path)));
  if (!session_.execute(core::VolumeLoadCommand::schema().to_json(p))) return {};
  return p.name;
}

void VolumeUi::draw_load_progress() {
  const char* id = "Loading volume###volume_load";
  if (load_ && !ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(
          id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove))
    return;
  if (!load_) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  const double f = load_progress();
  ImGui::Text("Loading %s", display_name(load_->path).c_str());
  ui::tooltip(load_->path.string().c_str());
  ImGui::TextColored(ui::colors::dim, "%s",
                     load_->cancel ? "cancelling..."
                     : f <= 0.0    ? "reading the file, making the spline D..."
                                   : "singletons: value and gradient bounds per cell (seed section 7.3.2)");
  char label[32];
  std::snprintf(label, sizeof label, "%.0f %%", 100.0 * f);
  ImGui::ProgressBar(float(f), ImVec2(380.0f, 0.0f), label);
  ui::probe::item("volume.load.progress");
  ui::probe::value("volume.load.progress", label);
  ui::tooltip("Preprocessing, once per file: a later load of the same file reads the result from the disk cache");
  ImGui::BeginDisabled(load_->cancel);
  if (ImGui::Button("Cancel", ImVec2(100.0f, 0.0f))) cancel_load();
  ImGui::EndDisabled();
  ui::probe::item("volume.load.cancel");
  ui::tooltip("Stop loading this volume: nothing is added to the scene");
  ImGui::EndPopup();
}

// ---- live view

VolumeUi::LiveKey VolumeUi::wanted_key(const core::VolumeObject& v, const core::Camera& view) const {
  LiveKey k;
  k.spline = v.spline;
  k.table = v.table;
  k.iso = preview_iso(v.name).value_or(v.iso);
  for (const core::VolumeIsoLevel& l : v.more_levels) k.more_isos.push_back(l.iso);
  k.hidden = v.silhouette.hidden;
  k.projection = v.silhouette.projection;
  k.subdivision = v.silhouette.params.subdivision;
  k.accuracy = v.silhouette.params.accuracy;
  const core::SilhouetteView sv = v.screen_silhouette_view(view);
  (sv.perspective ? k.eye : k.direction) = sv.perspective ? sv.eye : sv.direction;
  k.pixel_size = sv.pixel_size;
  return k;
}

std::optional<double> VolumeUi::preview_iso(const std::string& volume) const {
  if (preview_ && preview_->first == volume) return preview_->second;
  if (held_ && held_->first == volume) return held_->second;
  return std::nullopt;
}

void VolumeUi::update(const core::Scene& shown, const core::Camera& view) {
  if (!panel_drawn_) preview_.reset();  // the panel (and its drag) went away
  panel_drawn_ = false;
  last_view_ = view;
  if (job_ && ready(job_->future)) {
    const std::unique_ptr<Job> job = std::move(job_);
    Live live{job->key, nullptr, -1.0, {}};
    try {
      Extracted e = job->future.get();
      live.result = std::move(e.result);
      live.more = std::move(e.more);
      live.ms = last_ms_ = e.ms;
      ++finished_;
      last_points_ = live.result->points;
    } catch (const std::exception& e) {
      messages_.error("silhouettes of '" + job->volume + "' for this view failed: " + e.what());
    }
    live_[job->volume] = std::move(live);
  }
  std::erase_if(live_, [&](const auto& kv) {
    const core::VolumeObject* v = shown.find_volume(kv.first);
    return !v || !v->silhouette.enabled;
  });
  if (!job_)
    std::erase_if(sequences_, [&](const auto& kv) {
      const core::VolumeObject* v = shown.find_volume(kv.first);
      return !v || !v->silhouette.enabled;
    });
  if (job_) return;
  for (const core::VolumeObject& v : shown.volumes()) {
    if (!v.visible || !v.silhouette.enabled || !v.spline || !v.table) continue;
    const LiveKey key = wanted_key(v, view);
    if (const auto it = live_.find(v.name); it != live_.end() && it->second.key == key) continue;
    // The volume's own silhouettes serve when they are for this eye, level and settings (after volume.export).
    const bool own_levels = std::all_of(v.more_levels.begin(), v.more_levels.end(),
                                        [](const core::VolumeIsoLevel& l) { return l.silhouettes != nullptr; });
    if (v.silhouettes && own_levels && key.iso == v.iso && key == wanted_key(v, v.silhouette_camera) &&
        !preview_iso(v.name)) {
      Results more;
      for (const core::VolumeIsoLevel& l : v.more_levels) more.push_back(l.silhouettes);
      live_[v.name] = {key, v.silhouettes, v.silhouettes->extract_ms + v.silhouettes->hidden_ms, std::move(more)};
      last_ms_ = live_[v.name].ms;
      last_points_ = v.silhouettes->points;
      continue;
    }
    core::SilhouetteParams params = v.silhouette.params;
    params.hidden_test = v.silhouette.hidden != "show";
    // Hidden parts removed: cells behind the surface seed nothing (the same visible curves, a third of the time on
    // a noisy MRI; docs/decisions.md). Exports and replays keep the complete extraction.
    params.seed_hidden = v.silhouette.hidden != "remove";
    // The live view follows the camera: each extraction starts from the curves of the one before, at the screen's
    // density (exports and replays extract each view whole).
    std::shared_ptr<core::SilhouetteSequence>& sequence = sequences_[v.name];
    if (!sequence || &sequence->spline() != v.spline.get() || &sequence->table() != v.table.get())
      sequence = std::make_shared<core::SilhouetteSequence>(v.spline, v.table);
    auto job = std::make_unique<Job>();
    job->volume = v.name;
    job->key = key;
    // Further levels are extracted whole after the first (their curves change with the level: no sequence).
    job->future = std::async(std::launch::async, [sequence, iso = key.iso, more_isos = key.more_isos,
                                                  sv = v.screen_silhouette_view(view), params] {
      const auto t0 = std::chrono::steady_clock::now();
      auto r = std::make_shared<const core::SilhouetteResult>(sequence->next(iso, sv, params));
      Results more;
      for (double level : more_isos)
        more.push_back(std::make_shared<const core::SilhouetteResult>(
            core::extract_silhouettes(sequence->spline(), sequence->table(), level, sv, params)));
      return Extracted{std::move(r),
                       std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                       std::move(more)};
    });
    job_ = std::move(job);
    break;
  }
}

void VolumeUi::decorate(gpu::ViewOptions& options) const {
  std::vector<std::string> named;
  for (const auto& [name, live] : live_) {
    options.overlays.volumes_in_place.push_back({name, preview_iso(name), live.result, live.more});
    named.push_back(name);
  }
  for (const auto* p : {&preview_, &held_})
    if (*p && std::find(named.begin(), named.end(), (*p)->first) == named.end()) {
      options.overlays.volumes_in_place.push_back({(*p)->first, preview_iso((*p)->first), nullptr});
      named.push_back((*p)->first);
    }
}

ui::VolumeLiveInfo VolumeUi::live_info(const std::string& volume) const {
  ui::VolumeLiveInfo info;
  info.extracting = job_ && job_->volume == volume;
  if (const auto it = live_.find(volume); it != live_.end() && it->second.result) {
    info.points = it->second.result->points;
    info.ms = it->second.ms;
    if (const core::VolumeObject* v = session_.scene().find_volume(volume))
      info.current = it->second.key == wanted_key(*v, last_view_);
  }
  return info;
}

// ---- panel and export

const ui::VolumeExportKind* VolumeUi::draw_panel(const ui::Rect& rect, const core::VolumeObject& volume) {
  panel_drawn_ = true;
  const ui::VolumePanelResult r = ui::draw_volume_panel(rect, volume, panel_, live_info(volume.name));
  if (r.iso_preview)
    preview_ = {volume.name, *r.iso_preview};
  else if (preview_ && preview_->first == volume.name)
    preview_.reset();
  if (r.line) {
    const nlohmann::json line = *r.line;
    const bool iso = line.value("cmd", "") == "volume.iso";
    if (iso) held_ = {volume.name, line.at("level").get<double>()};  // drawn until the line ran
    defer_(iso ? "Setting the iso-level of " + volume.name : "Silhouettes of " + volume.name, [this, line, iso] {
      session_.execute(line);
      if (iso) held_.reset();
    });
  }
  return r.export_kind;
}

bool VolumeUi::export_volume(const std::string& volume, const ui::VolumeExportKind& kind, fs::path path,
                             const core::Camera& view) {
  if (!core::has_extension(path, kind.extension)) path += kind.extension;
  const std::string what = kind.what;
  core::VolumeExportParams p;
  p.object = volume;
  p.what = what;
  // The user chose the file in a dialog: its folder is the output folder, and the line names the file in it.
  path = fs::absolute(path);
  p.path = path.filename().string();
  if (what == "silhouettes") p.camera = view;  // the view the user sees
  if (!session_.execute(core::VolumeExportCommand::schema().to_json(p), {}, path.parent_path())) return false;
  messages_.info("exported the " + std::string(what == "iso" ? "iso-surface" : "silhouettes") + " of " + volume +
                 " to " + path.string());
  return true;
}

namespace {
nlohmann::json transfer_values(const core::TransferFunction& tf) {
  nlohmann::json out = nlohmann::json::array();
  for (const core::TransferPoint& p : tf.points) out.push_back(p.value);
  return out;
}
}  // namespace

nlohmann::json VolumeUi::probe(const core::Scene& scene) const {
  nlohmann::json volumes = nlohmann::json::array();
  for (const core::VolumeObject& v : scene.volumes()) {
    const ui::VolumeLiveInfo live = live_info(v.name);
    const auto& d = v.spline->dims();
    // The further levels: their values and the points of their live silhouettes (-1: none drawn).
    nlohmann::json levels = nlohmann::json::array();
    const auto it = live_.find(v.name);
    for (std::size_t k = 0; k < v.more_levels.size(); ++k) {
      const bool drawn = it != live_.end() && k < it->second.more.size() && it->second.more[k];
      levels.push_back({{"iso", v.more_levels[k].iso},
                        {"style", v.more_levels[k].style},
                        {"live_points", drawn ? nlohmann::json(it->second.more[k]->points) : nlohmann::json(-1)}});
    }
    volumes.push_back({{"name", v.name},
                       {"more_levels", levels},
                       {"iso", v.iso},
                       {"preview_iso", preview_iso(v.name) ? nlohmann::json(*preview_iso(v.name)) : nlohmann::json()},
                       {"dims", {d[0], d[1], d[2]}},
                       {"silhouettes", v.silhouette.enabled},
                       {"style", v.silhouette.style},
                       {"render", v.render_mode == core::VolumeObject::RenderMode::dvr ? "dvr" : "iso"},
                       {"transfer_values", transfer_values(v.transfer)},
                       {"live_points", live.points},
                       {"live_current", live.current},
                       {"extracting", live.extracting}});
  }
  nlohmann::json load;
  if (load_) load = {{"path", load_->path.string()}, {"progress", load_progress()}, {"cancel", load_->cancel.load()}};
  return {{"volumes", volumes}, {"volume_load", load}};
}

}  // namespace trispline::editor
