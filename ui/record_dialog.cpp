#include "ui/record_dialog.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/commands/anim_record.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

namespace {
constexpr const char* kRecordTitle = "Record animation";
constexpr const char* kProgressTitle = "Recording";
}  // namespace

void open_record_dialog(RecordDialogState& s, const core::Timeline& t, int viewport_w, int viewport_h,
                        const core::Scene& scene, const core::Camera& view) {
  s.scene_camera_set = scene.camera_set;
  s.view = view;
  if (s.camera < 0) s.camera = scene.camera_set ? kSceneCamera : kCurrentView;
  s.frames[0] = t.frame_start;
  s.frames[1] = t.frame_end;
  if (viewport_w > 0 && viewport_h > 0) {
    s.size[0] = viewport_w;
    s.size[1] = viewport_h;
  }
  s.open = true;
}

nlohmann::json record_line(const RecordDialogState& s) {
  core::AnimRecordParams p;
  p.out = s.out_dir;
  p.format = s.format == 1 ? "exr" : "png";
  p.frames = glm::ivec2(s.frames[0], s.frames[1]);
  p.glb = s.glb;
  p.mp4 = s.mp4;
  p.width = s.size[0];
  p.height = s.size[1];
  if (s.camera == kCurrentView) p.camera = s.view;
  return core::AnimRecordCommand::schema().to_json(p);
}

std::optional<nlohmann::json> draw_record_dialog(RecordDialogState& s, const core::Timeline& t) {
  std::optional<nlohmann::json> line;
  if (!s.open) return line;
  if (!ImGui::IsPopupOpen(kRecordTitle)) ImGui::OpenPopup(kRecordTitle);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(kRecordTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return line;
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s", s.out_dir.c_str());
  ImGui::SetNextItemWidth(420);
  if (ImGui::InputText("Output folder", buf, sizeof buf)) s.out_dir = buf;
  tooltip("Folder for frame_NNNN.png|exr, animation.glb and animation.mp4 (created if missing)");
  ImGui::SetNextItemWidth(200);
  ImGui::Combo("Format", &s.format, "PNG (8-bit sRGB)\0EXR (half float, linear)\0");
  tooltip("Image format of the numbered frames");
  ImGui::SetNextItemWidth(200);
  drag_int_n("Frames", s.frames, 2, 0.2f, t.frame_start, t.frame_end, "%d", ImGuiSliderFlags_AlwaysClamp);
  tooltip("First and last timeline frame to record, inclusive (default: the whole timeline)");
  s.frames[1] = std::max(s.frames[1], s.frames[0]);
  ImGui::SetNextItemWidth(200);
  drag_int_n("Size", s.size, 2, 1.0f, 16, 8192, "%d px", ImGuiSliderFlags_AlwaysClamp);
  tooltip("Image width and height in pixels (default: the viewport)");
  ImGui::TextUnformatted("Camera");
  ImGui::SameLine();
  ImGui::RadioButton("Scene camera", &s.camera, kSceneCamera);
  probe::item("record.camera.scene");
  tooltip(s.scene_camera_set ? "The scene's camera: the log's last camera.set (File > Save sets it to the view)"
                             : "The scene has no camera (no camera.set): one framing every object, as replay uses");
  ImGui::SameLine();
  ImGui::RadioButton("Current view", &s.camera, kCurrentView);
  probe::item("record.camera.view");
  tooltip("The viewport's view as it is now; the recording keeps it in the log (anim.record's camera)");
  ImGui::TextColored(colors::dim, "Records %s",
                     s.camera == kCurrentView ? "the current view"
                     : s.scene_camera_set     ? "the scene camera (the log's camera.set)"
                                              : "the scene camera (none set: framing the whole scene)");
  probe::value("record.camera", s.camera == kCurrentView ? "view" : "scene");
  ImGui::Checkbox("Animated GLB", &s.glb);
  tooltip("animation.glb: one mesh per object with a morph target per frame (Blender imports shape keys)");
  ImGui::SameLine();
  ImGui::Checkbox("MP4", &s.mp4);
  tooltip("animation.mp4 (H.264) at the timeline's fps; needs ffmpeg on PATH (reported when it is missing)");
  ImGui::TextColored(colors::dim, "%d frames at %.4g fps", s.frames[1] - s.frames[0] + 1, t.fps);
  ImGui::Separator();
  const bool can = !s.out_dir.empty();
  ImGui::BeginDisabled(!can);
  const bool pressed = ImGui::Button("Record", ImVec2(120, 0));
  probe::item("record.ok");
  if (pressed) {
    line = record_line(s);
    s.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
    s.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return line;
}

bool draw_record_progress(const RecordProgress& p) {
  bool cancel = false;
  if (!ImGui::IsPopupOpen(kProgressTitle)) ImGui::OpenPopup(kProgressTitle);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(kProgressTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return cancel;
  ImGui::Text("Rendering frame %d into %s", p.frame, p.out_dir.c_str());
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%d / %d frames", p.done, p.total);
  ImGui::ProgressBar(p.total > 0 ? float(p.done) / float(p.total) : 0.0f, ImVec2(360, 0), overlay);
  if (p.seconds_left >= 0)
    ImGui::Text("about %.0f s left", p.seconds_left);
  else
    ImGui::TextColored(colors::dim, "estimating the time left...");
  if (ImGui::Button("Cancel", ImVec2(120, 0))) cancel = true;
  tooltip("Stop after the current frame; the frames already written stay");
  if (p.close) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return cancel;
}

}  // namespace trispline::ui
