// trispline::editor GUI probe file — `trispline edit --gui-probe FILE` writes, after every frame, one small JSON
// object that GUI tests (tests/gui/gui_lib.sh) poll instead of reading pixels:
//   frame              frames drawn so far
//   popups             names of the open ImGui popups (menus, modals), innermost last; [] when none
//   typing             a text field has the keyboard (io.WantTextInput)
//   tooltip            a tooltip is drawn this frame
//   items              {"name": [x0, y0, x1, y1]} screen rectangles of the widgets named with ui::probe::item()
//   values             {"name": "text"} of ui::probe::value() (e.g. the file dialog's path field)
//   the editor's part  document, modified, history {labels, applied}, objects, object_px (each object's bounds
//                      centre on screen), selected, tool, log (last messages), viewport (the visible region
//                      [x0, y0, x1, y1]), scene_center_px, camera, current_frame, transform (the G / R / S
//                      modal's header line while it runs, else null), volumes (name, iso, preview_iso, dims,
//                      silhouettes, style, live_points, live_current, extracting), volume_load (path, progress,
//                      cancel; null when none runs), volume_refining (the last frame showed a volume preview)
// Written to FILE.tmp and renamed, so a reader never sees half a file.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace trispline::editor {

nlohmann::json imgui_probe_fields();  // popups, tooltip, typing, items (call after the frame's widgets, before Render)
void write_probe_file(const std::filesystem::path& path, const nlohmann::json& probe);  // atomic; errors ignored

}  // namespace trispline::editor
