// Shared helpers of the incision tests: frames cut from a camera looking at a mesh (topology checks are in
// tests/mesh_topology.h).
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "core/incision/incision.h"
#include "core/mesh/tri_mesh.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/camera.h"
#include "tests/mesh_topology.h"

namespace trispline::core::test {

// The frame of a stroke through world points `pts` (projected to pixels of `cam`) on `mesh`.
inline std::optional<IncisionFrame> frame_through(const TriMesh& mesh, const Camera& cam,
                                                  const std::vector<glm::dvec3>& pts,
                                                  std::vector<glm::dvec2>* px_out = nullptr) {
  RayCaster rc;
  rc.add_mesh(mesh);
  rc.commit();
  std::vector<glm::dvec2> px;
  for (const glm::dvec3& p : pts) {
    const glm::dvec3 q = cam.project(p);
    px.emplace_back(q.x, q.y);
  }
  if (px_out) *px_out = px;
  return fit_incision_frame(px, cam, rc);
}

// Points along the straight segment a → b (count ≥ 2).
inline std::vector<glm::dvec3> segment(const glm::dvec3& a, const glm::dvec3& b, int count) {
  std::vector<glm::dvec3> out;
  for (int i = 0; i < count; ++i) out.push_back(a + (b - a) * (double(i) / (count - 1)));
  return out;
}

}  // namespace trispline::core::test
