#include "editor/tools/select_tool.h"

#include <imgui.h>

#include <cmath>
#include <limits>

#include "core/mesh/mesh_io.h"
#include "core/raycast/ray_caster.h"
#include "core/volume/iso_raycast.h"
#include "editor/session/session.h"
#include "ui/gui_probe.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::editor {

std::optional<std::string> pick_object(const core::Scene& scene, const core::Camera& camera, glm::dvec2 px) {
  core::RayCaster caster;
  std::vector<std::string> names;
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible || !o.world_mesh || o.world_mesh->empty()) continue;
    caster.add_mesh(*o.world_mesh);
    names.push_back(o.name);
  }
  const glm::dvec3 dir = camera.ray_direction(px);
  std::optional<std::string> picked;
  double nearest = std::numeric_limits<double>::infinity();
  if (!names.empty()) {
    caster.commit();
    const auto hit = caster.intersect(camera.eye, dir);
    if (hit && hit->geometry >= 0 && hit->geometry < int(names.size())) picked = names[hit->geometry], nearest = hit->t;
  }
  // Volumes: the first crossing of their iso-surface D = iso along the same ray (the CPU reference of the drawn one).
  for (const core::VolumeObject& v : scene.volumes()) {
    if (!v.visible || !v.spline || !v.show_surface) continue;
    const core::IsoHit hit = core::iso_ray_hit(*v.spline, v.iso, camera.eye, dir, 0.25, nearest);
    if (hit.hit && hit.t < nearest) picked = v.name, nearest = hit.t;
  }
  return picked;
}

ui::ToolEntry SelectTool::entry() const { return {"Select", "Q", "Click an object to select it"}; }

void SelectTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  if (in.left_pressed) {
    pressed_ = true;
    press_px_ = in.mouse_px;
  }
  if (in.left_released && pressed_) {
    pressed_ = false;
    if (glm::length(in.mouse_px - press_px_) > 4.0) return;  // a drag, not a click
    try {
      const auto name = pick_object(ctx.session.scene(), ctx.view, in.mouse_px);
      ctx.selected = name.value_or("");
    } catch (const std::exception& e) {
      ctx.session.messages().error(std::string("pick failed: ") + e.what());
    }
  }
}

void SelectTool::draw_panel(ToolContext& ctx) {
  const core::SceneObject* o = ctx.session.scene().find(ctx.selected);
  if (!o && ctx.session.scene().find_volume(ctx.selected)) {
    ImGui::Text("%s", ctx.selected.c_str());
    ImGui::TextColored(ui::colors::dim, "A volume: its iso-level, silhouettes and exports are in the Volume panel.");
    return;
  }
  if (!o) {
    ImGui::TextColored(ui::colors::dim, "Nothing selected.");
    ImGui::TextWrapped("Click an object in the viewport or in the Scene panel.");
    return;
  }
  ImGui::Text("%s", o->name.c_str());
  ImGui::TextColored(ui::colors::dim, "%s", o->source.c_str());
  if (o->world_mesh)
    ImGui::Text("%zu vertices, %zu triangles", o->world_mesh->vertex_count(), o->world_mesh->triangle_count());
  const auto& t = o->transform;
  ImGui::Text("translate %.3g %.3g %.3g", t.translate.x, t.translate.y, t.translate.z);
  ImGui::Text("rotate    %.3g %.3g %.3g deg", t.rotate_deg.x, t.rotate_deg.y, t.rotate_deg.z);
  ImGui::Text("scale     %.3g %.3g %.3g", t.scale.x, t.scale.y, t.scale.z);
  if (o->ffd) ImGui::TextColored(ui::colors::accent, "Deformed by an FFD lattice");
  if (o->placement) ImGui::Text("Placed: %d x %d contact rays", o->placement->samples_u, o->placement->samples_v);
  draw_ring_section(ctx, *o);
}

void SelectTool::draw_ring_section(ToolContext& ctx, const core::SceneObject& o) {
  ImGui::Spacing();
  const bool open = ImGui::CollapsingHeader("Ring lattice");
  ui::probe::item("select.ring");
  ui::tooltip(
      "Bind the object to a ring-shaped lattice periodic around its axis, so that it can travel round without a seam "
      "(seed section 4.5); a twist of 180 degrees makes a Moebius band (Fig. 4.6). One undoable lattice.ring.");
  if (!open) return;
  if (ring_.object != o.name) {
    ring_ = core::LatticeRingParams{};
    ring_.object = o.name;
    // A ring twice the object's size across (its length fits a fraction of a turn), centred so that the object
    // starts where it stands: u = 0 lies at +x from the centre, w = 0 on the plane y = center.y under the object.
    const core::Aabb box = o.world_mesh ? core::mesh_bounds(*o.world_mesh) : core::Aabb{};
    const double diagonal = box.valid() ? box.diagonal() : 0.0;
    ring_.radius = std::isfinite(diagonal) && diagonal > 0.0 ? 2.0 * diagonal : 1.0;
    if (std::isfinite(diagonal) && diagonal > 0.0)
      ring_.center = glm::dvec3(box.center().x - ring_.radius, box.lo.y, box.center().z);
  }
  const auto& schema = core::LatticeRingCommand::schema();
  for (const char* field : {"center", "radius", "twist_deg", "phase", "controls"})
    ui::param_widget(schema, field, ring_);
  if (ImGui::Button("Bind to ring")) {
    ctx.execute_deferred("Binding " + o.name + " to a ring", schema.to_json(ring_));
  }
  ui::probe::item("select.ring.bind");
  ui::tooltip(
      "Replaces the object's FFD by the ring lattice; lattice.animate_offset (or anim.keyframe) then moves it round. "
      "Errors (a radius the object does not fit, a twist that is not a multiple of 90) go to the Log.");
}

}  // namespace trispline::editor
