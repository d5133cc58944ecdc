// trispline::editor — `trispline bench dffd`: the per-frame cost of a global discontinuous FFD (seed §6.3) on the
// 35K-vertex bunny walking through three bars (assets/scenes/seed/bars_walk.jsonl): split + cap + deform at frames
// where the bunny is cut, per stage; and `incision.draw`'s core on a ~100K-vertex surface when the incision module is
// there. Prints figures; never asserts timings (docs/performance.md records them with the machine).
#pragma once

#include <iosfwd>
#include <string>

namespace trispline::editor {

struct BenchDffdOptions {
  std::string scene_path;  // empty: assets/scenes/seed/bars_walk.jsonl
  int runs = 7;            // timed evaluations per frame (median), ≥ 1
  int frames = 9;          // frames sampled evenly over the walk, ≥ 1
  bool json = false;       // one JSON object instead of a table
};

// Returns 0, or 1 with a message on `err` when the scene cannot be loaded.
int run_bench_dffd(const BenchDffdOptions& options, std::ostream& out, std::ostream& err);

}  // namespace trispline::editor
