// `volume.export` — writes a volume's silhouettes or iso-surface to a file. Fields: declared in volume_export.cpp
// (ParamSchema), listed in docs/commands.md.
// what = silhouettes: extracted for the camera (the volume's style, hidden-line mode and projection) and written as
// SVG (.svg: a line drawing for illustrations, the camera's viewport in pixels) or glTF line strips (.glb: world
// millimetres, a node "<id>/silhouettes"); the volume keeps them (scene.glb exports them too).
// what = iso: the surface D = iso as a triangle mesh (OpenVDB volume-to-mesh on the sampled spline, vertices projected
// onto D = iso: iso_mesh.h) written as .glb, .obj or .ply (world millimetres); the volume keeps it (scene.glb node
// "<id>/iso").
// The output folder is CommandContext::output_dir (replay's --out, the folder chosen in the editor's export dialog;
// else the log's folder); CommandContext::resolve_output resolves the path inside it (paths that leave it through `..`
// or a symlink are refused); the logged line keeps the relative path. The result is checked before anything is
// written: non-finite points or vertices fail the command (field "object"), no file.
// Undo forgets what the volume kept (the file stays). stats(): what was written (points/polylines or
// vertices/triangles), the file and ms.
// A FileOutput (core/commands/file_output.h): with set_writes_files(false) (Open, crash recovery) the volume keeps
// the same result and no file is written; write_files() writes it later (History's Run again), the same bytes.
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/file_output.h"
#include "core/commands/volume_snapshot.h"

namespace trispline::core {

struct VolumeExportParams {
  std::string object;
  std::string what = "silhouettes";  // silhouettes | iso
  std::string path;
  int samples_per_voxel = 1;     // iso: IsoMeshOptions::samples_per_voxel
  std::optional<Camera> camera;  // silhouettes: the view (camera.set's fields); default: the scene camera
};

class VolumeExportCommand
    : public ObjectSnapshotCommand<VolumeExportCommand, VolumeExportParams, VolumeSnapshotCommand>,
      public FileExport {
 public:
  // `file`: p.path resolved by CommandContext::resolve_output (absolute, inside the output folder).
  VolumeExportCommand(VolumeExportParams p, std::filesystem::path file)
      : ObjectSnapshotCommand(std::move(p)), FileExport(std::move(file)) {}
  static Schema declare();
  static CommandPtr parse(const nlohmann::json& line, const CommandContext& ctx) {
    return parse_with_output<VolumeExportCommand>(line, ctx);
  }

 protected:
  std::optional<VolumeObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
