// trispline::ui Timeline panel — Blender's Timeline editor at the bottom of the window: transport buttons
// (jump to start, previous frame, play/pause, next frame, jump to end), the current frame, the scene's frame range
// and rate, the selected object's offset keys as diamonds on a scrub bar (drag to scrub), Insert / Delete keyframe
// and Record. Seed §2.4.3 (objects walking along the sketched path).
//
// The frame range and rate are document state (core::Scene::timeline): the panel only returns the anim.timeline /
// anim.keyframe lines for the editor to execute. The current frame and the playing state are view state
// (Playback): not undoable, not logged. Scene time = timeline.time_of_frame(Playback::frame).
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "ui/layout.h"

namespace trispline::ui {

// The playback clock (view state). Frames are whole numbers, as in Blender; real time accumulates in `carry`.
struct Playback {
  int frame = 1;  // current timeline frame
  bool playing = false;
  bool scrubbing = false;  // the scrub bar is being dragged: playback does not advance meanwhile
  double carry = 0.0;      // fraction of a frame of real time not shown yet, in [0, 1)
};

// frame clamped into [frame_start, frame_end].
int clamp_frame(const core::Timeline& timeline, int frame);

// Advances `p` by `dt_s` seconds of real time (≥ 0) at timeline.fps when playing and not scrubbing: whole frames,
// wrapping from frame_end back to frame_start (Blender loops). A frame outside the range first jumps into it.
// Returns true when the frame changed.
bool advance_playback(Playback& p, const core::Timeline& timeline, double dt_s);

// The selected object as the timeline sees it (filled by the editor from the scene).
struct TimelineObject {
  std::string name;                // "" = nothing selected
  bool keyable = false;            // has an FFD lattice or a DFFD rig (anim.keyframe needs one)
  std::vector<double> key_frames;  // timeline frames of its offset keys (frame_of_time of each key), sorted
  // Its other keyed channels' keys: an incision's opening (incision.animate), a DFFD seam (dffd.animate), its tile
  // layers' offset and morph keys (ddm.animate) — drawn as diamonds of their own colour (frame, channel), sorted.
  std::vector<std::pair<double, std::string>> channel_keys;
  glm::dvec3 offset{0.0};  // its keyed offset at the current frame (param_offset without keys), parameter units
  std::string source;      // file it was loaded from ("" for primitives): the default clip file
  std::string clip;        // name of its glTF clip ("" = none)
};

// The selected object's timeline view from the scene at `frame` (object "" or unknown: an empty TimelineObject).
TimelineObject timeline_object(const core::Scene& scene, const std::string& name, int frame);

// True when `object` has a key at `frame` (within 1e-6 frames).
bool has_key_at(const TimelineObject& object, int frame);

// Command lines the panel issues (docs/commands.md: anim.timeline, anim.keyframe).
nlohmann::json timeline_line(double fps, int start, int end);
nlohmann::json keyframe_line(const std::string& object, int frame, const glm::dvec3& offset,
                             const std::string& interpolation);
nlohmann::json remove_keyframe_line(const std::string& object, int frame);

// Widget state the panel keeps between frames (owned by the editor).
struct TimelinePanelState {
  // Edit buffers of the range/rate fields; re-read from the document whenever none of them is being edited.
  double fps = 24;
  int start = 1, end = 120;
  // The offset to key ("Offset u v w"), reset to the object's value whenever the object or the frame changes.
  glm::dvec3 offset{0.0};
  std::string offset_for;  // object the offset was read from
  int offset_frame = -1;   // frame it was read at
  int interpolation = 0;   // 0 linear, 1 constant, 2 smooth (the segment that starts at the new key)
  // The "Animate" popup: place.array and anim.clip fields.
  int array_count = 2;
  double array_spacing = 0.25;
  char clip_path[512] = "";
  char clip_name[128] = "";
  double clip_speed = 1.0;
};

// place.array and anim.clip lines of the Animate popup (docs/commands.md).
nlohmann::json array_line(const std::string& object, int count, double spacing);
nlohmann::json clip_line(const std::string& object, const std::string& path, const std::string& clip, double speed);
const char* interpolation_name(int index);  // "linear" / "constant" / "smooth"

struct TimelineRequest {
  std::optional<nlohmann::json> command;  // an anim.timeline or anim.keyframe line to execute
  bool record = false;                    // the Record button: open the Record dialog
  bool frame_changed = false;             // the user moved the current frame (scrub, field, buttons)
};

// Draws the docked "Timeline" window in `rect`. `playback` is edited in place.
TimelineRequest draw_timeline_panel(const Rect& rect, const core::Timeline& timeline, Playback& playback,
                                    const TimelineObject& object, TimelinePanelState& state);

// Height of the panel for the current font, pixels (two rows: controls, scrub bar).
float timeline_panel_height();

// The key-insertion line for the I key: the panel's offset for the selected keyable object at the current frame,
// or nothing (no keyable object selected).
std::optional<nlohmann::json> insert_key_request(const TimelineObject& object, const Playback& playback,
                                                 const TimelinePanelState& state);
// The deletion line for Alt+I: nothing when the object has no key at the current frame.
std::optional<nlohmann::json> delete_key_request(const TimelineObject& object, const Playback& playback);

}  // namespace trispline::ui
