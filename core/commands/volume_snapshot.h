// trispline::core::VolumeSnapshotCommand — base for commands that create, change or remove one volume (seed ch. 7):
// SnapshotCommand's transaction for a VolumeObject (splines, singleton tables and silhouettes are shared immutable
// pointers, so snapshots cost a few pointers).
#pragma once

#include <optional>

#include "core/commands/snapshot_command.h"

namespace trispline::core {

using VolumeSnapshotCommand = BasicSnapshotCommand<VolumeObject>;

// The volume named `name`. Throws CommandError (field `field`): no volume of that name (naming the object when the
// name is a mesh object's).
const VolumeObject& require_volume(const Scene& scene, const std::string& name, const char* field = "object");

// `volume` with its silhouettes — of its first level and of every further level (more_levels) — extracted for
// `camera` under its settings (null when disabled). Fills `stats` with the first level's figures (points, polylines,
// length_mm, candidates, seeds, extract_ms, hidden_ms, max_value_residual, max_dot_residual) and, with further
// levels, points_all_levels.
VolumeObject volume_with_silhouettes(const VolumeObject& volume, const Camera& camera, nlohmann::json* stats = nullptr);

}  // namespace trispline::core
