// `trispline bench place` and `trispline bench press` — figures for docs/performance.md. Numbers, never asserts.
//
// bench place (bench_place.cpp): placement end to end through the real command path (registry parse →
// History::execute → undo, as the editor and replay run it) — the Stanford bunny (assets/data/bunny.obj, 34,835
// vertices; a scene.primitive sphere when absent) placed along a stroke over a real scene:
//   teapot   assets/scenes/default.jsonl: the teapot primitive, its camera and its stroke (offset volume, 12×5×3)
//   terrain  tests/logs/real_mesh_on_terrain.jsonl: seeded terrain "hills", its camera and its stroke (extrude,
//            10×4×2), the bunny in place of Venus (length axis x, up axis y)
// with nu×nv contact rays (default 64×8), mass-spring contact surface on ("springs" as in
// tests/logs/bridge_springs.jsonl: stiffness 100, damping 30, threshold 5°, at most 5000 steps) and off. Each case:
// one untimed warm-up, then `runs` timed executions; per stage (the place.sketch stats that ui/frame_timings.h
// reads: bvh, fit, rays, surface, springs, volume, embed, evaluate), the command's wall time ("total", what
// History records) and "other" (= total − stages: snapshot, rest-mesh transform), the median over runs, ms.
//
// bench press (bench_press.cpp): one pressing drag on a big object (the bunny refined with core::subdivide_bilinear
// to the level closest to --vertices, default 1 M → 835,994 vertices; a UV sphere of ~N vertices when the file is
// absent) placed with place.sketch on the teapot scene (12×5×3 lattice), driven through the real Press tool
// (editor/tools/press_tool.h) over a row of the default 1280×720 view, and per drag sample (path prefix) the cost
// of the live preview: (a) the pressed lattice (lattice.press on a proxy object that shares the
// lattice and embedding but has 8 vertices: redo time − its ms_evaluate), (b) re-evaluating every vertex with
// positions + normals: cpu_fast (set_lattice + evaluate, then read-back and, with GL, MeshBuffers upload) and
// glsl_compute (set_lattice + evaluate + glFinish; needs an EGL context), and (c) the full lattice.press command at
// mouse release (History::execute: snapshot + double-precision reference re-evaluation, undone between runs).
// "interactive" = at least 30 updates per second.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/ffd_bench.h"

namespace trispline::editor {

struct BenchPlaceOptions {
  std::string mesh_path;              // empty: assets/data/bunny.obj (sphere primitive if absent)
  int runs = 5;                       // timed runs per case (median), ≥ 1
  int samples_u = 64, samples_v = 8;  // contact rays nu × nv (each ≥ the lattice's controls there)
  std::string springs = "both";       // "on" | "off" | "both"
  std::vector<std::string> scenes{"teapot", "terrain"};  // each "teapot" or "terrain"
  bool json = false;                                     // one JSON object on `out` instead of a table
};

// Returns the process exit code (0). Progress lines go to `err`. Throws std::invalid_argument on bad options and
// std::runtime_error when a set-up command or the placement fails (with the command's message).
// JSON: {bench:"place", cpu, threads, runs, samples:[nu,nv], mesh {source, fallback, vertices},
//        cases:[{scene, springs (bool), scene_vertices, rays_total, rays_hit, springs_steps, springs_converged,
//                warmup_ms, min_total_ms, max_total_ms, stages [names in pipeline order], median_ms {bvh, fit, rays,
//                surface, [springs], volume, embed, evaluate, other, total}}]}
int run_bench_place(const BenchPlaceOptions& options, std::ostream& out, std::ostream& err);

struct BenchPressOptions {
  std::string mesh_path;           // empty: assets/data/bunny.obj (UV sphere of ~vertices if absent)
  std::size_t vertices = 1000000;  // target vertex count (the subdivision level closest to it is used)
  int runs = 7;                    // drags / timed preview updates / command runs (median), ≥ 1
  bool json = false;
  bool gpu = true;  // also glsl_compute (needs an EGL context); false = --cpu-only
};

// Returns the process exit code (0). Throws as run_bench_place does.
// JSON: {bench:"press", cpu, threads, renderer, mesh {source, fallback, base_vertices, vertices, triangles,
//        subdivision_level}, lattice {controls, order}, place_ms, drag {pixels, samples, radius, strength},
//        tool {first_hover_ms, move_median_ms, move_max_ms, hover_after_release_ms, bvh_build_ms, ray_cast_ms,
//              default_radius_ms},
//        per_update [{stage, median_ms, updates_per_s, interactive}], bind_ms {cpu_fast, glsl_compute},
//        command {median_ms, ms_evaluate, updates_per_s, interactive}}
int run_bench_press(const BenchPressOptions& options, std::ostream& out, std::ostream& err);

// Helpers shared by both benches.
// The set-up lines of scene "teapot" or "terrain" (scene primitive, camera.set) followed, last, by its place.sketch
// line for the object "bunny" (no "samples", no "springs": the defaults apply), read from the scene's log (relative
// to the repository root). Throws std::invalid_argument for another name, std::runtime_error when the log cannot be
// read or has no place.sketch line.
std::vector<nlohmann::json> bench_place_scene(const std::string& name);
double bench_median(std::vector<double> values);    // of a non-empty list
using core::bench_cpu_model;                        // "model name" of /proc/cpuinfo, or "unknown"
double bench_ms(const std::function<void()>& fn);   // wall time of one call, milliseconds
std::string bench_fixed(double value, int digits);  // std::fixed with `digits` decimals
// Writes a benchmark's result: one JSON line with `json`, else `table`'s human-readable form. Returns 0 (the exit
// code).
int bench_emit(const nlohmann::json& result, bool json, std::ostream& out,
               void (*table)(const nlohmann::json&, std::ostream&));

}  // namespace trispline::editor
