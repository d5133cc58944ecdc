// trispline::editor::LastStep — the History step a stroke tool made last, so that the tool can re-run it with new
// values while it is still the newest applied step (Blender's "Adjust Last Operation"): the Sketch tool's
// place.sketch, the Incision tool's incision.draw.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "editor/commands/history.h"

namespace trispline::editor {

struct LastStep {
  const core::Command* command = nullptr;  // identity of the History entry (compared, never dereferenced)
  std::size_t applied = 0;                 // History::applied() right after it ran

  // Takes the newest applied step of `h` as the tool's (call right after the tool's command ran).
  void mark(const History& h) {
    applied = h.applied();
    command = applied > 0 ? &h.at(applied - 1) : nullptr;
  }

  // Whether the tool's step is still the newest applied one: the same History entry, of command `id`, and — since a
  // new command can reuse the freed memory of an undone one — a line naming `object` with a stroke of
  // `stroke_points` points.
  bool is_top(const History& h, const char* id, const std::string& object, std::size_t stroke_points) const {
    if (!command || h.applied() != applied || h.applied() == 0) return false;
    const core::Command& top = h.at(h.applied() - 1);
    if (&top != command || top.id() != id) return false;
    const nlohmann::json j = top.to_json();
    return j.value("object", "") == object && j.contains("stroke") && j["stroke"].size() == stroke_points;
  }
};

}  // namespace trispline::editor
