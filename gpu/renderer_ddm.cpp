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

namespace {

// The object deforms its tiles (some layer is not drawn with the transform alone).
bool follows(const core::SceneObject& o) {
  if (o.ffd || o.dffd || o.clip || o.morph) return true;
  for (const auto& l : o.ddm_layers)
    if (l && l->host_mesh && l->host_mesh != o.rest_mesh) return true;
  return false;
}

}  // namespace

const FfdLatticeBuffers& DdmDisplay::lattice_buffers(const core::DdmLayerDeformation& d) {
  LatticeGl& g = lattices_[d.lattice()];
  if (!g.buffers) {
    g.owner = d.lattice_owner();
    g.buffers = std::make_unique<FfdLatticeBuffers>();
    g.buffers->upload(core::FfdPackedLattice::build(*d.lattice(), d.embedding()));
  }
  return *g.buffers;
}

template <class Setup>
DdmDrawn DdmDisplay::draw_object(const core::SceneObject& o, double time_s, const ShaderDefines& variant,
                                 const Setup& setup) {
  DdmDrawn drawn;
  const bool follow = follows(o);
  const glm::dmat4 model = o.transform.matrix();
  const ShaderProgram* current = nullptr;
  const auto use = [&](const ShaderDefines& defines) -> const ShaderProgram& {
    const ShaderProgram& p = gl_.program(defines);
    if (&p != current) p.use(), setup(p), current = &p;
    return p;
  };
  for (const auto& layer : o.ddm_layers) {
    if (!has_instances(layer)) continue;
    const DdmPose pose = DdmPose::at(*layer, time_s);
    if (follow) {
      const core::DdmLayerDeformation d(o, *layer, time_s);
      if (!d.rigid()) {
        ShaderDefines defines = variant;
        defines.push_back({"FOLLOW", ""});
        if (d.lattice()) defines.push_back({"FFD", ""});
        const ShaderProgram& p = use(defines);
        setup.layer(p, *layer);
        const DdmFollow f{&d, d.lattice() ? &lattice_buffers(d) : nullptr};
        drawn.vertices += gl_.draw(layer, pose, model, p, &f);
        ++drawn.layers;
        continue;
      }
    }
    const ShaderProgram& p = use(variant);
    setup.layer(p, *layer);
    drawn.vertices += gl_.draw(layer, pose, model, p);
    ++drawn.layers;
  }
  return drawn;
}

namespace {
// The pass uniforms of a program (set once per program and object) and per layer.
struct ShadedSetup {
  glm::mat4 view_proj;
  glm::vec3 eye, key_dir, albedo;
  float highlight;
  void operator()(const ShaderProgram& p) const {
    p.set("u_view_proj", view_proj);
    p.set("u_eye", eye);
    p.set("u_key_dir", key_dir);
    p.set("u_flat_normal", 0);
    p.set("u_highlight", highlight);
  }
  void layer(const ShaderProgram& p, const core::DdmLayer& l) const { p.set("u_albedo", l.color.value_or(albedo)); }
};
struct FlatSetup {
  glm::mat4 view_proj;
  glm::vec4 color;
  glm::vec2 viewport{0.0f};
  float outline_px = 0.0f;
  bool outline = false;
  void operator()(const ShaderProgram& p) const {
    p.set("u_view_proj", view_proj);
    p.set("u_flat_color", color);
    if (outline) p.set("u_viewport", viewport), p.set("u_outline_px", outline_px);
  }
  void layer(const ShaderProgram&, const core::DdmLayer&) const {}
};
}  // namespace

DdmDrawn DdmDisplay::draw_shaded(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                                 const glm::vec3& eye, const glm::vec3& key_dir, const std::string& selected) {
  DdmDrawn drawn;
  if (!any_visible(scene)) return drawn;
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible || o.ddm_layers.empty()) continue;
    const bool is_selected = !selected.empty() && o.name == selected;
    glStencilFunc(GL_ALWAYS, is_selected ? 1 : 0, 0xFF);
    const DdmDrawn d =
        draw_object(o, time_s, {}, ShadedSetup{view_proj, eye, key_dir, o.color, is_selected ? 1.0f : 0.0f});
    drawn.layers += d.layers;
    drawn.vertices += d.vertices;
  }
  return drawn;
}

void DdmDisplay::draw_flat(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                           const glm::vec4& color) {
  if (!any_visible(scene)) return;
  for (const core::SceneObject& o : scene.objects())
    if (o.visible) draw_object(o, time_s, {{"FLAT_COLOR", ""}}, FlatSetup{view_proj, color});
}

void DdmDisplay::draw_outline(const core::SceneObject& object, double time_s, const glm::mat4& view_proj,
                              const glm::vec2& viewport, float outline_px, const glm::vec4& color) {
  bool any = false;
  for (const auto& layer : object.ddm_layers) any = any || has_instances(layer);
  if (!object.visible || !any) return;
  draw_object(object, time_s, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}},
              FlatSetup{view_proj, color, viewport, outline_px, true});
}

void DdmDisplay::release_unused(const core::Scene& scene) {
  std::unordered_set<const core::DdmLayer*> live;
  for (const core::SceneObject& o : scene.objects())
    for (const auto& l : o.ddm_layers)
      if (l) live.insert(l.get());
  gl_.release_unused(live);
  std::unordered_set<const void*> lattices;
  for (const core::SceneObject& o : scene.objects()) {
    if (o.ffd) lattices.insert(&o.ffd->lattice);
    if (o.dffd) lattices.insert(&o.dffd->lattice);
  }
  std::erase_if(lattices_, [&](const auto& kv) { return !lattices.count(kv.first); });
}

}  // namespace trispline::gpu::detail
