// trispline::core prepared volumes: a volume file read, made into its spline D and preprocessed into singletons —
// everything volume.load needs, computed once per file content and kept (in memory for the session, on disk across
// sessions: singletons.h cached_singleton_table).
//
// The editor prepares a volume on a worker thread (progress bar, Cancel) and then runs volume.load, which finds the
// prepared volume in the session cache and returns at once; a replay prepares it inside the command. Either way the
// command's result is the same (deterministic preprocessing).
#pragma once

#include <filesystem>
#include <cstdint>
#include <memory>
#include <string>

#include "core/volume/singletons.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

// Memory a prepared volume's spline and singleton table may take (bytes): 6 GiB, ~200 M voxels (a 585³ CT).
inline constexpr std::uint64_t kPreparedVolumeBudget = 6ull << 30;

struct PreparedVolume {
  std::shared_ptr<const VolumeSpline> spline;   // non-null
  std::shared_ptr<const SingletonTable> table;  // non-null
  std::string units, modality, source;          // as ScalarVolume
  double default_iso = 0.0;                     // default_iso_level of the samples
  bool table_from_disk = false;                 // the singleton table came from the disk cache
  double load_ms = 0.0, prep_ms = 0.0;          // reading the file; spline + singletons (or reading the cache)
};

// Reads `path` (load_volume; "analytic:sphere|torus|sines" makes an analytic volume of 96 samples a side), builds the
// spline of `order` (2…4; interpolating or not) and its singleton table. A second call with the same path, file size,
// modification time, order and mode returns the session's copy. Throws what load_volume throws (VolumeLoadError),
// std::invalid_argument on a bad order or a volume whose table would exceed kPreparedVolumeBudget (checked before it
// is built), OperationCancelled through `progress`.
PreparedVolume prepare_volume(const std::filesystem::path& path, int order, bool interpolate,
                              const ProgressSink& progress = {});

// Forgets the session's prepared volumes (tests; memory).
void clear_prepared_volumes();

// A sensible first iso-level: 226 for CT in HU (InVesalius' bone threshold), else Otsu's threshold of the samples
// (the level that best separates two classes of values; Otsu 1979, 256-bin histogram).
double default_iso_level(const ScalarVolume& volume);

}  // namespace trispline::core
