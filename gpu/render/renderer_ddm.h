// trispline::gpu::detail::DdmDisplay — how the Renderer shows live DDM layers (SceneObject::ddm_layers,
// seed §5.3.2): every visible object's layers through DdmGl's instanced path at ViewOptions::time_s (α =
// alpha_at(t), offset = offset_at(t)), in object space through the object's transform (Transform::matrix(); normals
// by its inverse transpose), shaded like the object (its colour, studio shading of mesh.frag.glsl), and in the
// wireframe overlay and the selection outline. GPU copies are cached per layer / maps pointer (DdmGl) and dropped
// in release_unused. With ViewOptions::ddm (the editor's view) the shaded pass first chooses each layer's instances
// (gpu/view/ddm_cull.h: culled on objects without FFD / DFFD / clip, then thinned to the motion budget while the view
// moves) and the wireframe and outline passes of the same frame draw the same ones. Layers of an object whose
// deformation carries them (core/scene/ddm_follow.h: FFD, DFFD, clip, morph, a moved host surface) are drawn with
// DdmGl's FOLLOW (+ FFD) variant: host maps per instance, the object's lattice at ViewOptions::time_s (its buffers
// cached per lattice), never culled. Internal to the renderer (renderer.cpp); not a public API.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <unordered_map>

#include "core/scene/scene.h"
#include "gpu/eval/ddm_gl.h"
#include "gpu/render/material_textures.h"
#include "gpu/view/ddm_cull.h"
#include "gpu/view/view_options.h"

namespace trispline::gpu::detail {

struct DdmDrawn {
  int layers = 0;            // layers drawn (with at least one instance)
  int following = 0;         // of those, drawn through their object's deformation (FOLLOW)
  std::size_t vertices = 0;  // Σ drawn instances × tile vertices
  std::size_t instances = 0, instances_drawn = 0, instances_culled = 0;  // see RenderStats
  double keep = 1.0;                                                     // the motion LOD's share
};

class DdmDisplay {
 public:
  explicit DdmDisplay(std::shared_ptr<FfdProgramCache> programs) : gl_(std::move(programs)) {}
  // True when some visible object has a layer with instances (the renderer then times the DDM pass on its own).
  static bool any_visible(const core::Scene& scene);
  // Shaded pass (inside the renderer's object pass: depth test on, stencil test on with GL_REPLACE): each visible
  // object's layers in its colour, writing stencil 1 for the object named `selected` (outline mask), 0 otherwise.
  // `view`: what to leave out (ViewOptions::ddm); `view_proj` is also the culling's. With `textures` (Material
  // shading) texture-mapped tiles are drawn with their own materials (MATERIAL variant, one draw per material run;
  // BLEND runs blended in place, not sorted), the others in their colour as in Solid shading.
  DdmDrawn draw_shaded(const core::Scene& scene, double time_s, const glm::mat4& view_proj, const glm::vec3& eye,
                       const glm::vec3& key_dir, const std::string& selected, const DdmViewOptions& view = {},
                       MaterialTextures* textures = nullptr);
  // Wireframe overlay pass (polygon mode GL_LINE set by the caller): every visible object's layers in `color`.
  void draw_flat(const core::Scene& scene, double time_s, const glm::mat4& view_proj, const glm::vec4& color);
  // Selection outline of `object`'s layers (the caller set stencil and depth state, as for the object's outline);
  // `center`: the object's centre, world units (outline.glsl pushes tiles seen face-on away from it).
  void draw_outline(const core::SceneObject& object, double time_s, const glm::mat4& view_proj,
                    const glm::vec2& viewport, float outline_px, const glm::vec4& color, const glm::vec3& center);
  void release_unused(const core::Scene& scene);
  DdmGl& gl() { return gl_; }

 private:
  // Per layer: its bounds (made at first need), the instances chosen for this frame and what they were chosen for.
  struct LayerView {
    std::shared_ptr<const core::DdmLayer> layer;  // held so the address cannot be reused
    bool bounded = false;                         // bounds computed (maybe empty: the layer is not culled)
    DdmInstanceBounds bounds;
    DdmSelection selection;
    std::size_t culled = 0;
    glm::dmat4 key_view_proj{0.0}, key_model{0.0};  // what `selection` was made for
    double key_keep = -1.0, key_margin = 0.0, key_pixels = -1.0;
    bool key_cull = false;
    std::uint64_t frame = 0;  // the frame it is valid for
  };
  // The instances to draw of `layer` this frame (null: all).
  const DdmSelection* selection(const core::DdmLayer* layer) const;

  // Draws `object`'s layers with `variant`'s programs (plus FOLLOW / FFD where they follow, else this frame's
  // selection); `setup` sets the program's pass uniforms whenever a program is first used. Returns what was drawn.
  // With `textures`, texture-mapped layers use the MATERIAL variant and their materials.
  template <class Setup>
  DdmDrawn draw_object(const core::SceneObject& object, double time_s, const ShaderDefines& variant, const Setup& setup,
                       MaterialTextures* textures = nullptr);
  const FfdLatticeBuffers& lattice_buffers(const core::DdmLayerDeformation& d);

  DdmGl gl_;
  struct LatticeGl {
    std::shared_ptr<const void> owner;  // the FfdBinding / DffdRig holding the lattice (address kept)
    std::unique_ptr<FfdLatticeBuffers> buffers;
  };
  std::unordered_map<const void*, LatticeGl> lattices_;  // by lattice address
  std::unordered_map<const core::DdmLayer*, LayerView> views_;
  std::uint64_t frame_ = 0, versions_ = 0;
};

}  // namespace trispline::gpu::detail
