// trispline::editor — `trispline bench ddm`: live DDM layers drawn by the renderer's instanced GPU path (seed
// §5.3.2, Table 5.1) in an offscreen target: per case the tile vertices, the GPU time of the layer pass
// (RenderStats::ddm_ms, GpuTimer: GL_TIME_ELAPSED queries on GPUs, glFinish + wall clock on llvmpipe), the whole
// frame (draw + glFinish, wall clock) and frames per second. Cases (like the seed's table, with our tiles):
//   thorns_face      assets/scenes/seed/face_thorns.jsonl replayed: 645 thorns painted on the Loop limit surface of
//                    CGAL's Nefertiti face mask, ≈ 0.40 M vertices (needs the repository's assets: run from its root
//                    after scripts/fetch_assets.sh; skipped with a note otherwise, an error when asked for by name)
//   thorns_teapot    640 thorns (626 vertices each) on the teapot's body patches, ≈ 0.40 M vertices
//   chains_1m        a chain tile (1152 vertices) on every chart of the Loop limit surface of a sphere, ≈ 1.0 M
//   chains_3m        the same on a finer sphere, ≈ 3.1 M
// Orbit cases (the editor's view of a filled teapot on this renderer, ViewOptions::ddm): assets/scenes/default.jsonl
// replayed (teapot and bunny) and the teapot filled as the Tile Paint panel fills it by default (thorns, its default
// base teapot_body and tile size: a tenth of the mesh's diagonal), at rest and orbiting 3° per frame round the scene
// camera's target, with everything drawn, with culling, and with culling and the motion LOD (the editor's budget for
// this renderer); MSAA as the editor's window (none on a software renderer):
//   orbit_default    the panel's defaults
//   orbit_fine       the same with a quarter of the default tile size (16× the tiles)
// The generated layers' texture-space offset moves every frame (seed §5.4.2); every frame evaluates every tile vertex
// in the vertex shader either way. Prints figures; never asserts timings (docs/performance.md records them with the
// machine).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace trispline::editor {

struct BenchDdmOptions {
  int frames = 30;                 // timed frames per case (after 2 warm-up frames), ≥ 1
  int width = 1280, height = 720;  // offscreen target, pixels
  int samples = 4;                 // MSAA samples of the target (as the editor's viewport)
  std::vector<std::string> cases;  // empty: all; else names from the lists above
  bool cpu_reference = true;       // also time one core::ddm_layer_mesh of each layer (the CPU reference)
  bool json = false;               // one JSON object instead of a table
};

// Returns 0; 1 with a message on `err` when no GL context can be made, a case name is unknown, thorns_face is asked
// for without its assets, or a case cannot be built.
// JSON: {bench:"ddm", renderer, timer_mode, cpu, threads, width, height, samples, frames,
//        cases [{name, base, tile, instances, tile_vertices, vertices, setup_ms, first_frame_ms, cpu_reference_ms,
//                ddm_gpu_ms {median, min, max}, draw_ms_median, frame_ms {median, min, max}, fps,
//                vertices_per_s}],
//        orbit [{name, tile_size, instances, vertices, modes [{mode: rest | orbit_all | orbit_cull | orbit_lod,
//                frame_ms {median, min, max}, fps, drawn_median, culled_median, keep_median}]}]}
int run_bench_ddm(const BenchDdmOptions& options, std::ostream& out, std::ostream& err);

}  // namespace trispline::editor
