// trispline::core::MeshClip — a glTF animation clip played on a mesh in its own (flat, rest) space: morph-target
// weights, linear-blend skinning and node transforms, evaluated at a clip time. The first level of the seed's
// two-level animation (§2.4.3): the clip animates the object in the rest domain, the FFD then warps every frame onto
// the terrain.
//
// The clip's mesh is exactly the mesh load_mesh(path) returns for the same file (same vertices, same order, same
// node transforms baked in), and its rest state — every node at its file TRS, morph weights at their defaults — IS
// that mesh (load() checks it to 1e-9 × size). Because load_mesh bakes each mesh node's transform X and ignores
// skins and default weights, the clip is made relative to that rest state:
//   morph   p = base + Σ_k (w_k(t) − default_k) · Δ_k                         (glTF 2.0 §3.7.2.2)
//   skin    p = X · B_rest⁻¹ · B(t) · p_morph,  B(t) = Σ_j weight_j · G_t(joint_j) · IBM_j   (§3.7.3)
//   other   p = G_t(node) · p_morph                                           (animated node hierarchy, §3.5.3)
// When the rest pose is the bind pose (B_rest = I) and X = I this is exactly the spec; otherwise the spec's motion
// expressed in load_mesh's frame. As the spec says, the skinned mesh node's own (animated) transform does not move
// the skin. Normals: the file's NORMAL (plus morph NORMAL deltas) through the inverse transpose of the same linear
// map, renormalised; when load_mesh computed them instead, area-weighted normals of the posed triangles.
// Samplers (§3.11, Appendix C): STEP, LINEAR (slerp for rotations; keys normalised), CUBICSPLINE (Hermite); all
// accessor component types, normalised integers and sparse accessors (base POSITION/NORMAL as load_mesh: no sparse).
// Not supported: KHR_animation_pointer and other extensions (such channels are ignored), TANGENT morphing, nodes with
// a `matrix` that are animated (invalid glTF: load throws). Evaluation is deterministic (fixed operation order, no
// threads, double precision); pose() is const and safe to call from several threads.
// Source: glTF 2.0 specification §3.5 (nodes), §3.6.2 (accessors), §3.7 (meshes, morph targets, skins), §3.11.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace trispline::core {

// MeshClip::load's name for every animation of a file played together.
inline constexpr const char* kAllClips = "*";

class MeshClip {
 public:
  // Names of the animations in a .gltf/.glb, in file order ("" for an unnamed one shows as "animation_<i>").
  // Throws MeshIoError on a missing or unparseable file.
  static std::vector<std::string> list(const std::filesystem::path& path);

  // Loads animation `clip` of the file: its name (or "animation_<i>"), or "#<i>" for the i-th, or "" for the first, or
  // kAllClips ("*") for all of them played together (files that keep one animation per joint); where two animate the
  // same node property, the later one's channel wins.
  // The animation must drive a morph-weight channel of a mesh node that load_mesh(path) includes, or the transform
  // of such a node, of one of its ancestors, or of a joint (or a joint's ancestor) of its skin.
  // Throws MeshIoError (missing/unparseable file, bad accessors or hierarchy, what load_mesh throws) or
  // std::invalid_argument (no animation, unknown clip — the message lists the clips —, clip animates no mesh, empty
  // sampler, non-finite or decreasing keys, wrong output count, singular rest skin) with a message that names the
  // file and the clip.
  static std::shared_ptr<const MeshClip> load(const std::filesystem::path& path, const std::string& clip = "");

  const std::string& name() const { return name_; }
  const std::filesystem::path& path() const { return path_; }
  double duration_s() const { return duration_s_; }  // last key time of any channel, seconds (≥ 0)
  std::size_t vertex_count() const { return rest_positions_.size(); }
  const std::vector<glm::dvec3>& rest_positions() const { return rest_positions_; }  // #V × 3, as load_mesh

  // Positions and unit normals (#V × 3, object space = load_mesh's space) at clip time `t_s` seconds. Times outside
  // [0, duration] are clamped (the caller wraps for looping: see wrap_clip_time). Normals are recomputed from the
  // posed triangles' area-weighted face normals when the file has none to morph/skin. Throws std::invalid_argument
  // on a non-finite t_s. Cost: O(#V · (#targets + #influences)) plus O(#nodes) per call.
  void pose(double t_s, std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) const;

  struct Impl;  // glTF data needed for evaluation (defined in mesh_clip.cpp)

 private:
  std::string name_;
  std::filesystem::path path_;
  double duration_s_ = 0;
  std::vector<glm::dvec3> rest_positions_;
  std::shared_ptr<const Impl> impl_;
};

// Clip time for scene time `time_s`: (time_s − start_s)·speed wrapped into [0, duration) when `loop`, else clamped
// to [0, duration]. A zero-length clip always gives 0.
double wrap_clip_time(double time_s, double start_s, double speed, double duration_s, bool loop);

}  // namespace trispline::core
