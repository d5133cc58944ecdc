// trispline::core::Scene — the document: named objects (rest mesh + transform + optional FFD) and the camera.
//
// Objects are value types whose meshes are shared immutable pointers, so a command can snapshot an object for
// undo at the cost of a few pointers, and build the new object completely before swapping it in (transaction).
// Object order is insertion order (it is the export order of scene.glb).
#pragma once

#include "core/deform/ffd.h"
#include "core/mesh/tri_mesh.h"
#include "core/scene/camera.h"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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
  std::vector<glm::dvec2> stroke_px;        // #S × 2, viewport pixels
  int samples_u = 0, samples_v = 0;         // contact sampling grid (nu × nv)
  std::vector<glm::dvec3> contact_points;   // #(nu·nv) × 3 ray hits (filled where missed), u fastest
  std::vector<unsigned char> contact_hit;   // #(nu·nv): 1 = real hit, 0 = filled from neighbours
};

struct SceneObject {
  std::string name;                          // stable id used by commands
  std::string source;                        // file path or "primitive:<kind>"
  std::shared_ptr<const TriMesh> rest_mesh;  // object space, as loaded (with normals)
  Transform transform;
  glm::vec3 color{0.8f, 0.8f, 0.8f};         // linear RGB
  bool visible = true;
  std::shared_ptr<const FfdBinding> ffd;     // null unless deformed; binding over the *transformed* rest mesh
  std::shared_ptr<const PlacementRecord> placement;  // null unless placed by place.sketch
  std::shared_ptr<const TriMesh> world_mesh;  // evaluated: ffd ? F(E(T(rest)) + param_offset) : T(rest); see refresh()
  // Parameter offset added to every vertex's (u,v,w) before F is evaluated (seed §4.5 animation offset), parameter
  // units; on a periodic axis an offset of 1 is one full turn. Ignored without ffd.
  glm::dvec3 param_offset{0.0};
  // Rate of change of the offset during playback, parameter units per second: at scene time t the object shows
  // F(E(x) + param_offset + offset_velocity·t). world_mesh is the t = 0 pose; see scene_at_time().
  glm::dvec3 offset_velocity{0.0};
  // param_offset + offset_velocity·time_s.
  glm::dvec3 offset_at(double time_s) const { return param_offset + offset_velocity * time_s; }
  bool animated() const { return ffd && offset_velocity != glm::dvec3(0.0); }

  // Recomputes world_mesh from rest_mesh, transform and ffd. Throws std::invalid_argument on inconsistency.
  void refresh();
  // Transformed rest mesh, world units (what an FFD embeds).
  TriMesh world_rest_mesh() const;
};

class Scene;
// Copy of `scene` at time `time_s` (seconds): every animated object's param_offset becomes offset_at(time_s) and its
// world_mesh is re-evaluated on the CPU reference path (the authoritative geometry, e.g. replay --time). Objects
// that are not animated share their meshes with `scene`. Throws std::invalid_argument on a non-finite time.
Scene scene_at_time(const Scene& scene, double time_s);

class Scene {
 public:
  const std::vector<SceneObject>& objects() const { return objects_; }
  const SceneObject* find(const std::string& name) const;
  SceneObject* find(const std::string& name);
  int index_of(const std::string& name) const;  // -1 if absent

  // Inserts at `index` (-1 = end). Throws std::invalid_argument if the name is empty or taken.
  void insert(SceneObject object, int index = -1);
  // Removes and returns the object. Throws std::out_of_range if absent.
  SceneObject remove(const std::string& name);
  // Replaces the object with the same name. Throws std::out_of_range if absent.
  void replace(SceneObject object);
  void clear();

  Camera camera;
  bool camera_set = false;  // true once a camera.set command ran

  // Bounds of all visible world meshes (invalid if there are none).
  Aabb bounds() const;
  // A name not used yet, derived from `base` ("bunny", "bunny.001", ... as Blender does).
  std::string unique_name(const std::string& base) const;

 private:
  std::vector<SceneObject> objects_;
};

// Default per-object colour for the i-th object (a fixed, colour-blind-friendly palette).
glm::vec3 palette_color(int i);

}  // namespace trispline::core
