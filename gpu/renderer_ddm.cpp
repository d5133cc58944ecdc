// The renderer's DDM layer passes (shaded, wireframe, outline). See renderer_ddm.h.
#include "gpu/renderer_ddm.h"

#include <unordered_set>

namespace trispline::gpu::detail {
namespace {

bool has_instances(const std::shared_ptr<const core::DdmLayer>& l) { return l && !l->instances.empty(); }

}  // namespace

bool DdmDisplay::any_visible(const core::Scene& scene) {
  for (const core::SceneObject& o : scene.objects())
    if (o.visible)
      for (const auto& l : o.ddm_layers)
        if (has_instances(l)) return true;
  return false;
}

DdmDrawn DdmDisplay::draw_shaded(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                                 const glm::vec3& eye, const glm::vec3& key_dir, const std::string& selected) {
  DdmDrawn drawn;
  if (!any_visible(scene)) return drawn;
  const ShaderProgram& p = gl_.program({});
  p.use();
  p.set("u_view_proj", view_proj);
  p.set("u_eye", eye);
  p.set("u_key_dir", key_dir);
  p.set("u_flat_normal", 0);
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible || o.ddm_layers.empty()) continue;
    const bool is_selected = !selected.empty() && o.name == selected;
    glStencilFunc(GL_ALWAYS, is_selected ? 1 : 0, 0xFF);
    p.set("u_highlight", is_selected ? 1.0f : 0.0f);
    const glm::dmat4 model = o.transform.matrix();
    for (const auto& layer : o.ddm_layers) {
      if (!has_instances(layer)) continue;
      p.set("u_albedo", layer->color.value_or(o.color));
      drawn.vertices += gl_.draw(layer, DdmPose::at(*layer, time_s), model, p);
      ++drawn.layers;
    }
  }
  return drawn;
}

void DdmDisplay::draw_flat(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                           const glm::vec4& color) {
  if (!any_visible(scene)) return;
  const ShaderProgram& p = gl_.program({{"FLAT_COLOR", ""}});
  p.use();
  p.set("u_view_proj", view_proj);
  p.set("u_flat_color", color);
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible) continue;
    for (const auto& layer : o.ddm_layers)
      if (has_instances(layer)) gl_.draw(layer, DdmPose::at(*layer, time_s), o.transform.matrix(), p);
  }
}

void DdmDisplay::draw_outline(const core::SceneObject& object, double time_s, const glm::mat4& view_proj,
                              const glm::vec2& viewport, float outline_px, const glm::vec4& color) {
  bool any = false;
  for (const auto& layer : object.ddm_layers) any = any || has_instances(layer);
  if (!object.visible || !any) return;
  const ShaderProgram& p = gl_.program({{"OUTLINE", ""}, {"FLAT_COLOR", ""}});
  p.use();
  p.set("u_view_proj", view_proj);
  p.set("u_viewport", viewport);
  p.set("u_outline_px", outline_px);
  p.set("u_flat_color", color);
  for (const auto& layer : object.ddm_layers)
    if (has_instances(layer)) gl_.draw(layer, DdmPose::at(*layer, time_s), object.transform.matrix(), p);
}

void DdmDisplay::release_unused(const core::Scene& scene) {
  std::unordered_set<const core::DdmLayer*> live;
  for (const core::SceneObject& o : scene.objects())
    for (const auto& l : o.ddm_layers)
      if (l) live.insert(l.get());
  gl_.release_unused(live);
}

}  // namespace trispline::gpu::detail
