// The renderer's DDM layer passes (shaded, wireframe, outline). See renderer_ddm.h.
#include "gpu/render/renderer_ddm.h"

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

namespace {

// Binds material `slot` of `set` for the MATERIAL variant: blending for BLEND, its textures and uniforms. No face
// culling, whatever double_sided says: the GPU draws every copy with its tile's winding, and a copy on a mirrored
// chart (det J < 0: a uv base whose S_u × S_v points against N) is wound the other way round.
void bind_tile_material(MaterialTextures& textures, const core::MaterialSet& set, core::MaterialSlot slot,
                        const ShaderProgram& p) {
  static const core::Material fallback;  // a slot without a material: the glTF default material
  const core::Material& m = slot < set.materials.size() ? set.materials[slot] : fallback;
  glDisable(GL_CULL_FACE);
  if (m.alpha_mode == core::AlphaMode::Blend) {
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  } else {
    glDisable(GL_BLEND);
  }
  textures.bind(m, set);
  p.use();
  MaterialTextures::set_uniforms(m, p);
}

}  // namespace

template <class Setup>
DdmDrawn DdmDisplay::draw_object(const core::SceneObject& o, double time_s, const ShaderDefines& variant,
                                 const Setup& setup, MaterialTextures* textures) {
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
    const glm::dvec3 colour(layer->color.value_or(o.color));  // of the plain tiles among texture-mapped ones
    const std::shared_ptr<const core::MaterialSet> set = textures ? gl_.materials(layer, colour) : nullptr;
    ShaderDefines defines = variant;
    if (set) defines.push_back({"MATERIAL", ""});
    const ShaderProgram* program = nullptr;
    const DdmMaterialBinder binder = [&](core::MaterialSlot slot) {
      bind_tile_material(*textures, *set, slot, *program);
    };
    const DdmMaterialBinder* bind = set ? &binder : nullptr;
    if (follow) {
      const core::DdmLayerDeformation d(o, *layer, time_s);
      if (!d.rigid()) {
        defines.push_back({"FOLLOW", ""});
        if (d.lattice()) defines.push_back({"FFD", ""});
        program = &use(defines);
        setup.layer(*program, *layer);
        const DdmFollow f{&d, d.lattice() ? &lattice_buffers(d) : nullptr};
        drawn.vertices += gl_.draw(layer, pose, model, *program, &f, nullptr, bind);
        ++drawn.layers;
        ++drawn.following;
        if (set) glDisable(GL_CULL_FACE), glDisable(GL_BLEND), textures->unbind();
        continue;
      }
    }
    program = &use(defines);
    setup.layer(*program, *layer);
    drawn.vertices += gl_.draw(layer, pose, model, *program, nullptr, selection(layer.get()), bind);
    ++drawn.layers;
    if (set) glDisable(GL_CULL_FACE), glDisable(GL_BLEND), textures->unbind();
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
  glm::vec3 outline_center{0.0f};  // world units
  void operator()(const ShaderProgram& p) const {
    p.set("u_view_proj", view_proj);
    p.set("u_flat_color", color);
    if (outline)
      p.set("u_viewport", viewport), p.set("u_outline_px", outline_px), p.set("u_outline_center", outline_center);
  }
  void layer(const ShaderProgram&, const core::DdmLayer&) const {}
};
}  // namespace

DdmDrawn DdmDisplay::draw_shaded(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                                 const glm::vec3& eye, const glm::vec3& key_dir, const std::string& selected,
                                 const DdmViewOptions& view, MaterialTextures* textures) {
  DdmDrawn drawn;
  ++frame_;
  if (!any_visible(scene)) return drawn;
  const bool thin = view.moving && view.motion_budget_vertices > 0;
  if (view.cull || thin) {
    // 1. Cull: per layer the instances in the view (objects without a deformation), and the vertices they make.
    std::size_t kept_vertices = 0;
    std::vector<std::pair<const core::SceneObject*, LayerView*>> chosen;
    for (const core::SceneObject& o : scene.objects()) {
      if (!o.visible) continue;
      const bool deformed = follows(o);  // drawn where the layer's own mesh is not: never culled
      for (const auto& layer : o.ddm_layers) {
        if (!has_instances(layer)) continue;
        LayerView& v = views_[layer.get()];
        v.layer = layer;
        if (view.cull && !deformed && !v.bounded) v.bounds = ddm_instance_bounds(*layer), v.bounded = true;
        chosen.push_back({&o, &v});
        drawn.instances += layer->instances.size();
      }
    }
    // 2. Thin: the power-of-two share of the kept vertices that fits the motion budget.
    const auto cull_view = [&](const core::SceneObject& o, const LayerView& v, double keep) {
      DdmCullView cv;
      cv.view_proj = glm::dmat4(view_proj);
      cv.model = o.transform.matrix();
      cv.eye = glm::dvec3(eye);
      cv.frustum = view.cull && !v.bounds.empty();
      cv.backface_margin_deg = cv.frustum ? view.backface_margin_deg : -1.0;
      cv.keep = keep;
      cv.pixels_per_unit = cv.frustum ? view.pixels_per_unit : 0.0;
      return cv;
    };
    const auto choose = [&](const core::SceneObject& o, LayerView& v, double keep) {
      const DdmCullView cv = cull_view(o, v, keep);
      const bool cull = cv.frustum;
      if (v.key_view_proj == cv.view_proj && v.key_model == cv.model && v.key_keep == keep && v.key_cull == cull &&
          v.key_margin == cv.backface_margin_deg && v.key_pixels == cv.pixels_per_unit &&
          v.selection.drawn.size() == v.layer->instances.size()) {
        v.frame = frame_;
        return;
      }
      const core::DdmLayer& l = *v.layer;
      std::vector<std::uint8_t> flags(l.instances.size(), 1);
      std::size_t culled = 0;
      if (cull || keep < 1.0) {
        static const DdmInstanceBounds none;
        const DdmCuller culler(cull ? v.bounds : none, cv);
        for (std::size_t k = 0; k < flags.size(); ++k) {
          const DdmCullReason r =
              cull ? culler.test(k) : (ddm_lod_rank(k) < keep ? DdmCullReason::kept : DdmCullReason::thinned);
          flags[k] = r == DdmCullReason::kept ? std::uint8_t(1 + (cull ? culler.level(k) : 0)) : 0;
          culled += r == DdmCullReason::outside || r == DdmCullReason::facing_away;
        }
      }
      if (flags != v.selection.drawn) v.selection.drawn = std::move(flags), v.selection.version = ++versions_;
      v.culled = culled;
      v.key_view_proj = cv.view_proj, v.key_model = cv.model, v.key_keep = keep, v.key_cull = cull;
      v.key_margin = cv.backface_margin_deg, v.key_pixels = cv.pixels_per_unit;
      v.frame = frame_;
    };
    for (auto& [o, v] : chosen) {
      choose(*o, *v, 1.0);
      for (std::size_t k = 0; k < v->selection.drawn.size(); ++k)
        if (const int f = v->selection.drawn[k])  // level f − 1 draws about 1/4^(f − 1) of the tile's vertices
          kept_vertices +=
              v->layer->tiles[std::size_t(v->layer->instances[k].tile)].mesh.vertex_count() >> (2 * (f - 1));
    }
    if (thin)
      while (drawn.keep > 1.0 / 256.0 && double(kept_vertices) * drawn.keep > double(view.motion_budget_vertices))
        drawn.keep *= 0.5;
    if (drawn.keep < 1.0)
      for (auto& [o, v] : chosen) choose(*o, *v, drawn.keep);
    for (auto& [o, v] : chosen) {
      drawn.instances_culled += v->culled;
      for (std::uint8_t f : v->selection.drawn) drawn.instances_drawn += f != 0;
    }
  }
  for (const core::SceneObject& o : scene.objects()) {
    if (!o.visible || o.ddm_layers.empty()) continue;
    const bool is_selected = !selected.empty() && o.name == selected;
    glStencilFunc(GL_ALWAYS, is_selected ? 1 : 0, 0xFF);
    const DdmDrawn d =
        draw_object(o, time_s, {}, ShadedSetup{view_proj, eye, key_dir, o.color, is_selected ? 1.0f : 0.0f}, textures);
    drawn.layers += d.layers;
    drawn.following += d.following;
    drawn.vertices += d.vertices;
  }
  if (!view.cull && !thin) {
    for (const core::SceneObject& o : scene.objects())
      if (o.visible)
        for (const auto& layer : o.ddm_layers)
          if (has_instances(layer)) drawn.instances += layer->instances.size();
    drawn.instances_drawn = drawn.instances;
  }
  return drawn;
}

const DdmSelection* DdmDisplay::selection(const core::DdmLayer* layer) const {
  const auto it = views_.find(layer);
  return it != views_.end() && it->second.frame == frame_ ? &it->second.selection : nullptr;
}

void DdmDisplay::draw_flat(const core::Scene& scene, double time_s, const glm::mat4& view_proj,
                           const glm::vec4& color) {
  if (!any_visible(scene)) return;
  for (const core::SceneObject& o : scene.objects())
    if (o.visible) draw_object(o, time_s, {{"FLAT_COLOR", ""}}, FlatSetup{view_proj, color});
}

void DdmDisplay::draw_outline(const core::SceneObject& object, double time_s, const glm::mat4& view_proj,
                              const glm::vec2& viewport, float outline_px, const glm::vec4& color,
                              const glm::vec3& center) {
  bool any = false;
  for (const auto& layer : object.ddm_layers) any = any || has_instances(layer);
  if (!object.visible || !any) return;
  draw_object(object, time_s, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}},
              FlatSetup{view_proj, color, viewport, outline_px, true, center});
}

void DdmDisplay::release_unused(const core::Scene& scene) {
  std::unordered_set<const core::DdmLayer*> live;
  for (const core::SceneObject& o : scene.objects())
    for (const auto& l : o.ddm_layers)
      if (l) live.insert(l.get());
  gl_.release_unused(live);
  std::erase_if(views_, [&](const auto& kv) { return !live.count(kv.first); });
  std::unordered_set<const void*> lattices;
  for (const core::SceneObject& o : scene.objects()) {
    if (o.ffd) lattices.insert(&o.ffd->lattice);
    if (o.dffd) lattices.insert(&o.dffd->lattice);
  }
  std::erase_if(lattices_, [&](const auto& kv) { return !lattices.count(kv.first); });
}

}  // namespace trispline::gpu::detail
