#include "editor/commands/command_registry.h"

#include "core/commands/anim_clip.h"
#include "core/commands/anim_keyframe.h"
#include "core/commands/anim_keys.h"
#include "core/commands/anim_record.h"
#include "core/commands/anim_timeline.h"
#include "core/commands/camera_set.h"
#include "core/commands/ddm_animate.h"
#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_export.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_paint.h"
#include "core/commands/ddm_remove.h"
#include "core/commands/dffd_animate.h"
#include "core/commands/dffd_cut.h"
#include "core/commands/dffd_split.h"
#include "core/commands/incision_animate.h"
#include "core/commands/incision_draw.h"
#include "core/commands/lattice_animate_offset.h"
#include "core/commands/lattice_certify.h"
#include "core/commands/lattice_press.h"
#include "core/commands/lattice_pull_column.h"
#include "core/commands/lattice_ring.h"
#include "core/commands/lattice_set_point.h"
#include "core/commands/mesh_refine.h"
#include "core/commands/mesh_set.h"
#include "core/commands/mesh_subdivide.h"
#include "core/commands/object_inside.h"
#include "core/commands/object_transform.h"
#include "core/commands/object_visibility.h"
#include "core/commands/place_array.h"
#include "core/commands/place_sketch.h"
#include "core/commands/scene_load.h"
#include "core/commands/scene_primitive.h"
#include "core/commands/scene_remove.h"
#include "core/commands/scene_text.h"
#include "core/commands/volume_export.h"
#include "core/commands/volume_iso.h"
#include "core/commands/volume_load.h"
#include "core/commands/volume_remove.h"
#include "core/commands/volume_render.h"
#include "core/commands/volume_silhouettes.h"

namespace trispline::editor {

void CommandRegistry::add(const std::string& id, std::string summary, CommandParser parser) {
  entries_[id] = Entry{std::move(summary), std::move(parser), {}, false};
}

core::CommandPtr CommandRegistry::parse(const nlohmann::json& line, const core::CommandContext& ctx) const {
  if (!line.is_object()) throw core::CommandError("a command must be a JSON object");
  auto it = line.find("cmd");
  if (it == line.end()) throw core::CommandError("field 'cmd': missing", "cmd");
  if (!it->is_string()) throw core::CommandError("field 'cmd': expected a string", "cmd");
  const std::string id = it->get<std::string>();
  auto e = entries_.find(id);
  if (e == entries_.end()) throw core::CommandError("field 'cmd': unknown command '" + id + "'", "cmd");
  return e->second.parser(line, ctx);
}

std::vector<std::string> CommandRegistry::ids() const {
  std::vector<std::string> out;
  for (const auto& [id, e] : entries_) out.push_back(id);
  return out;
}

const std::string& CommandRegistry::summary(const std::string& id) const { return entries_.at(id).summary; }

const std::vector<core::ParamDoc>& CommandRegistry::params(const std::string& id) const {
  return entries_.at(id).params;
}

bool CommandRegistry::declared(const std::string& id) const { return entries_.at(id).declared; }

const CommandRegistry& CommandRegistry::builtin() {
  static const CommandRegistry registry = [] {
    CommandRegistry r;
    r.add<core::SceneLoadCommand>();
    r.add<core::ScenePrimitiveCommand>();
    r.add<core::SceneTextCommand>();
    r.add<core::SceneRemoveCommand>();
    r.add<core::ObjectTransformCommand>();
    r.add<core::ObjectVisibilityCommand>();
    r.add<core::ObjectInsideCommand>();
    r.add<core::CameraSetCommand>();
    r.add<core::PlaceSketchCommand>();
    r.add<core::LatticeRingCommand>();
    r.add<core::LatticeAnimateOffsetCommand>();
    r.add<core::LatticePressCommand>();
    r.add<core::LatticePullColumnCommand>();
    r.add<core::LatticeSetPointCommand>();
    r.add<core::LatticeCertifyCommand>();
    r.add<core::MeshRefineCommand>();
    r.add<core::MeshSubdivideCommand>();
    r.add(core::MeshSetCommand::kId, "Replace an object's mesh with given vertices and triangles",
          [](const nlohmann::json& line, const core::CommandContext&) { return core::MeshSetCommand::parse(line); });
    r.add<core::DdmFillCommand>();
    r.add<core::DdmPaintCommand>();
    r.add<core::DdmBakeCommand>();
    r.add<core::DdmRemoveCommand>();
    r.add<core::DdmColorCommand>();
    r.add<core::DdmAnimateCommand>();
    r.add<core::DdmExportCommand>();
    r.add<core::AnimTimelineCommand>();
    r.add<core::AnimKeyframeCommand>();
    r.add<core::AnimClipCommand>();
    r.add<core::DffdCutCommand>();
    r.add<core::IncisionDrawCommand>();
    r.add<core::IncisionAnimateCommand>();
    r.add<core::DffdSplitCommand>();
    r.add<core::DffdAnimateCommand>();
    r.add<core::PlaceArrayCommand>();
    r.add<core::AnimRecordCommand>();
    r.add<core::VolumeLoadCommand>();
    r.add<core::VolumeIsoCommand>();
    r.add<core::VolumeRenderCommand>();
    r.add<core::VolumeSilhouettesCommand>();
    r.add<core::VolumeExportCommand>();
    r.add<core::VolumeRemoveCommand>();
    return r;
  }();
  return registry;
}

}  // namespace trispline::editor
