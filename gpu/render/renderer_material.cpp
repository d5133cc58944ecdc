// The renderer's Material shading (ViewOptions::shading): one draw per material range of an object, BLEND ranges
// after the opaque scene sorted back to front, and the selection outline that keeps MASK cut-outs open.
#include <algorithm>

#include "gpu/render/renderer_impl.h"

namespace trispline::gpu {
namespace {

using detail::Frame;

// Uniforms of the default (Solid) mesh program.
struct SolidUniforms {
  const Frame& f;
  glm::vec3 albedo;
  int flat_normal;
  bool selected;
  void operator()(const ShaderProgram& p) const {
    p.set("u_view_proj", f.view_proj);
    p.set("u_eye", f.eye);
    p.set("u_key_dir", f.key);
    p.set("u_albedo", albedo);
    p.set("u_highlight", selected ? 1.0f : 0.0f);
    p.set("u_flat_normal", flat_normal);
  }
};

}  // namespace

void Renderer::Impl::draw_material_range(const Frame& f, std::size_t i,
                                         const std::shared_ptr<const core::TriMesh>& shown, const core::Material& m,
                                         const core::MaterialSet& set, TriangleRange range, bool selected,
                                         int flat_normal) {
  if (m.double_sided) {
    glDisable(GL_CULL_FACE);
  } else {  // glTF 2.0 §3.9.6: back faces of single-sided materials are not drawn
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  }
  textures.bind(m, set);
  material.use();
  draw_object(
      shown, f.plans[i], material, {{"MATERIAL", ""}},
      [&](const ShaderProgram& p) {
        p.set("u_view_proj", f.view_proj);
        p.set("u_eye", f.eye);
        p.set("u_key_dir", f.key);
        p.set("u_highlight", selected ? 1.0f : 0.0f);
        p.set("u_flat_normal", flat_normal);
        MaterialTextures::set_uniforms(m, p);
      },
      range);
  glDisable(GL_CULL_FACE);
}

void Renderer::Impl::draw_materials(const Frame& f, const core::SceneObject& o, std::size_t i,
                                    const std::shared_ptr<const core::TriMesh>& shown, bool selected) {
  const detail::CachedMesh& c = cached(shown);
  static const core::MaterialSet kNone;
  const core::MaterialSet& set = o.materials ? *o.materials : kNone;
  const std::shared_ptr<const core::MaterialSet> inside = core::inside_material(o);
  for (const MaterialRange& r : c.buffers.material_ranges()) {
    if (r.slot == core::kMaterialInside && inside && o.inside_textured()) {  // caps with uvs of their own
      draw_material_range(f, i, shown, inside->materials[0], *inside, r.range, selected, 1);
      continue;
    }
    if (r.slot == core::kMaterialInside || r.slot >= set.materials.size()) {
      // Cut surfaces flat in the inside colour; a slot without a material in the object's colour.
      const bool inside = r.slot == core::kMaterialInside;
      mesh.use();
      draw_object(shown, f.plans[i], mesh, {},
                  SolidUniforms{f, inside ? o.inside_color : o.color, inside ? 1 : 0, selected}, r.range);
      continue;
    }
    const core::Material& m = set.materials[r.slot];
    if (m.alpha_mode == core::AlphaMode::Blend) {
      blended.push_back({i, r, glm::length(c.center - f.eye)});
      continue;
    }
    draw_material_range(f, i, shown, m, set, r.range, selected);
  }
  mesh.use();
}

void Renderer::Impl::pass_blended(const Frame& f, const detail::SelectedObject& sel) {
  if (blended.empty()) return;
  // Back to front by object; an object's ranges in slot order.
  std::stable_sort(blended.begin(), blended.end(), [](const detail::BlendedRange& a, const detail::BlendedRange& b) {
    return a.distance > b.distance;
  });
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  // The selected object's translucent pixels join its stencil mask (no outline drawn over them); others keep it.
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 1, 0xFF);
  const std::vector<core::SceneObject>& objects = f.scene.objects();
  for (const detail::BlendedRange& b : blended) {
    const core::SceneObject& o = objects[b.object];
    const bool selected = sel.object == &o;
    glStencilOp(GL_KEEP, GL_KEEP, selected ? GL_REPLACE : GL_KEEP);
    draw_material_range(f, b.object, detail::shown_mesh(o, f.options), o.materials->materials[b.range.slot],
                        *o.materials, b.range.range, selected);
  }
  textures.unbind();
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
}

void Renderer::Impl::draw_outline(const Frame& f, const core::SceneObject& o, std::size_t i) {
  const std::shared_ptr<const core::TriMesh>& shown = detail::shown_mesh(o, f.options);
  const auto common = [&](const ShaderProgram& p) {
    p.set("u_view_proj", f.view_proj);
    p.set("u_viewport", glm::vec2(f.vp));
    p.set("u_outline_px", f.options.style.outline_px);
    p.set("u_flat_color", detail::rgba(f.options.style.selection_color));
    p.set("u_outline_center", cached(shown).center);
  };
  const ShaderDefines plain{{"OUTLINE", ""}, {"FLAT_COLOR", ""}};
  if (!f.material || !o.materials || o.materials->empty()) {  // no MASK range to cut out
    outline.use();
    draw_object(shown, f.plans[i], outline, plain, common);
    return;
  }
  // Per material range: MASK ranges discard their cut-out texels so holes stay open; the rest as usual.
  const MeshBuffers& b = buffers(shown);
  for (const MaterialRange& r : b.material_ranges()) {
    const core::Material* m = r.slot < o.materials->materials.size() ? &o.materials->materials[r.slot] : nullptr;
    if (m && m->alpha_mode == core::AlphaMode::Mask) {
      textures.bind(*m, *o.materials);
      outline_mask.use();
      draw_object(
          shown, f.plans[i], outline_mask, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}, {"MATERIAL", ""}, {"ALPHA_MASK", ""}},
          [&](const ShaderProgram& p) {
            common(p);
            p.set("u_base_tex", 0);
            p.set("u_base_alpha", float(m->base_color.w));
            p.set("u_alpha_cutoff", float(m->alpha_cutoff));
          },
          r.range);
    } else {
      outline.use();
      draw_object(shown, f.plans[i], outline, plain, common, r.range);
    }
  }
  textures.unbind();
}

}  // namespace trispline::gpu
