// `volume.load` — adds a CT/MRI volume as a scalar trivariate B-spline D (seed ch. 7). Fields: declared in
// volume_load.cpp (ParamSchema), listed in docs/commands.md.
// The file loads whole or the command fails. A volume whose samples, spline and singleton table would exceed
// kPreparedVolumeBudget (preparation_budget.h: 40 bytes per sample) is refused from its header's dimensions, before
// the file is inflated (CommandError, field 'path', naming the dimensions, the bytes and the budget). The default
// iso-level comes from default_iso_level. World units are the file's millimetres. The singleton table is read from
// the disk cache when the same content was preprocessed before (prepared_volume.h). stats(): dims, order, units, iso,
// from_cache, load_ms, prep_ms, table_mb.
#pragma once

#include <optional>

#include "core/commands/declared_command.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

struct VolumeLoadParams {
  std::string path;      // a volume file, or
  std::string analytic;  // an analytic test volume: sphere | torus | sines
  std::string name;      // default: the file stem made unique
  int order = 4;
  bool interpolate = false;
  std::optional<double> iso;
  std::string axes = "superior_up";  // superior_up: the patient's superior axis is +Y | file: the file's own axes
};

class VolumeLoadCommand : public DeclaredSnapshotCommand<VolumeLoadCommand, VolumeLoadParams, VolumeSnapshotCommand> {
 public:
  static Schema declare();

 protected:
  std::string target() const override { return p_.name; }
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
