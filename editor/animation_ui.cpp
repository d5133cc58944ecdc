#include "editor/animation_ui.h"

#include <cmath>
#include <filesystem>

#include "core/commands/anim_record.h"

namespace fs = std::filesystem;

namespace trispline::editor {

void AnimationUi::begin_frame(const std::string& selected, bool playing) {
  if (playing != playback_.playing) playback_.carry = 0.0;
  playback_.playing = playing;
  selected_ = selected;
  ui::advance_playback(playback_, session_.scene().timeline, 0.0);
  object_ = ui::timeline_object(session_.scene(), selected_, playback_.frame);
}

double AnimationUi::time_s() const { return session_.scene().timeline.time_of_frame(playback_.frame); }

void AnimationUi::draw_timeline(const ui::Rect& rect, glm::ivec2 viewport) {
  const ui::TimelineRequest r = ui::draw_timeline_panel(rect, session_.scene().timeline, playback_, object_, panel_);
  const bool keying = r.command && r.command->value("cmd", "") == "anim.keyframe" && !r.command->contains("remove");
  if (r.command && (keying ? insert_key(*r.command) : session_.execute(*r.command)))
    object_ = ui::timeline_object(session_.scene(), selected_, playback_.frame);
  if (r.record) handle_action(ui::MenuAction::RecordAnimation, viewport);
}

bool AnimationUi::handle_action(ui::MenuAction action, glm::ivec2 viewport) {
  using A = ui::MenuAction;
  const core::Timeline& t = session_.scene().timeline;
  auto go = [&](int frame) {
    playback_.frame = ui::clamp_frame(t, frame);
    playback_.carry = 0.0;
  };
  switch (action) {
    case A::InsertKeyframe:
      if (auto line = ui::insert_key_request(object_, playback_, panel_))
        insert_key(*line);
      else
        messages_.warning("Insert keyframe: select an object with a lattice (placed, ring or split) first");
      break;
    case A::DeleteKeyframe:
      if (auto line = ui::delete_key_request(object_, playback_))
        session_.execute(*line);
      else
        messages_.warning("Delete keyframe: the selected object has no key at frame " +
                          std::to_string(playback_.frame));
      break;
    case A::FramePrev:
      go(playback_.frame - 1);
      break;
    case A::FrameNext:
      go(playback_.frame + 1);
      break;
    case A::FrameStart:
      go(t.frame_start);
      break;
    case A::FrameEnd:
      go(t.frame_end);
      break;
    case A::RecordAnimation:
      if (recorder_) break;
      if (dialog_.out_dir.empty() || dialog_.out_dir == default_out_) {  // the artist's own choice stays
        default_out_ = default_folder().string();
        dialog_.out_dir = default_out_;
      }
      ui::open_record_dialog(dialog_, t, viewport.x, viewport.y, session_.scene(), view_);
      break;
    default:
      return false;
  }
  object_ = ui::timeline_object(session_.scene(), selected_, playback_.frame);
  return true;
}

bool AnimationUi::insert_key(const nlohmann::json& line) {
  // Keying the same offset at a frame that has that very key again (I pressed twice) is not a new history step.
  const core::SceneObject* o = session_.scene().find(line.value("object", ""));
  const core::Timeline& t = session_.scene().timeline;
  if (o && line.contains("offset") && line["offset"].size() == 3) {
    const double time = t.time_of_frame(line.value("frame", 0));
    const glm::dvec3 offset(line["offset"][0].get<double>(), line["offset"][1].get<double>(),
                            line["offset"][2].get<double>());
    const std::string interp = line.value("interpolation", "linear");
    for (const core::OffsetKey& k : o->offset_keys) {
      const char* name = k.interpolation == core::KeyInterpolation::constant ? "constant"
                         : k.interpolation == core::KeyInterpolation::smooth ? "smooth"
                                                                             : "linear";
      if (std::abs(k.time_s - time) < 1e-9 && k.offset == offset && interp == name) {
        messages_.info("'" + o->name + "' already has this key at frame " + std::to_string(line.value("frame", 0)));
        return false;
      }
    }
  }
  return session_.execute(line);
}

void AnimationUi::advance(double dt_s) {
  if (!recorder_) ui::advance_playback(playback_, session_.scene().timeline, dt_s);
}

namespace {

// Where an executed anim.record writes: the folder its line named, else `fallback`.
fs::path out_dir_of(const core::RecordRequest& r, const fs::path& fallback) {
  return r.out_dir.empty() ? fallback : r.out_dir;
}

}  // namespace

bool AnimationUi::start_recording(const nlohmann::json& line, const std::function<void()>& restore_context) {
  if (recorder_ || !session_.execute(line)) return false;  // anim.record validates range, format, size and camera
  const auto* cmd = dynamic_cast<const core::AnimRecordCommand*>(&session_.history().last_executed());
  if (cmd)
    begin_recording(session_.scene(), record_options(cmd->request(), out_dir_of(cmd->request(), default_folder())));
  if (restore_context) restore_context();
  return recorder_ != nullptr;
}

bool AnimationUi::run_again(std::size_t k, const std::function<void()>& restore_context) {
  if (k >= session_.history().outputs().size()) return false;
  HistoryOutput& o = session_.history().output(k);
  auto* cmd = dynamic_cast<core::AnimRecordCommand*>(o.command.get());
  if (!cmd) return session_.run_again_output(k);
  if (recorder_ || !session_.busy().empty()) {
    messages_.warning("Run again refused: " + (recorder_ ? std::string("a recording runs") : session_.busy()));
    return false;
  }
  if (!o.scene) {
    messages_.warning(cmd->label() + ": nothing to run again (its frames were recorded)");
    return false;
  }
  // An opened log is shared input: Run again records only under the scene's folder (`..` and symlinks resolved).
  // Elsewhere, the artist chooses the folder in the Record dialog.
  const fs::path out = cmd->request().out_dir.empty() ? default_folder() : cmd->request().out_dir;
  const fs::path doc = session_.document();
  std::error_code ec;
  const fs::path root =
      fs::weakly_canonical(fs::absolute(doc.empty() ? fs::current_path(ec) : doc.parent_path(), ec), ec);
  const fs::path target = fs::weakly_canonical(fs::absolute(out, ec), ec);
  auto t = target.begin();
  bool inside = !ec;
  for (auto r = root.begin(); inside && r != root.end() && !r->empty(); ++r, ++t)
    inside = t != target.end() && *t == *r;
  if (!inside) {
    messages_.warning("Run again refused: the log records into '" + out.string() + "', outside the scene's folder '" +
                      root.string() +
                      "' (a shared log must not write where you did not choose); use File ▸ Record "
                      "animation… to choose a folder");
    return false;
  }
  // The frames as they were recorded at that step: the scene it ran on, its request (range resolved then).
  begin_recording(*o.scene, record_options(cmd->request(), out_dir_of(cmd->request(), default_folder())));
  if (recorder_) {
    cmd->mark_written();
    o.scene.reset();
  }
  if (restore_context) restore_context();
  return recorder_ != nullptr;
}

void AnimationUi::begin_recording(const core::Scene& scene, const RecordOptions& ro) {
  try {
    recorder_ = std::make_unique<Recorder>(scene, ro);
    record_out_ = ro.out_dir.string();
    messages_.info("recording " + std::to_string(recorder_->frames_total()) + " frames into " + record_out_);
  } catch (const std::exception& e) {
    messages_.error(std::string("cannot record: ") + e.what());
  }
}

fs::path AnimationUi::default_folder() const {
  // Beside the scene file, like Blender's //render: <scene dir>/<scene stem>_frames/ (untitled: ./frames/).
  const fs::path doc = session_.document();
  std::error_code ec;
  return doc.empty() ? fs::current_path(ec) / "frames" : doc.parent_path() / (doc.stem().string() + "_frames");
}

void AnimationUi::draw_record_ui(const std::function<void()>& restore_context) {
  if (auto line = ui::draw_record_dialog(dialog_, session_.scene().timeline)) start_recording(*line, restore_context);
  if (!recorder_) return;
  ui::RecordProgress p{recorder_->frames_done(), recorder_->frames_total(), recorder_->seconds_left(),
                       recorder_->current_frame(), record_out_};
  const bool cancel = ui::draw_record_progress(p);
  bool more = false;
  try {
    if (cancel) recorder_->cancel();
    more = !cancel && recorder_->step() && recorder_->frames_done() < recorder_->frames_total();
  } catch (const std::exception& e) {
    messages_.error(std::string("recording stopped: ") + e.what());
  }
  if (!more) {
    try {
      const RecordResult res = recorder_->finish();
      std::string files;
      for (const fs::path& f : res.files)
        if (f.extension() != ".png" && f.extension() != ".exr") files += " " + f.string();
      messages_.info((res.cancelled ? "recording cancelled after " : "recorded ") + std::to_string(res.frames_written) +
                     " frames (" + std::to_string(res.frame_first) + "-" + std::to_string(res.frame_last) + ") into " +
                     record_out_ + (files.empty() ? "" : ":" + files));
      if (!res.cancelled && !res.mp4_note.empty()) messages_.warning("no MP4: " + res.mp4_note);
    } catch (const std::exception& e) {
      messages_.error(std::string("recording failed: ") + e.what());
    }
    recorder_.reset();
    p.close = true;
    ui::draw_record_progress(p);
  }
  if (restore_context) restore_context();
}

const core::Scene& AnimationUi::drawn_scene() {
  const core::Scene& doc = session_.scene();
  bool clips = false;  // a clip object hidden in the viewport is not posed
  for (const core::SceneObject& o : doc.objects()) clips = clips || (o.cpu_animated() && o.visible);
  if (!clips) {
    drawn_.reset();
    return doc;
  }
  if (!drawn_ || drawn_changes_ != session_.change_count() || drawn_frame_ != playback_.frame) {
    drawn_ = core::scene_with_posed_clips(doc, time_s());
    ++poses_computed_;
    drawn_frame_ = playback_.frame;
    drawn_changes_ = session_.change_count();
  }
  return *drawn_;
}

}  // namespace trispline::editor
