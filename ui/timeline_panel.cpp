#include "ui/timeline_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/place_array.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::ui {

int clamp_frame(const core::Timeline& t, int frame) { return std::clamp(frame, t.frame_start, t.frame_end); }

bool advance_playback(Playback& p, const core::Timeline& t, double dt_s) {
  const int before = p.frame;
  if (p.frame < t.frame_start || p.frame > t.frame_end) {
    p.frame = clamp_frame(t, p.frame);
    p.carry = 0.0;
  }
  if (!p.playing || p.scrubbing || !(dt_s > 0.0) || !(t.fps > 0.0)) return p.frame != before;
  p.carry += dt_s * t.fps;
  const double whole = std::floor(p.carry);
  p.carry -= whole;
  const long long count = t.frame_count();
  const long long steps = static_cast<long long>(whole) % count;  // a long stall wraps, never loops forever
  p.frame = t.frame_start + static_cast<int>((p.frame - t.frame_start + steps) % count);
  return p.frame != before;
}

TimelineObject timeline_object(const core::Scene& scene, const std::string& name, int frame) {
  TimelineObject o;
  const core::SceneObject* so = name.empty() ? nullptr : scene.find(name);
  if (!so) return o;
  o.name = so->name;
  o.keyable = so->ffd != nullptr || so->dffd != nullptr;  // anim.keyframe walks an FFD or a DFFD split
  for (const core::OffsetKey& k : so->offset_keys) o.key_frames.push_back(scene.timeline.frame_of_time(k.time_s));
  auto channel = [&](const std::vector<core::OffsetKey>& keys, const std::string& what) {
    for (const core::OffsetKey& k : keys) o.channel_keys.emplace_back(scene.timeline.frame_of_time(k.time_s), what);
  };
  if (so->morph) channel(so->morph->weight_keys, so->morph->what.empty() ? "morph" : so->morph->what);
  if (so->dffd) channel(so->dffd->stitch_keys, "seam");
  for (const auto& layer : so->ddm_layers) {
    channel(layer->offset_keys, "tiles '" + layer->name + "' offset");
    channel(layer->alpha_keys, "tiles '" + layer->name + "' morph");
    channel(layer->rotate_keys, "tiles '" + layer->name + "' turn");
    channel(layer->scale_keys, "tiles '" + layer->name + "' scale");
    channel(layer->w_keys, "tiles '" + layer->name + "' w");
  }
  std::sort(o.channel_keys.begin(), o.channel_keys.end());
  const double t = scene.timeline.time_of_frame(frame);
  o.offset = so->offset_keys.empty() ? so->param_offset : core::evaluate_offset_keys(so->offset_keys, t);
  // A file the object was loaded from (a generated object's source is "primitive:…", "text:…" or "ddm.bake:…").
  const bool generated = so->source.rfind("primitive:", 0) == 0 || so->source.rfind("text:", 0) == 0 ||
                         so->source.rfind("ddm.bake:", 0) == 0;
  if (!generated) o.source = so->source;
  if (so->clip) o.clip = so->clip->clip->name();
  return o;
}

nlohmann::json array_line(const std::string& object, int count, double spacing) {
  return core::PlaceArrayCommand::schema().to_json({.object = object, .count = count, .spacing = spacing});
}

nlohmann::json clip_line(const std::string& object, const std::string& path, const std::string& clip, double speed) {
  return core::AnimClipCommand::schema().to_json({.object = object, .path = path, .clip = clip, .speed = speed});
}

bool has_key_at(const TimelineObject& object, int frame) {
  for (double f : object.key_frames)
    if (std::abs(f - frame) < 1e-6) return true;
  return false;
}

const char* interpolation_name(int index) {
  static const char* names[] = {"linear", "constant", "smooth"};
  return names[std::clamp(index, 0, 2)];
}

nlohmann::json timeline_line(double fps, int start, int end) {
  return core::AnimTimelineCommand::schema().to_json(core::AnimTimelineParams{fps, start, end});
}

nlohmann::json keyframe_line(const std::string& object, int frame, const glm::dvec3& offset,
                             const std::string& interpolation) {
  return core::AnimKeyframeCommand::schema().to_json(
      {.object = object, .frame = double(frame), .offset = offset, .interpolation = interpolation});
}

nlohmann::json remove_keyframe_line(const std::string& object, int frame) {
  return core::AnimKeyframeCommand::schema().to_json({.object = object, .frame = double(frame), .remove = true});
}

std::optional<nlohmann::json> insert_key_request(const TimelineObject& object, const Playback& playback,
                                                 const TimelinePanelState& state) {
  if (object.name.empty() || !object.keyable) return std::nullopt;
  const bool fresh = state.offset_for == object.name && state.offset_frame == playback.frame;
  return keyframe_line(object.name, playback.frame, fresh ? state.offset : object.offset,
                       interpolation_name(state.interpolation));
}

std::optional<nlohmann::json> delete_key_request(const TimelineObject& object, const Playback& playback) {
  if (object.name.empty() || !has_key_at(object, playback.frame)) return std::nullopt;
  return remove_keyframe_line(object.name, playback.frame);
}

float timeline_panel_height() {
  const ImGuiStyle& s = ImGui::GetStyle();
  return ImGui::GetFrameHeight() * 3.0f + s.ItemSpacing.y * 2.0f + s.WindowPadding.y * 2.0f + 4.0f;
}

namespace {

// A transport button of a fixed width; returns true on click.
bool transport(const char* label, const char* tip) {
  const bool clicked = ImGui::Button(label, ImVec2(ImGui::GetFrameHeight() * 1.6f, 0));
  tooltip(tip);
  ImGui::SameLine();
  return clicked;
}

// The scrub bar: frame ruler, key diamonds, current frame marker. Dragging sets playback.frame.
bool scrub_bar(const core::Timeline& t, Playback& p, const TimelineObject& object) {
  const ImVec2 pos = ImGui::GetCursorScreenPos();
  const ImVec2 size(std::max(ImGui::GetContentRegionAvail().x, 10.0f), ImGui::GetFrameHeight() * 1.6f);
  ImGui::InvisibleButton("##scrub", size);
  const bool active = ImGui::IsItemActive();
  if (ImGui::IsItemHovered() && !active)
    ImGui::SetTooltip("Drag to scrub (frames %d to %d at %.4g fps); yellow diamonds: keys of %s", t.frame_start,
                      t.frame_end, t.fps, object.name.empty() ? "the selected object" : object.name.c_str());
  const float pad = 8.0f, x0 = pos.x + pad, x1 = pos.x + size.x - pad;
  const int span = std::max(1, t.frame_end - t.frame_start);
  auto x_of = [&](double f) { return x0 + float((f - t.frame_start) / span) * (x1 - x0); };
  bool changed = false;
  p.scrubbing = active;
  if (active) {
    const double f = t.frame_start + double(ImGui::GetIO().MousePos.x - x0) / double(x1 - x0) * span;
    const int frame = clamp_frame(t, static_cast<int>(std::lround(f)));
    if (frame != p.frame) {
      p.frame = frame;
      p.carry = 0.0;
      changed = true;
    }
  }

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(pos, ImVec2(pos.x + size.x, pos.y + size.y), ImGui::GetColorU32(ImGuiCol_FrameBg), 3.0f);
  // Ruler: a tick every `step` frames, with labels where there is room.
  const float px_per_frame = (x1 - x0) / span;
  int step = 1;
  for (int s : {1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000})
    if ((step = s) * px_per_frame >= 40.0f) break;
  const ImU32 tick = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  const int first = (t.frame_start + step - 1) / step * step;
  for (int f = first; f <= t.frame_end; f += step) {
    const float x = x_of(f);
    dl->AddLine(ImVec2(x, pos.y + size.y * 0.55f), ImVec2(x, pos.y + size.y), tick);
    char label[16];
    std::snprintf(label, sizeof label, "%d", f);
    if (x + 2.0f + ImGui::CalcTextSize(label).x < pos.x + size.x)
      dl->AddText(ImVec2(x + 2.0f, pos.y + 1.0f), tick, label);
  }
  // Keys of the selected object (Blender draws them as diamonds).
  const float r = size.y * 0.18f, ky = pos.y + size.y * 0.72f;
  for (double f : object.key_frames) {
    if (f < t.frame_start - 1e-9 || f > t.frame_end + 1e-9) continue;
    const float x = x_of(f);
    const bool here = std::abs(f - p.frame) < 1e-6;
    dl->AddQuadFilled(ImVec2(x, ky - r), ImVec2(x + r, ky), ImVec2(x, ky + r), ImVec2(x - r, ky),
                      here ? IM_COL32(255, 235, 140, 255) : IM_COL32(230, 180, 40, 255));
    dl->AddQuad(ImVec2(x, ky - r), ImVec2(x + r, ky), ImVec2(x, ky + r), ImVec2(x - r, ky), IM_COL32(0, 0, 0, 200));
  }
  // The other channels' keys, a little lower, in teal (Blender draws keys of other channels in the summary row). The
  // one under the mouse names its channel.
  const float rc = size.y * 0.14f, cy = pos.y + size.y * 0.90f;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (const auto& [f, what] : object.channel_keys) {
    if (f < t.frame_start - 1e-9 || f > t.frame_end + 1e-9) continue;
    const float x = x_of(f);
    dl->AddQuadFilled(ImVec2(x, cy - rc), ImVec2(x + rc, cy), ImVec2(x, cy + rc), ImVec2(x - rc, cy),
                      IM_COL32(90, 200, 190, 255));
    dl->AddQuad(ImVec2(x, cy - rc), ImVec2(x + rc, cy), ImVec2(x, cy + rc), ImVec2(x - rc, cy), IM_COL32(0, 0, 0, 200));
    if (std::abs(mouse.x - x) <= rc + 1.0f && std::abs(mouse.y - cy) <= rc + 1.0f)
      ImGui::SetTooltip("%s key at frame %g", what.c_str(), f);
  }
  probe::value("timeline.channel_keys", std::to_string(object.channel_keys.size()));
  // Current frame: Blender's blue line with the number on top.
  const ImU32 blue = ImGui::GetColorU32(colors::accent);
  const float cx = x_of(p.frame);
  dl->AddLine(ImVec2(cx, pos.y), ImVec2(cx, pos.y + size.y), blue, 2.0f);
  char label[16];
  std::snprintf(label, sizeof label, "%d", p.frame);
  const ImVec2 ts = ImGui::CalcTextSize(label);
  dl->AddRectFilled(ImVec2(cx - ts.x * 0.5f - 3.0f, pos.y), ImVec2(cx + ts.x * 0.5f + 3.0f, pos.y + ts.y + 1.0f), blue,
                    3.0f);
  dl->AddText(ImVec2(cx - ts.x * 0.5f, pos.y), IM_COL32_WHITE, label);
  return changed;
}

// Start, End and FPS: edited in st's buffers; one anim.timeline line in r when an edit finishes.
void range_fields(const core::Timeline& t, TimelinePanelState& st, float num_w, TimelineRequest& r) {
  bool editing = false, committed = false;
  const auto int_field = [&](const char* label, const char* id, int* value, const char* probe_id, const char* tip) {
    ImGui::TextUnformatted(label);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(num_w);
    drag_int(id, value, 0.2f, 0, 100000, "%d", ImGuiSliderFlags_AlwaysClamp);
    probe::item(probe_id);
    editing |= ImGui::IsItemActive();
    committed |= ImGui::IsItemDeactivatedAfterEdit();
    tooltip(tip);
    ImGui::SameLine();
  };
  int_field("Start", "##start", &st.start, "timeline.start",
            "First frame of the timeline (anim.timeline \"start\", >= 0); logged and undoable");
  int_field("End", "##end", &st.end, "timeline.end",
            "Last frame of the timeline, inclusive (anim.timeline \"end\", >= start, <= 100000); playback loops here");
  ImGui::TextUnformatted("FPS");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(num_w);
  drag_scalar("##fps", ImGuiDataType_Double, &st.fps, 0.1f, nullptr, nullptr, "%.3g");
  probe::item("timeline.fps");
  editing |= ImGui::IsItemActive();
  committed |= ImGui::IsItemDeactivatedAfterEdit();
  tooltip("Frames per second, in (0, 240] (anim.timeline \"fps\"); playback and recordings use it");
  if (committed && (st.fps != t.fps || st.start != t.frame_start || st.end != t.frame_end))
    r.command = timeline_line(st.fps, st.start, st.end);
  else if (!editing) {
    st.fps = t.fps;
    st.start = t.frame_start;
    st.end = t.frame_end;
  }
}

// The selected object's offset and its key buttons (anim.keyframe), or why there is nothing to key.
void key_fields(const TimelineObject& object, const Playback& p, TimelinePanelState& st, float num_w,
                TimelineRequest& r) {
  if (object.name.empty() || !object.keyable) {
    ImGui::TextColored(
        colors::dim,
        object.name.empty() ? "Select a placed object to key its offset" : "'%s' has no lattice: nothing to key",
        object.name.c_str());
  } else {
    ImGui::Text("%s offset", object.name.c_str());
    ImGui::SameLine();
    ImGui::SetNextItemWidth(num_w * 3.0f);
    drag_scalar_n("##offset", ImGuiDataType_Double, &st.offset.x, 3, 0.002f, nullptr, nullptr, "%.3f");
    probe::item("timeline.offset");
    tooltip(
        "Parameter offset (u along the path, v, w) of the object inside its lattice at this frame, parameter\n"
        "units (u = 1 is the whole path). Edit it, then Insert key (I): the object walks along the path\n"
        "between keys (seed section 2.4.3).");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("constant").x + ImGui::GetFrameHeight() * 1.5f);
    ImGui::Combo("##interp", &st.interpolation, "linear\0constant\0smooth\0");
    tooltip("Interpolation from the new key to the next one: linear, constant (hold), smooth (ease in/out)");
    ImGui::SameLine();
    if (ImGui::Button("Insert key")) r.command = insert_key_request(object, p, st);
    tooltip("Key the offset at the current frame (I): anim.keyframe, undoable");
    ImGui::SameLine();
    ImGui::BeginDisabled(!has_key_at(object, p.frame));
    if (ImGui::Button("Delete key")) r.command = delete_key_request(object, p);
    ImGui::EndDisabled();
    tooltip("Delete the key at the current frame (Alt+I)");
  }
}

// "Animate...": a row of copies along the path (place.array) and a glTF clip under the FFD (anim.clip).
void animate_popup(const TimelineObject& object, TimelinePanelState& st, float num_w, TimelineRequest& r) {
  ImGui::SameLine();
  if (ImGui::Button("Animate...")) {
    if (!object.source.empty() && !*st.clip_path)
      std::snprintf(st.clip_path, sizeof st.clip_path, "%s", object.source.c_str());
    ImGui::OpenPopup("animate_popup");
  }
  tooltip(
      "Copies in a row along the path (place.array, the seed's ants) and a glTF clip played under the FFD\n"
      "(anim.clip: morph targets and skins, the seed's two-level animation)");
  if (ImGui::BeginPopup("animate_popup")) {
    ImGui::TextUnformatted("Row of copies along the path");
    ImGui::BeginDisabled(!object.keyable);
    ImGui::SetNextItemWidth(num_w * 2);
    ImGui::InputInt("Count", &st.array_count);
    st.array_count = std::clamp(st.array_count, 1, 64);
    tooltip("Number of copies (1-64): they share the lattice, keys and clip");
    ImGui::SetNextItemWidth(num_w * 2);
    ImGui::InputDouble("Spacing (u)", &st.array_spacing, 0.01, 0.05, "%.3f");
    tooltip(
        "Copy k trails the object by k x spacing along u (parameter units; >= the Sketch tool's Extent keeps\n"
        "them apart). Key the leader to start at u >= count x spacing.");
    if (ImGui::Button("Add copies")) {
      r.command = array_line(object.name, st.array_count, st.array_spacing);
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndDisabled();
    ImGui::Separator();
    ImGui::Text("glTF clip%s%s", object.clip.empty() ? "" : ": playing ", object.clip.c_str());
    ImGui::SetNextItemWidth(num_w * 6);
    ImGui::InputText("File", st.clip_path, sizeof st.clip_path);
    tooltip("The .gltf/.glb the object was loaded from (the clip must animate the same vertices)");
    ImGui::SetNextItemWidth(num_w * 3);
    ImGui::InputText("Clip", st.clip_name, sizeof st.clip_name);
    tooltip("Animation name, #i for the i-th, empty for the first");
    ImGui::SetNextItemWidth(num_w * 2);
    ImGui::InputDouble("Speed", &st.clip_speed, 0.1, 0.5, "%.2f");
    tooltip("Clip seconds per scene second (> 0)");
    if (ImGui::Button("Attach clip")) {
      r.command = clip_line(object.name, st.clip_path, st.clip_name, st.clip_speed);
      ImGui::CloseCurrentPopup();
    }
    if (!object.clip.empty()) {
      ImGui::SameLine();
      if (ImGui::Button("Remove clip")) {
        core::AnimClipParams remove;
        remove.object = object.name;
        remove.remove = true;
        r.command = core::AnimClipCommand::schema().to_json(remove);
        ImGui::CloseCurrentPopup();
      }
    }
    ImGui::EndPopup();
  }
}

}  // namespace

TimelineRequest draw_timeline_panel(const Rect& rect, const core::Timeline& t, Playback& p,
                                    const TimelineObject& object, TimelinePanelState& st) {
  TimelineRequest r;
  if (!begin_docked("Timeline", rect, ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar)) {
    ImGui::End();
    return r;
  }
  if (st.offset_for != object.name || st.offset_frame != p.frame) {
    st.offset = object.offset;
    st.offset_for = object.name;
    st.offset_frame = p.frame;
  }
  auto set_frame = [&](int f) {
    f = clamp_frame(t, f);
    if (f != p.frame) r.frame_changed = true;
    p.frame = f;
    p.carry = 0.0;
  };

  // Row 1: transport, current frame, range and rate, keying, record.
  if (transport("|<", "Jump to the first frame (Shift+Left)")) set_frame(t.frame_start);
  if (transport("<", "Previous frame (Left)")) set_frame(p.frame - 1);
  ImGui::PushStyleColor(ImGuiCol_Button, p.playing ? ImGui::GetStyleColorVec4(ImGuiCol_HeaderActive)
                                                   : ImGui::GetStyleColorVec4(ImGuiCol_Button));
  const bool play = ImGui::Button(p.playing ? "Pause##play" : "Play##play", ImVec2(ImGui::GetFrameHeight() * 2.8f, 0));
  ImGui::PopStyleColor();
  tooltip("Play / pause (Space); playback loops at the end frame");
  ImGui::SameLine();
  if (play) {
    p.playing = !p.playing;
    p.carry = 0.0;
  }
  if (transport(">##next", "Next frame (Right)")) set_frame(p.frame + 1);
  if (transport(">|", "Jump to the last frame (Shift+Right)")) set_frame(t.frame_end);

  const float num_w = ImGui::CalcTextSize("000000").x + ImGui::GetFrameHeight();
  int frame = p.frame;
  ImGui::SetNextItemWidth(num_w);
  if (drag_int("##frame", &frame, 0.2f, t.frame_start, t.frame_end, "%d", ImGuiSliderFlags_AlwaysClamp))
    set_frame(frame);
  probe::item("timeline.frame");
  tooltip("Current frame (view state: not logged, not undoable). Scene time = (frame - start) / fps seconds");
  ImGui::SameLine();
  ImGui::TextColored(colors::dim, "%.2f s", t.time_of_frame(p.frame));
  ImGui::SameLine(0, 20);

  range_fields(t, st, num_w, r);

  ImGui::SameLine(0, 20);
  key_fields(object, p, st, num_w, r);
  if (!object.name.empty()) animate_popup(object, st, num_w, r);
  ImGui::SameLine(0, 20);
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.55f, 0.16f, 0.16f, 1.0f));
  if (ImGui::Button("Record...")) r.record = true;
  ImGui::PopStyleColor();
  tooltip("Render the timeline's frames to PNG/EXR images, an animated GLB and an MP4 (anim.record)");

  // Row 2: the scrub bar.
  if (scrub_bar(t, p, object)) r.frame_changed = true;
  ImGui::End();
  return r;
}

}  // namespace trispline::ui
