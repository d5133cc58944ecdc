// `place.array` — a row of copies of a placed object walking the same path (seed §2.4.3, Fig. 2.11: the ants).
// Fields: declared in place_array.cpp (ParamSchema), listed in docs/commands.md.
// Adds n = count copies named "<ID>.001", "<ID>.002", … (the next free names) right after the object. Copy k (1..n)
// shares the object's lattice, embedding, clip and keys, and is shifted back along the path by k·s in u (s = spacing;
// with place.sketch "extent":e the object covers u ∈ [0, e], so s ≥ e keeps the copies apart): its param_offset and
// every offset key get −k·s in u. A clip starts k·p seconds later on copy k (p = clip_phase_s), so gaits differ.
// Copies get the next palette colours. Undo removes the copies.
// Errors beyond the declared ranges (CommandError, field named): unknown or undeformed object ("object").
#pragma once

#include <vector>

#include "core/commands/command.h"
#include "core/commands/declared_command.h"

namespace trispline::core {

struct PlaceArrayParams {
  std::string object;
  int count = 2;
  double spacing = 0.25;      // parameter units along u
  double clip_phase_s = 0.0;  // seconds
};

class PlaceArrayCommand : public DeclaredCommand<PlaceArrayCommand, PlaceArrayParams> {
 public:
  static Schema declare();

  void redo(Scene& scene) override;
  void undo(Scene& scene) override;
  nlohmann::json stats() const override { return stats_; }

 private:
  std::vector<std::string> added_;  // names of the copies, known after redo
  nlohmann::json stats_ = nlohmann::json::object();
};

}  // namespace trispline::core
