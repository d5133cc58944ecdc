// trispline::editor `trispline bench editor`: the editor's own frame times on real scenes, under X (Xvfb and Mesa's
// llvmpipe when there is no GPU), beside Blender's viewport redraw of the same meshes in the same run.
//
// Scenes: "default" (assets/scenes/default.jsonl: the teapot and the placed bunny), "tiles" (the teapot filled with
// thorns at tile size 0.065, auto UVs: ~1,200 tiles, ~770 K tile vertices) and "volume" (a CT/MRI volume, default
// the Cranium CT at 226 HU, with its silhouettes). Each opens in the real editor (`trispline edit --bench-out`,
// AppOptions::bench_out): idle frames (a redraw with nothing changed) and frames orbiting 3° a frame. Blender 3.4
// (scripts/blender_redraw_timer.py, Solid shading, `bpy.ops.wm.redraw_timer`) draws the same meshes — the scene's
// scene.glb from `trispline replay`, for the volume its iso-surface as a mesh (Blender does not ray cast splines) —
// idle and orbiting 3° a redraw. Then the cost of recording with a render-hidden volume: `anim.record` of the default
// scene with and without a loaded, render-hidden volume (replay, 640×360), per frame.
// Prints figures; never asserts timings (docs/performance.md records them with the machine).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace trispline::editor {

struct EditorBenchOptions {
  int frames = 30;                                       // idle frames and orbiting frames per scene
  std::filesystem::path assets = "assets";               // holds scenes/default.jsonl and data/
  std::string volume_path = "assets/data/Cranium.inv3";  // the volume scene's volume
  double iso = 226.0;                                    // its iso-level, the volume's units
  int width = 1280, height = 800;                        // the editor's and Blender's window, pixels
  int record_frames = 12;                                // frames recorded with and without the hidden volume
  bool blender = true;                                   // also time Blender (its absence is an error)
  std::filesystem::path work;                            // logs, outputs and child logs; default a fresh temp folder
};

// Result: {"bench":"editor", "frames", "window":[w,h], "gl_renderer", "work",
//          "scenes":[{"name":"default|tiles|volume", "idle_median_ms", "idle_p95_ms", "orbit_median_ms",
//                     "orbit_p95_ms", "viewport":[w,h], "silhouette_median_ms" (volume: extractions while orbiting),
//                     "blender_redraw_ms" (idle median), "blender_orbit_median_ms", "blender_vertices"}],
//          "record_hidden_volume_ratio": per-frame recording time with the hidden volume ÷ without,
//          "record_ms_per_frame": {"without", "with_hidden_volume"}}.
// Throws std::runtime_error when there is no X display, a scene cannot be opened, or Blender fails (its log named).
nlohmann::json run_editor_benchmark(const EditorBenchOptions& options);

}  // namespace trispline::editor
