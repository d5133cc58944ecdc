// trispline::core prepared volumes: a volume file read, made into its spline D and preprocessed into singletons —
// everything volume.load needs, computed once per file content and kept in memory for the session. Nothing is kept on
// disk: preparing takes about a second per 3.5 M samples on 2 cores, less than reading back and checking a table that
// takes 24 bytes a sample (docs/decisions.md, Caches).
//
// The editor prepares a volume on a worker thread (progress bar, Cancel) and then runs volume.load, which finds the
// prepared volume in the session cache and returns at once; a replay prepares it inside the command. Either way the
// command's result is the same (deterministic preprocessing).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/volume/preparation_budget.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_io.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

struct PreparedVolume {
  std::shared_ptr<const VolumeSpline> spline;   // non-null
  std::shared_ptr<const SingletonTable> table;  // non-null
  std::string units, modality, source, frame;   // as ScalarVolume
  bool superior_up = false;                     // the world was turned so that superior is +Y (prepare_volume)
  double default_iso = 0.0;                     // default_iso_level of the samples
  double load_ms = 0.0, prep_ms = 0.0;          // reading the file; spline + singletons
};

// The loader options of a volume about to be prepared: the whole kPreparedVolumeBudget, and
// kPreparationBytesPerVoxel as extra_bytes_per_voxel, so the loader refuses a file whose header dimensions leave no
// room for the spline and its table before it inflates a byte.
VolumeLoadOptions preparation_load_options();

// Reads `path` (load_volume with preparation_load_options(); "analytic:sphere|torus|sines" makes an analytic volume
// of 96 samples a side), builds the spline of `order` (2…4; interpolating or not) and its singleton table. A second
// call with the same path, file size, modification time, order and mode returns the session's copy (the session keeps
// the last three, older ones only while all of them hold less than kPreparedVolumeBudget). Throws std::invalid_argument
// on a bad order (before reading), what load_volume throws (VolumeLoadError, among others over the budget from the
// header's dimensions), PreparationBudgetError when samples, spline and table would exceed kPreparedVolumeBudget
// (checked from the dimensions and order before the spline is made), OperationCancelled through `progress`.
PreparedVolume prepare_volume(const std::filesystem::path& path, int order, bool interpolate,
                              const ProgressSink& progress = {}, bool superior_up = false);

// The rotation that turns a patient frame ("RAS" or "LPS") into the editor's Y-up world: superior → +Y, anterior →
// +Z (facing a camera on +Z), the patient's right → −X (the viewer's left); identity for any other frame.
glm::dmat4 superior_up_rotation(const std::string& frame);

// Forgets the session's prepared volumes (tests; memory).
void clear_prepared_volumes();

// A sensible first iso-level: 226 for CT in HU (InVesalius' bone threshold), else Otsu's threshold of the samples
// (the level that best separates two classes of values; Otsu 1979, 256-bin histogram).
double default_iso_level(const ScalarVolume& volume);

}  // namespace trispline::core
