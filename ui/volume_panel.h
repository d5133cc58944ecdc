// trispline::ui Volume panel — the selected CT/MRI volume (core::VolumeObject, seed ch. 7): what it is (grid, spacing,
// units, value range, file), its iso-level, its silhouettes' settings and the export buttons. Plain data in, intents
// out: the editor executes volume.iso / volume.silhouettes lines, draws the live iso preview and opens the Save
// dialog for an export (editor/volume_ui.h).
//
//   Iso-level    a drag field in the volume's units over the values D takes (a click types a value): while dragged
//                the preview level is returned every frame (the ray caster and the live silhouettes follow it); on
//                release (or Enter) one volume.iso line
//   Silhouettes  on/off, style, hidden lines, projection, subdivision, accuracy: each change one volume.silhouettes
//                line carrying all of them
//   More levels  further iso-levels drawn as silhouettes only (seed Figs. 7.4–7.6, 7.12): level, style, colour,
//                remove, Add level; each change one volume.iso line with every level
//   Render       iso-surface or direct volume rendering (seed §7.4, Fig. 7.7); for the latter the transfer function
//                as a table (value, colour and opacity per point; remove, Add point, presets) and the step: each
//                change one volume.render line with all of them (value drags on release)
//   Export       silhouettes as SVG or glTF lines, the iso-surface as GLB / OBJ / PLY
// Widgets are named for GUI tests: "volume.iso", "volume.silhouettes.<field>", "volume.export.<kind>",
// "volume.levels.add", "volume.levels.<k>" (k = 1, 2, … the further levels), "volume.levels.<k>.style",
// "volume.levels.<k>.color", "volume.levels.<k>.remove", "volume.render.mode", "volume.render.step",
// "volume.transfer.<i>" (point i's value), "volume.transfer.<i>.color", "volume.transfer.<i>.remove",
// "volume.transfer.add", "volume.transfer.preset".
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/commands/volume_iso.h"
#include "core/commands/volume_render.h"
#include "core/commands/volume_silhouettes.h"
#include "core/scene/scene.h"
#include "ui/layout.h"

namespace trispline::ui {

// The panel's values while edited, kept by the editor across frames: a value being dragged or typed is not refreshed
// from the volume until it is committed, and values the volume changes (undo, a replayed command) are picked up.
struct VolumePanelState {
  std::string volume;  // whose values these are
  double iso = 0.0;    // the iso field (volume units)
  double seen_iso = 0.0;
  core::VolumeSilhouettesParams silhouettes;  // the silhouette section (object = volume)
  core::VolumeSilhouetteSettings seen;        // the volume's settings when last refreshed
  std::vector<double> more_iso;               // the further levels' fields (VolumeObject::more_levels)
  std::vector<double> seen_more_iso;
  core::VolumeRenderParams render;  // the Render section (object = volume; transfer always set)
  core::VolumeRenderParams seen_render;
};

// What the live silhouettes are doing, for the panel's status line.
struct VolumeLiveInfo {
  bool extracting = false;  // an extraction is running
  std::size_t points = 0;   // points of the silhouettes drawn
  double ms = -1.0;         // wall time of their extraction, ms (negative: none yet)
  bool current = false;     // they are for the current view and iso-level
};

// The export kinds, in the panel's order: id (probe "volume.export.<id>"), `what` of volume.export, file extension.
struct VolumeExportKind {
  const char* id;
  const char* what;       // "silhouettes" | "iso"
  const char* extension;  // ".svg", ".glb", ".obj", ".ply"
  const char* label;      // button text
  const char* tooltip;
};
inline constexpr VolumeExportKind kVolumeExports[] = {
    {"svg", "silhouettes", ".svg", "SVG",
     "The silhouettes of the current view as an SVG line drawing (pixels of the "
     "view; hidden lines as set above, strokes in the style set above)"},
    {"silhouettes_glb", "silhouettes", ".glb", "Lines GLB",
     "The silhouettes of the current view as glTF line strips in world millimetres (hidden parts kept unless "
     "'remove')"},
    {"iso_glb", "iso", ".glb", "GLB",
     "The iso-surface D = iso-level as a triangle mesh (OpenVDB on the sampled "
     "spline, vertices projected onto the spline), world millimetres"},
    {"iso_obj", "iso", ".obj", "OBJ", "The iso-surface as a Wavefront OBJ mesh with normals, world millimetres"},
    {"iso_ply", "iso", ".ply", "PLY", "The iso-surface as a PLY mesh with normals, world millimetres"},
};

struct VolumePanelResult {
  std::optional<double> iso_preview;              // the iso field is being dragged or typed: draw this level
  std::optional<nlohmann::json> line;             // a volume.iso, .silhouettes or .render line to execute
  const VolumeExportKind* export_kind = nullptr;  // an Export button was clicked
};

// "0.98 × 0.98 × 1.50 mm": the grid spacing along the index axes (lengths of index_to_world's columns).
std::string volume_spacing_text(const core::VolumeSpline& spline);

// Draws the panel as the docked window "Volume" in `rect` for volume `v`.
VolumePanelResult draw_volume_panel(const Rect& rect, const core::VolumeObject& v, VolumePanelState& state,
                                    const VolumeLiveInfo& live);

// The volume.iso line that sets `v`'s levels to its current ones with further level `k` (0-based) changed by `edit`
// (null: unchanged), removed (`remove`), or a new level `add` appended.
nlohmann::json volume_levels_line(const core::VolumeObject& v, int k,
                                  const std::function<void(core::VolumeLevelSpec&)>& edit, bool remove = false,
                                  std::optional<double> add = std::nullopt);

}  // namespace trispline::ui
