// trispline::core::Scene — the document: named objects (rest mesh + transform + optional FFD) and the camera.
//
// Objects are value types whose meshes are shared immutable pointers, so a command can snapshot an object for
// undo at the cost of a few pointers, and build the new object completely before swapping it in (transaction).
// Object order is insertion order (it is the export order of scene.glb).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ddm/ddm_layer.h"
#include "core/dffd/dffd_rig.h"
#include "core/ffd/ffd.h"
#include "core/mesh/material.h"
#include "core/mesh/mesh_clip.h"
#include "core/mesh/tri_mesh.h"
#include "core/scene/camera.h"
#include "core/spline/keyframes.h"
#include "core/volume/silhouettes.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_dvr.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

// Scale, then rotation (degrees about x, then y, then z), then translation.
struct Transform {
  glm::dvec3 translate{0.0};   // world units
  glm::dvec3 rotate_deg{0.0};  // degrees
  glm::dvec3 scale{1.0};       // per axis, must be non-zero
  glm::dmat4 matrix() const;
  bool is_identity() const;
};

// Applies `t` to positions and (inverse-transpose) to normals; flips triangle winding if det < 0.
TriMesh transformed(const TriMesh& mesh, const Transform& t);

// Placement record kept with a placed object, for display (contact surface, stroke) and the report.
struct PlacementRecord {
  std::vector<glm::dvec2> stroke_px;       // #S × 2, viewport pixels
  int samples_u = 0, samples_v = 0;        // contact sampling grid (nu × nv)
  std::vector<glm::dvec3> contact_points;  // #(nu·nv) × 3 ray hits (filled where missed), u fastest
  std::vector<unsigned char> contact_hit;  // #(nu·nv): 1 = real hit, 0 = filled from neighbours
};

// The scene's timeline (Blender's Output ▸ Frame Range and Frame Rate): frames frame_start..frame_end inclusive at
// `fps` frames per second. Frame f is shown at scene time (f − frame_start)/fps seconds; scene time is the single
// clock every animation reads (offset keys and velocities, glTF clips), so recordings are exact per frame.
struct Timeline {
  double fps = 24;      // frames per second, in [0.01, 240]
  int frame_start = 1;  // first frame number (≥ 0)
  int frame_end = 120;  // last frame number, inclusive (≥ frame_start, ≤ 100000)
  double time_of_frame(double frame) const { return (frame - frame_start) / fps; }  // seconds
  double frame_of_time(double time_s) const { return frame_start + time_s * fps; }
  int frame_count() const { return frame_end - frame_start + 1; }
  double duration_s() const { return (frame_end - frame_start) / fps; }
  bool operator==(const Timeline& o) const {
    return fps == o.fps && frame_start == o.frame_start && frame_end == o.frame_end;
  }
};

// A glTF clip attached to an object (anim.clip): the object's rest mesh is posed by it at every scene time.
struct ClipBinding {
  std::shared_ptr<const MeshClip> clip;  // non-null
  double speed = 1.0;                    // clip seconds per scene second (> 0)
  double start_s = 0.0;                  // scene time at which the clip is at its time 0, seconds
  bool loop = true;                      // wrap (true) or hold the last pose (false)
  double clip_time(double time_s) const { return wrap_clip_time(time_s, start_s, speed, clip->duration_s(), loop); }
};

// A per-vertex morph channel of an object's rest mesh (an incision's opening keyed on the timeline, incision.animate):
// at weight s the surface is rest + (s − 1)·(rest − base): `base` at s = 0 (the cut closed), the rest mesh itself at
// s = 1 (bit for bit), extrapolated outside [0,1]. Normals interpolated the same way and renormalised.
struct MorphChannel {
  std::vector<glm::dvec3> base_positions;  // #V × 3, object space: the surface at weight 0
  std::vector<glm::dvec3> base_normals;    // #V × 3, unit (or empty: normals kept)
  std::vector<OffsetKey> weight_keys;      // sorted by time; the weight is .offset.x (evaluate_offset_keys); ≥ 1 key
  std::string what;                        // what it animates, for labels ("incision opening")
  double weight_at(double time_s) const { return evaluate_offset_keys(weight_keys, time_s).x; }
  bool animated() const { return weight_keys.size() >= 2; }
};

// The rest mesh morphed to weight `s` (MorphChannel). Throws std::invalid_argument: base not #V, non-finite s.
TriMesh morphed(const TriMesh& rest, const MorphChannel& morph, double s);

struct SceneObject;

// The material of an object's textured cut surfaces (SceneObject::inside_textured()): one material "<name>.inside"
// of base colour inside_color × inside_texture (sRGB), metallic 0, roughness 0.8, double sided, the texture
// repeating; null when the object has no readable inside texture (the cut surfaces are drawn in inside_color).
std::shared_ptr<const MaterialSet> inside_material(const SceneObject& o);

struct SceneObject {
  std::string name;                          // stable id used by commands
  std::string source;                        // file path or "primitive:<kind>"
  std::shared_ptr<const TriMesh> rest_mesh;  // object space, as loaded (with normals)
  Transform transform;
  glm::vec3 color{0.8f, 0.8f, 0.8f};            // linear RGB
  glm::vec3 inside_color{0.62f, 0.10f, 0.08f};  // linear RGB of kMaterialInside faces (caps, incision walls: "flesh")
  // The inside texture (object.inside; seed Fig. 6.9's wood-textured caps): DFFD caps get vertices of their own with
  // planar uvs in the discontinuity plane (CapTexturing), one repeat spanning inside_texture_size world units, and
  // are drawn in Material shading with this image × inside_color. Null: the inside colour alone. Incision walls
  // keep the inside colour (unless the object is also split: they share the inside slot).
  std::shared_ptr<const MaterialImage> inside_texture;
  double inside_texture_size = 0.25;  // world units per repeat of inside_texture on the caps, > 0
  // The file's materials, indexed by the meshes' face_material (null or empty: Solid colour only, as primitives).
  // Shared by every mesh derived from rest_mesh (FFD, DFFD, incisions, refinement keep face_material and uvs).
  std::shared_ptr<const MaterialSet> materials;
  // The file's nodes when it had several (rest_mesh holds them all, node transforms applied); empty otherwise.
  std::vector<MeshPart> parts;
  bool visible = true;                    // shown in the viewport (Blender's hide_viewport); object.visibility
  bool render_visible = true;             // in recordings, animation.glb, scene.glb and farm frames (hide_render)
  std::shared_ptr<const FfdBinding> ffd;  // null unless deformed; binding over the *transformed* rest mesh
  std::shared_ptr<const PlacementRecord> placement;  // null unless placed by place.sketch
  // Discontinuous FFD (dffd.split, seed §6.3): null unless split around obstacles; never together with `ffd`. The
  // mesh is split at the rig's breaks when evaluated (dffd_apply), so world_mesh has more vertices than rest_mesh
  // and the renderer draws world_mesh as it is (no GPU re-evaluation).
  std::shared_ptr<const DffdRig> dffd;
  // Tile layers over the object's surface (DDM, seed ch. 5; ddm.fill / ddm.paint), in the order they were made. Their
  // meshes are in object space, drawn with the object's transform.
  std::vector<std::shared_ptr<const DdmLayer>> ddm_layers;
  std::shared_ptr<const TriMesh>
      world_mesh;  // evaluated at scene time 0: ffd ? F(E(T(rest)) + offset_at(0)) : T(rest),
                   // rest posed by the clip at time 0 when there is one; see refresh()
  // Parameter offset added to every vertex's (u,v,w) before F is evaluated (seed §4.5 animation offset), parameter
  // units; on a periodic axis an offset of 1 is one full turn. Ignored without ffd.
  glm::dvec3 param_offset{0.0};
  // Rate of change of the offset during playback, parameter units per second: at scene time t the object shows
  // F(E(x) + param_offset + offset_velocity·t). world_mesh is the t = 0 pose; see scene_at_time().
  glm::dvec3 offset_velocity{0.0};
  // Keyframes of the offset (anim.keyframe), sorted by time. When there are any they replace param_offset.
  std::vector<OffsetKey> offset_keys;
  // glTF clip posing the rest mesh over time (anim.clip); null = none. rest_mesh is then the clip's rest pose.
  std::shared_ptr<const ClipBinding> clip;
  // Per-vertex morph of the rest mesh over time (incision.animate); null = none, never together with a clip.
  std::shared_ptr<const MorphChannel> morph;
  // (offset_keys.empty() ? param_offset : evaluate_offset_keys(offset_keys, time_s)) + offset_velocity·time_s.
  glm::dvec3 offset_at(double time_s) const {
    return (offset_keys.empty() ? param_offset : evaluate_offset_keys(offset_keys, time_s)) + offset_velocity * time_s;
  }
  // The FFD offset changes with time (velocity or ≥ 2 keys); the renderer can play it in the vertex shader.
  bool offset_animated() const { return ffd && (offset_velocity != glm::dvec3(0.0) || offset_keys.size() >= 2); }
  // The rest mesh itself changes with time (a clip or an animated morph): every frame needs a new pose (CPU) before
  // the FFD.
  bool clip_animated() const { return clip != nullptr || (morph && morph->animated()); }
  // A DFFD object whose offset or keyed seam changes with time: every frame is split and evaluated again on the CPU.
  bool dffd_animated() const {
    return dffd && (offset_velocity != glm::dvec3(0.0) || offset_keys.size() >= 2 || dffd->stitch_animated());
  }
  // The object must be re-evaluated on the CPU for each scene time (clip poses, DFFD splits).
  bool cpu_animated() const { return clip_animated() || dffd_animated(); }
  bool animated() const { return offset_animated() || clip_animated() || dffd_animated(); }
  // The cap texturing of `rig` for this object's inside texture (cap_texturing); untextured when there is none or it
  // is not readable.
  CapTexturing cap_texturing_of(const DffdRig& rig) const {
    return inside_texture && inside_texture->readable() ? cap_texturing(rig, inside_texture_size) : CapTexturing{};
  }
  // The kMaterialInside faces carry the inside texture's uvs (a DFFD object with a readable inside texture).
  bool inside_textured() const { return dffd && inside_texture && inside_texture->readable(); }

  // Recomputes world_mesh from rest_mesh, transform and ffd (or dffd). Throws std::invalid_argument on
  // inconsistency.
  void refresh();
  // Transformed rest mesh, world units (what an FFD embeds).
  TriMesh world_rest_mesh() const;
};

// How a volume's silhouettes are extracted and stroked (volume.silhouettes; seed §7.3.3–7.3.4).
struct VolumeSilhouetteSettings {
  bool enabled = false;           // extracted for the current view (live in the editor, at export and in replay)
  std::string style = "hue";      // hue (hue by |∇D|) | glyphs (short strokes ⊥ the projected gradient) |
                                  // fans (fans across the curve, opening and hue by |∇D|) |
                                  // width (stroke width and grey by |∇D|) | plain (black) |
                                  // chromadepth (hue by depth: red nearest, blue farthest)
  std::string hidden = "remove";  // remove | dashed | show: what is done with parts hidden by the iso-surface
  std::string projection = "perspective";  // perspective (G·(P − eye) = 0) | orthographic (G·forward = 0)
  SilhouetteParams params;                 // subdivision, accuracy (hidden_test follows `hidden`)
};

// A further iso-level of a volume (seed Figs. 7.4–7.6, 7.9, 7.12: skin and bone, or several grey levels, at once):
// its silhouettes, stroked in a style and colour of their own, for the volume's silhouette camera and its silhouette
// settings (hidden lines, projection, subdivision, accuracy). Only the volume's first level (VolumeObject::iso) is
// ray cast as a surface; each level's hidden parts are those behind its own iso-surface.
struct VolumeIsoLevel {
  double iso = 0.0;             // iso-level c of D = c, in the volume's units
  std::string style = "plain";  // as VolumeSilhouetteSettings::style
  glm::vec3 color{0.0f};        // sRGB in [0,1]³: plain strokes' colour, the width style's darkest
  std::shared_ptr<const SilhouetteResult> silhouettes;  // null until extracted, or when silhouettes are disabled
};
// The most iso-levels one volume holds (its first and the further ones): each costs a silhouette extraction a view.
inline constexpr std::size_t kMaxVolumeLevels = 8;

// A CT/MRI volume as a scalar trivariate B-spline D (seed ch. 7): its samples' spline, the singleton table, the
// iso-level shown, and the silhouettes last extracted for the scene camera. World units: millimetres of the file's
// space.
struct VolumeObject {
  std::string name;                             // stable id (shares the namespace of SceneObject names)
  std::string source;                           // the file or folder it was read from
  std::string units;                            // value units ("HU" for CT, "" unknown)
  std::string modality;                         // "CT", "MR", ... or ""
  std::shared_ptr<const VolumeSpline> spline;   // non-null
  std::shared_ptr<const SingletonTable> table;  // non-null, built from `spline`
  double iso = 0.0;                             // iso-level c of D = c, in `units`
  bool visible = true;                          // shown in the viewport; object.visibility
  bool render_visible = true;                   // in recordings and exports; a hidden volume costs nothing there
  bool show_surface = true;                     // draw the volume: its iso-surface, or through `transfer` (dvr)
  // How the volume is drawn (volume.render): the iso-surface D = iso (ray cast), or direct volume rendering of D
  // through `transfer` (seed §7.4, Fig. 7.7) with segments of dvr_step index units.
  enum class RenderMode { iso, dvr } render_mode = RenderMode::iso;
  TransferFunction transfer;             // values in `units`; empty until volume.render sets one
  double dvr_step = 0.5;                 // index units
  glm::vec3 color{0.93f, 0.89f, 0.80f};  // linear RGB of the iso-surface
  VolumeSilhouetteSettings silhouette;
  // Silhouettes of D = iso for `silhouette_camera` (null until extracted, or when disabled).
  std::shared_ptr<const SilhouetteResult> silhouettes;
  Camera silhouette_camera;
  // Further iso-levels (volume.iso "levels"), at most kMaxVolumeLevels − 1; their silhouettes are for
  // silhouette_camera too.
  std::vector<VolumeIsoLevel> more_levels;
  // The iso-surface as a triangle mesh (volume.export of the surface), world millimetres; null until extracted.
  std::shared_ptr<const TriMesh> iso_mesh;

  // World-space corners of the grid box (millimetres).
  Aabb world_bounds() const;
  // The silhouette view of `camera` under this volume's projection setting.
  SilhouetteView silhouette_view(const Camera& camera) const;
  // The same with the camera's pixel size (SilhouetteView::pixel_size): the density a screen shows, for live views.
  SilhouetteView screen_silhouette_view(const Camera& camera) const;
};

class Scene;
// Copy of `scene` at time `time_s` (seconds): every animated object's param_offset becomes offset_at(time_s) (its
// offset_keys and offset_velocity are cleared, so the copy is a still), a clip object's rest_mesh becomes the clip's
// pose at that time (transform applied through refresh, FFD parameters re-embedded with the same embedding), and
// world_mesh is re-evaluated on the CPU reference path (the authoritative geometry: replay --time, anim.record), and
// every animated tile layer (DdmLayer::animated) becomes a still at that time (α fixed, offset as one constant key,
// mesh = ddm_layer_mesh at time_s).
// Objects that are not animated share their meshes with `scene`. Deterministic: the same scene and time give the
// same meshes bit for bit. Throws std::invalid_argument on a non-finite time.
Scene scene_at_time(const Scene& scene, double time_s);
// Copy of `scene` in which only the objects the renderer cannot animate (cpu_animated: clip objects, animated DFFD
// objects) are evaluated at `time_s` (as scene_at_time does for them), the others keep their offset animation
// (keys, velocity) for the renderer to play (gpu::ViewOptions::time_s = time_s): what the editor draws while
// playing. Throws std::invalid_argument on a non-finite time.
Scene scene_with_posed_clips(const Scene& scene, double time_s);

// Why `name` cannot name an object or a tile layer, or "" when it can: names are ids in logs and node names in
// scene.glb (a layer's node is "<object>/<layer>"), so they must be non-empty, at most 256 bytes, free of control
// characters (NUL included) and of '/', and not "." or "..".
std::string object_name_error(const std::string& name);
// `name` with every character object_name_error refuses replaced by '_' (empty → "object"), cut to 256 bytes at a
// character boundary: default names made from file names.
std::string sanitized_object_name(const std::string& name);

class Scene {
 public:
  const std::vector<SceneObject>& objects() const { return objects_; }
  const SceneObject* find(const std::string& name) const;
  SceneObject* find(const std::string& name);
  int index_of(const std::string& name) const;  // -1 if absent

  // Inserts at `index` (-1 = end). Throws std::invalid_argument if the name is taken or object_name_error refuses it.
  void insert(SceneObject object, int index = -1);
  // Removes and returns the object. Throws std::out_of_range if absent.
  SceneObject remove(const std::string& name);
  // Replaces the object with the same name. Throws std::out_of_range if absent.
  void replace(SceneObject object);
  void clear();

  // Volumes (seed ch. 7), in insertion order. Names are shared with objects: a name is used by at most one of them.
  const std::vector<VolumeObject>& volumes() const { return volumes_; }
  const VolumeObject* find_volume(const std::string& name) const;
  // Throws std::invalid_argument if the name is taken (by an object or a volume) or refused; std::invalid_argument
  // when spline or table is null.
  void insert_volume(VolumeObject volume, int index = -1);
  // Removes and returns the volume. Throws std::out_of_range if absent.
  VolumeObject remove_volume(const std::string& name);
  // Replaces the volume with the same name. Throws std::out_of_range if absent.
  void replace_volume(VolumeObject volume);
  int volume_index_of(const std::string& name) const;  // -1 if absent

  Camera camera;
  bool camera_set = false;  // true once a camera.set command ran
  Timeline timeline;        // anim.timeline; the default is Blender's (frames 1–120 at 24 fps)

  // Bounds of all visible world meshes and volume boxes (invalid if there are none).
  Aabb bounds() const;
  // A name not used yet, derived from `base` ("bunny", "bunny.001", ... as Blender does).
  std::string unique_name(const std::string& base) const;

 private:
  std::vector<SceneObject> objects_;
  std::vector<VolumeObject> volumes_;
};

// Default per-object colour for the i-th object (a fixed, colour-blind-friendly palette).
glm::vec3 palette_color(int i);

}  // namespace trispline::core
