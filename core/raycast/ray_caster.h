// trispline::core::RayCaster — first-hit ray casting against world-space triangle meshes through Embree 3.
// Built once per query set (e.g. one placement), immutable afterwards, thread-safe for queries.
// Deterministic: the same meshes and rays give the same hits.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct RayHit {
  double t = 0;            // distance along the (unit) direction, world units
  glm::dvec3 position{0};  // world units
  glm::dvec3 normal{0};    // unit geometric normal of the hit triangle, facing the ray origin
  int geometry = -1;       // index of the mesh in the order it was added
  int triangle = -1;       // triangle index within that mesh
};

// How much time Embree spends building the BVH: `high` (SAH with spatial splits; placement rays, the default) or
// `interactive` (Embree's medium quality: a few times faster to build, slightly slower rays — tools that rebuild over
// a freshly edited mesh and cast a handful of rays per mouse move). Hits are the same closest hits either way.
enum class BuildQuality { high, interactive };

class RayCaster {
 public:
  explicit RayCaster(BuildQuality quality = BuildQuality::high);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;

  // Adds a world-space mesh (copied into single-precision Embree buffers); returns its geometry index.
  // Meshes with no triangles are accepted and never hit. Throws std::invalid_argument on non-finite positions.
  int add_mesh(const TriMesh& world_mesh);
  // Builds the BVH; must be called after the last add_mesh and before any query.
  void commit();

  // First hit of the ray origin + t·dir, t in (t_min, t_max]; dir need not be unit (it is normalised).
  std::optional<RayHit> intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_min = 0.0,
                                  double t_max = 1e300) const;
  // Batched: one result per ray (#R origins, #R directions), evaluated in parallel (oneTBB).
  std::vector<std::optional<RayHit>> intersect_all(const std::vector<glm::dvec3>& origins,
                                                   const std::vector<glm::dvec3>& dirs) const;
  bool empty() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace trispline::core
