// trispline::gpu::DdmGl — live DDM layers on the GPU (seed §5.3.2): the base surface's P/N maps in
// an SSBO, each tile stored once, and ONE instanced draw per tile mesh whose vertex shader (shaders/ddm.vert.glsl)
// places every instance's copy: T(u,v,w) = P + N·w·height with normals through the cofactor of T's Jacobian, the
// metamorphosis of seed Eq. 5.3 and the texture-space offset of §5.4.2. It computes what core::ddm_layer_mesh
// computes (the CPU reference over core::DdmMapsBase), in float: tests hold positions to 1e-5 × maps.base_size and
// normals to 1e-4.
//
//   DdmPose             α, texture-space offset, tile transform and height of a layer at a scene time
//   DdmGl::draw         draws a layer with a program from program() (shaded / FLAT_COLOR / OUTLINE variants)
//   DdmGl::capture      the same vertex shader with transform feedback: positions and normals in object space
//   DdmGl::release_unused  forgets GPU copies of layers and maps no longer shown
//
// GPU resources: the maps are uploaded once per core::DdmMaps pointer (SSBO binding 6, std430 float[], 18 floats per
// sample as DdmMaps::samples); per layer pointer one instance buffer (chart slot, origin, size; grouped by tile) and
// each tile's positions / normals (+ its morph partner's) and indices (grouped by material slot for texture-mapped
// tiles, seed Fig. 5.12, with their uvs). Layers and maps are immutable and shared, so
// a pointer names its contents; the cache holds the shared_ptr, so an address cannot be reused while cached.
// All calls need the creating context (or one sharing with it) current; GL failures throw GlError.
#pragma once

#include <epoxy/gl.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/ddm/ddm_layer.h"
#include "core/scene/ddm_follow.h"
#include "gpu/eval/ffd_gl.h"
#include "gpu/eval/ffd_gl_lattice.h"
#include "gpu/gl/gl_resource.h"
#include "gpu/gl/shader_program.h"

namespace trispline::gpu {

// What changes with time in a layer (seed §5.4.2): metamorphosis weight α (0 without morph tiles; any real), the
// texture-space offset (chart parameter units), the tile transform (rotation, scale) and the height (w).
struct DdmPose {
  double alpha = 0.0;
  glm::dvec2 offset{0.0};
  core::DdmTileTransform transform;
  double height = 0.1;  // world units per tile unit of w
  double time_s = 0.0;  // scene time, seconds: an articulated tile's pose (core::DdmLayer::tile_clip)
  // layer.alpha_at(t) (0 when the layer has no morph tiles), offset_at(t), transform_at(t), height_at(t) and t.
  static DdmPose at(const core::DdmLayer& layer, double time_s);
};

// Positions and normals of every instance's vertices, instances one after another in layer.instances order, each in
// its tile's vertex order (the order of core::ddm_evaluate and ddm.bake). Object units; unit normals.
// How a layer follows its object's deformation (core::DdmLayerDeformation, in float): the host maps and parameter
// boxes per instance and, with a lattice, its buffers (uploaded by the caller from the deformation's lattice and
// embedding). Draw with program({{"FOLLOW", ""}}) or, with a lattice, program({{"FOLLOW", ""}, {"FFD", ""}}).
struct DdmFollow {
  const core::DdmLayerDeformation* deformation = nullptr;  // non-null
  const FfdLatticeBuffers* lattice = nullptr;              // non-null iff deformation->lattice()
};

struct DdmCapture {
  std::vector<glm::vec3> positions;  // #V × 3, #V = Σ over instances of the tile's vertex count
  std::vector<glm::vec3> normals;    // #V × 3
};

// Levels of detail of a tile mesh (the editor's screen-size LOD, gpu/view/ddm_cull.h): level 0 is the tile itself,
// level k ≥ 1 a decimated copy with about 1/4^k of its vertices (core::decimated_triangles; at least
// kDdmLodMinVertices), drawn with the same vertex buffers. Texture-mapped tiles have level 0 only.
inline constexpr int kDdmLodLevels = 3;
inline constexpr std::size_t kDdmLodMinVertices = 12;

// Which of a layer's instances DdmGl::draw draws, and at which level of detail (the editor's culling, motion LOD and
// screen-size LOD, gpu/view/ddm_cull.h): per instance in the layer's instance order (#I) 0 = not drawn, 1 + k = drawn
// at level k (k < kDdmLodLevels; a tile without level k draws its coarsest), and a version that names the flags (the
// same version again = the same flags: the compacted instance buffer is uploaded once per version, then shared by
// every pass).
struct DdmSelection {
  std::vector<std::uint8_t> drawn;
  std::uint64_t version = 0;
};

// Called before each run of a texture-mapped layer's triangles that share a material (core::ddm_tile_materials'
// slot, or core::kMaterialInside) with the program in use: binds that material's textures and sets its uniforms.
using DdmMaterialBinder = std::function<void(core::MaterialSlot slot)>;

class DdmGl {
 public:
  // `programs`: where compiled programs are kept (shared with the renderer's FFD programs); null = a private cache.
  // Needs a current context; programs are compiled at first use (ShaderError then).
  explicit DdmGl(std::shared_ptr<FfdProgramCache> programs = nullptr);
  ~DdmGl();
  DdmGl(const DdmGl&) = delete;
  DdmGl& operator=(const DdmGl&) = delete;

  // The drawing program: ddm.vert.glsl + mesh.frag.glsl specialised with `variant` (e.g. {} shaded, {{"FLAT_COLOR",
  // ""}}, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}}). Set the fragment uniforms and u_view_proj (and OUTLINE's) on it;
  // draw() sets the rest.
  const ShaderProgram& program(const ShaderDefines& variant);

  // Draws every instance of `layer` at `pose`, one glDrawElementsInstancedBaseInstance per tile, with `program` (in
  // use, from program()) and object → world matrix `model` (normals by its inverse transpose). Uploads what is not
  // cached yet. Returns the vertices drawn (Σ instances × tile vertices). A layer without instances draws nothing.
  // Throws std::invalid_argument (see check below), GlError.
  // With `follow`, the FOLLOW (+ FFD) variant: `model` is ignored (the deformation's model() is used) and the
  // per-instance host maps / parameter boxes are uploaded when they changed; `selection` is then ignored (every
  // instance is drawn). With `selection` (#I flags) only the flagged instances: their instance records compacted into
  // a second buffer read through the same attributes (the vertex shader is the same), the vertices returned are theirs.
  // With `bind_material` and a layer whose tiles carry materials (materials() not null), each tile is drawn in runs
  // of one material slot, `bind_material` called before each (the MATERIAL variant reads the tile's uvs,
  // attribute 13); otherwise one draw per tile as above.
  std::size_t draw(const std::shared_ptr<const core::DdmLayer>& layer, const DdmPose& pose, const glm::dmat4& model,
                   const ShaderProgram& program, const DdmFollow* follow = nullptr,
                   const DdmSelection* selection = nullptr, const DdmMaterialBinder* bind_material = nullptr);
  // The layer's tile materials as one set (core::ddm_tile_materials, tiles without materials in `untextured_color`,
  // linear RGB: the layer's colour), null for untextured tiles. Uploads the layer when it is not cached yet (throws
  // as draw).
  std::shared_ptr<const core::MaterialSet> materials(const std::shared_ptr<const core::DdmLayer>& layer,
                                                     const glm::dvec3& untextured_color);

  // The same vertex shader with transform feedback and GL_RASTERIZER_DISCARD (a private 1×1 framebuffer when the
  // bound one is incomplete, as on surfaceless EGL): positions / normals in object space, in ddm_evaluate's order.
  // Waits for the GPU. Throws as draw, ShaderError.
  // With `follow`: world units through the deformation (the parity test of core::DdmLayerDeformation::apply).
  DdmCapture capture(const std::shared_ptr<const core::DdmLayer>& layer, const DdmPose& pose,
                     const DdmFollow* follow = nullptr);

  // Forgets layers not in `live` and maps no live layer uses.
  void release_unused(const std::unordered_set<const core::DdmLayer*>& live);
  std::size_t cached_layers() const;
  std::size_t cached_maps() const;
  int uploads() const { return uploads_; }  // layers and maps uploaded so far (tests: caching works)

  // Throws std::invalid_argument ("layer 'NAME': …") unless the layer can be drawn: maps present with resolution
  // ≥ 2 and 18 floats per sample of every slot, ≥ 1 tile, every tile with #normals = #V, morph tiles empty or one per
  // tile with the same vertex and triangle counts, every instance's tile in range and chart sampled (a slot), height
  // finite and > 0.
  static void check(const core::DdmLayer& layer);

 private:
  struct MapsGl;
  struct LayerGl;
  MapsGl& maps_for(const std::shared_ptr<const core::DdmMaps>& maps);
  LayerGl& layer_for(const std::shared_ptr<const core::DdmLayer>& layer);
  void select(LayerGl& g, const DdmSelection& selection);  // uploads the compacted instances of a new version
  // The coarser levels of g's untextured tiles, made and uploaded (after each tile's full index list) the first time
  // a selection asks for them: replays and recordings, which draw whole layers, never pay for the decimation.
  void ensure_levels(LayerGl& g);
  void set_uniforms(const ShaderProgram& p, const core::DdmLayer& layer, const DdmPose& pose,
                    const glm::dmat4& model) const;
  // Uploads the follow records (grouped order) when changed, points attributes 7–12 at them, sets the FFD uniforms
  // and binds the lattice.
  void bind_follow(LayerGl& g, const ShaderProgram& p, const DdmFollow& follow);
  // An articulated tile's buffers posed at `time_s` (core::DdmTileClip::pose), when they are not already.
  static void pose_tiles(LayerGl& g, const core::DdmLayer& layer, double time_s);

  std::shared_ptr<FfdProgramCache> programs_;
  std::unordered_map<const core::DdmMaps*, std::unique_ptr<MapsGl>> maps_;
  std::unordered_map<const core::DdmLayer*, std::unique_ptr<LayerGl>> layers_;
  Framebuffer fallback_fbo_;
  Renderbuffer fallback_rb_;
  Buffer capture_positions_, capture_normals_;
  std::size_t capture_capacity_ = 0;  // vertices the capture buffers hold
  int uploads_ = 0;
};

}  // namespace trispline::gpu
