// trispline::core::Command — one undoable change to the Scene (Blender operator / Godot UndoRedo style).
//
// Contract:
//  * id() is the stable string in the log's "cmd" field ("place.sketch"); to_json() is the complete log line
//    (it replays to the same result); label() is the human text of the History panel.
//  * redo(scene) is also "do". It computes everything first and mutates the scene only at the end, so when it
//    throws (CommandError) the scene is exactly as before. undo(scene) restores the state before redo bit for bit.
//  * stats() holds figures for report.json after the last redo (vertex counts, rays hit, stage timings in ms).
//  * A preparable() command can do its expensive part ahead of redo: prepare(scene, progress) runs on any thread over
//    `scene` — a copy of the document as redo will find it — and keeps its result; the next redo on that document
//    only applies it, bit for bit what an unprepared redo gives. The editor prepares ddm.fill / ddm.bake on a worker
//    thread behind a progress bar; replay never prepares (redo does everything, as for any command).
// Commands refer to objects by name, never by pointer.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/params/command_context.h"
#include "core/scene/scene.h"
#include "core/spline/progress.h"

namespace trispline::core {

// A command failed; the scene is unchanged. `field` names the offending JSON field when there is one.
class Command {
 public:
  virtual ~Command() = default;
  virtual std::string id() const = 0;
  virtual nlohmann::json to_json() const = 0;
  virtual std::string label() const = 0;
  virtual void redo(Scene& scene) = 0;  // throws CommandError; scene untouched on failure
  virtual void undo(Scene& scene) = 0;
  virtual nlohmann::json stats() const { return nlohmann::json::object(); }
  // Whether prepare() does this command's expensive part (default: no; prepare is then a no-op).
  virtual bool preparable() const { return false; }
  // The expensive part of redo over `scene` (not modified; the caller keeps it alive and unchanged meanwhile),
  // reporting to `progress` in [0, 1]. Throws CommandError (nothing prepared) or OperationCancelled (progress's
  // cancel flag was set; nothing prepared). Redo on a document other than `scene` is undefined: the caller blocks
  // every other change between prepare and redo.
  virtual void prepare(const Scene& /*scene*/, const ProgressSink& /*progress*/) {}
  // False for an action that leaves the document alone and is logged only so a replay repeats it (anim.record, like
  // Blender's renders): the history runs and logs it but never makes it an undo step.
  virtual bool undoable() const { return true; }
};

using CommandPtr = std::unique_ptr<Command>;

}  // namespace trispline::core
