// `ddm.export` — writes a tile layer's sampled position or normal map as a PNG picture (core/ddm/ddm_map_image.h:
// seed Figs. 5.3 and 5.5). Fields: declared in ddm_export.cpp (ParamSchema), listed in docs/commands.md.
// The output folder and path checks are volume.export's (CommandContext::resolve_output: paths that leave the output
// folder are refused); the picture is made before anything is written, and the scene does not change (undo has
// nothing to restore; the file stays). stats(): width, height, charts and the file.
// A FileOutput (core/commands/file_output.h): Open and crash recovery write nothing; History's Run again writes the
// same bytes later.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/file_output.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct DdmExportParams {
  std::string object, layer;
  std::string what = "positions";  // positions | normals
  std::string path;
};

class DdmExportCommand : public ObjectSnapshotCommand<DdmExportCommand, DdmExportParams>, public FileExport {
 public:
  // `file`: p.path resolved by CommandContext::resolve_output (absolute, inside the output folder).
  DdmExportCommand(DdmExportParams p, std::filesystem::path file)
      : ObjectSnapshotCommand(std::move(p)), FileExport(std::move(file)) {}
  static Schema declare();
  static CommandPtr parse(const nlohmann::json& line, const CommandContext& ctx) {
    return parse_with_output<DdmExportCommand>(line, ctx);
  }

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
