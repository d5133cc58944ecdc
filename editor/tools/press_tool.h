// trispline::editor::PressTool — spherical pressing of a deformed object's control lattice in the viewport (seed
// §2.4.1, Fig. 2.7, 2.8). A translucent sphere of the panel's radius follows the mouse over the
// chosen object (the object with an FFD lattice selected, or picked in the Object combo): its centre is the first
// ray hit on the object's deformed mesh (world_mesh) under the cursor. Left-drag samples the centre at every mouse
// move where the ray hits (misses skipped, samples closer than radius/4 to the previous one dropped) and shows the
// path; on mouse-up the tool executes ONE `lattice.press` command (core/commands/lattice_press.h) through the
// session (registry parse → History::execute; errors go to the Log panel, the scene stays as it was). Ctrl held at
// mouse-down pulls (negative strength), as Ctrl inverts a Blender sculpt brush. A drag that never hits the object
// issues nothing. With Keep fold-free on, the press (and its live preview) is limited to the largest strength whose
// lattice stays certified fold-free (core::press_lattice_fold_free); the panel says how far it was limited.
#pragma once

#include <future>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "core/commands/lattice_press.h"
#include "core/ffd/falloff.h"
#include "core/raycast/ray_caster.h"
#include "editor/tools/tool.h"
#include "ui/param_widgets.h"

namespace trispline::editor {

// The lattice.press line of `params` (core/commands/lattice_press.h): path #P×3, radius and strength world units.
nlohmann::json lattice_press_line(const core::LatticePressParams& params);

class PressTool : public Tool {
 public:
  ui::ToolEntry entry() const override;
  void activate(ToolContext& ctx) override;
  void deactivate(ToolContext& ctx) override;
  void handle_input(const ToolInput& in, ToolContext& ctx) override;
  void mouse_away() override;
  void draw_panel(ToolContext& ctx) override;
  void decorate(gpu::ViewOptions& options) const override;
  std::string hint() const override;
  bool owns_mouse() const override { return pressing_; }
  // During a drag: the object's lattice pressed along the path so far (core::press_lattice, the
  // same math as the command at mouse-up), recomputed only when the path grew; kept until the command has replaced
  // the object's lattice (at most a few frames), so the view never flickers back to the unpressed shape.
  std::optional<LivePreview> live_preview(const ToolContext& ctx) override;

  void set_object(const std::string& name) { object_ = name; }
  // World units; ≤ 0 = unset: the schema's object_size default (0.1 × the object's bounding-box diagonal).
  void set_radius(double r) { params_.radius = r; }
  // World units, the magnitude (Ctrl-drag negates it); ≤ 0 = unset: a quarter of the radius, a dent that shows.
  void set_strength(double s) { params_.strength = s; }
  void set_falloff(core::Falloff f) { params_.falloff = std::string(core::to_string(f)); }
  core::Falloff falloff() const { return core::parse_falloff(params_.falloff).value_or(core::Falloff::smooth); }
  // Keep fold-free: every press is limited (lattice.press keep_fold_free) so that the lattice stays certified.
  void set_keep_fold_free(bool on) { params_.keep_fold_free = on; }
  bool keep_fold_free() const { return params_.keep_fold_free; }
  // Radius the next press uses for the current object (the default when unset); 0 without a target object.
  double radius(const ToolContext& ctx) const;
  double strength(const ToolContext& ctx) const;  // the magnitude the next press uses (the default when unset)
  double signed_strength(const ToolContext& ctx) const { return pull_ ? -strength(ctx) : strength(ctx); }
  const std::optional<glm::dvec3>& hover() const { return hover_; }  // sphere centre under the cursor, if any
  const std::vector<glm::dvec3>& path() const { return path_; }      // centres of the drag under way

 private:
  const core::SceneObject* target(const ToolContext& ctx) const;  // object_ if it exists and has a lattice
  // First hit on the target's world_mesh; may use the previous mesh's BVH while the new one builds, unless
  // need_current (a drag presses what is shown).
  std::optional<glm::dvec3> cast(const ToolContext& ctx, glm::dvec2 px, bool need_current = false);
  void commit(ToolContext& ctx);
  // The panel's parts, top to bottom (draw_panel).
  const core::SceneObject* draw_object_combo(ToolContext& ctx);
  double draw_radius_field(ToolContext& ctx, const core::SceneObject* o, double diag);
  double draw_strength_field(ToolContext& ctx, double diag, double r);
  void draw_falloff_combo();
  void draw_fold_free(double s);

  std::string object_;
  std::string followed_selection_;  // selection the combo last followed
  // Makes `name` the object to press: its own typed radius and strength (kept per object), else unset.
  void follow_object(const std::string& name);
  std::map<std::string, std::pair<double, double>> typed_;  // per object: radius, strength when it was left
  // The next press's line: radius and strength ≤ 0 = unset (from the object's size, from the radius); object and
  // path are filled at mouse-up, the strength's sign by Ctrl.
  core::LatticePressParams params_{{}, {}, 0.0, 0.0, "smooth", false};
  ui::SizeFieldState radius_state_, strength_state_;  // as typed, and why limited
  // Keep fold-free during a drag: the strength the preview could use (negative: the whole strength; NaN: the lattice
  // is not certified before the press, so the command will refuse).
  double preview_strength_ = -1.0;
  std::string preview_refusal_;  // why the command will refuse the press being dragged (preview_strength_ NaN)

  std::optional<glm::dvec3> hover_;
  double hover_radius_ = 0.0;  // radius at the last hover (decorate has no context)
  std::vector<glm::dvec3> path_;
  bool pressing_ = false, pull_ = false;

  // Live preview (live_preview()): the binding shown, what it was made from, and for how many samples.
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> preview_;
  std::shared_ptr<const core::FfdBinding> preview_base_;
  std::size_t preview_samples_ = 0;
  int preview_linger_ = 0;  // frames left to show the preview after mouse-up while the command runs

  // Bounding-box diagonal of `o`'s world_mesh (0 without one), cached per mesh: it is an O(#V) pass and the default
  // radius needs it at every mouse move and every panel frame (6 ms per call on a 1 M-vertex mesh).
  double diagonal(const core::SceneObject& o) const;
  mutable std::weak_ptr<const core::TriMesh> diagonal_mesh_;  // weak: an expired mesh is never mistaken for a new one
  mutable double diagonal_ = 0.0;

  // Ray caster over the target's world_mesh, rebuilt when that pointer changes (held, so it cannot be reused).
  std::shared_ptr<const core::TriMesh> caster_mesh_;
  std::unique_ptr<core::RayCaster> caster_;
  std::shared_ptr<const core::TriMesh> pending_mesh_;  // mesh whose BVH is building on a worker thread
  std::future<std::unique_ptr<core::RayCaster>> pending_;
};

}  // namespace trispline::editor
