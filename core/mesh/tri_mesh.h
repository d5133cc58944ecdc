// trispline::core::TriMesh — the plain triangle mesh every layer exchanges (libigl style V/F arrays).
//
//   positions  #V × 3   world units (object space for rest meshes, world space for evaluated meshes)
//   normals    #V × 3   unit vertex normals, empty or #V
//   uvs        #V × 2   texture coordinates, empty or #V
//   triangles  #F × 3   vertex indices, counter-clockwise seen from outside
//   face_material #F    per-triangle material slot, empty or #F: an index into the object's MaterialSet
//                       (core/mesh/material.h; 0 = the object's colour when it has none), or kMaterialInside for
//                       its inside colour (cut surfaces: DFFD caps and incision walls, SceneObject::inside_color)
//
// Vertex order is the order of the source file; operations that add vertices append them.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace trispline::core {

// Material slots of TriMesh::face_material: an index into the object's materials, or kMaterialInside.
using MaterialSlot = std::uint16_t;
inline constexpr MaterialSlot kMaterialSurface = 0;      // the object's first material (its colour when it has none)
inline constexpr MaterialSlot kMaterialInside = 0xFFFF;  // cut surfaces (caps, incision walls): the inside colour
inline constexpr std::size_t kMaxMaterialsPerMesh = 0xFFFE;  // material indices below kMaterialInside

struct TriMesh {
  std::vector<glm::dvec3> positions;        // #V × 3
  std::vector<glm::dvec3> normals;          // #V × 3 or empty
  std::vector<glm::dvec2> uvs;              // #V × 2 or empty
  std::vector<glm::uvec3> triangles;        // #F × 3
  std::vector<MaterialSlot> face_material;  // #F or empty (= all 0); material index or kMaterialInside

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool empty() const { return positions.empty() || triangles.empty(); }
  // Material slot of triangle f (kMaterialSurface when face_material is empty).
  MaterialSlot material(std::size_t f) const { return face_material.empty() ? kMaterialSurface : face_material[f]; }
  bool has_inside_faces() const {
    for (MaterialSlot m : face_material)
      if (m == kMaterialInside) return true;
    return false;
  }
};

// Axis-aligned bounding box, world units. An empty box has lo > hi.
struct Aabb {
  glm::dvec3 lo{1e300};
  glm::dvec3 hi{-1e300};
  void extend(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
  glm::dvec3 size() const { return hi - lo; }
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return valid() ? glm::length(hi - lo) : 0.0; }
};

// Bounds of mesh.positions, the mesh's units (an invalid box if there are none).
inline Aabb mesh_bounds(const TriMesh& mesh) {
  Aabb box;
  for (const glm::dvec3& p : mesh.positions) box.extend(p);
  return box;
}

}  // namespace trispline::core
