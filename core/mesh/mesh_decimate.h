// trispline::core coarser versions of a small mesh for drawing it far away (a tile a few pixels wide): quadric edge
// collapses (Garland & Heckbert 1997) by OpenMesh's Decimater, over the mesh's own vertices.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// The triangles of `mesh` after collapsing edges until about `target_vertices` vertices remain (OpenMesh
// DecimaterT with ModQuadricT, and ModNormalFlippingT so no triangle turns over). A collapse keeps one of its two
// vertices where it is, so the result indexes the input's vertices (#F' × 3, F' ≤ #F) and draws with the input's
// vertex buffers; boundary vertices are kept (a tile's rim stays closed against its neighbours). Returns the input's
// triangles when nothing can be collapsed: target_vertices ≥ #V, or a mesh OpenMesh does not take as a manifold
// (a face it refuses). Deterministic. Throws nothing but std::bad_alloc.
std::vector<glm::uvec3> decimated_triangles(const TriMesh& mesh, std::size_t target_vertices);

// The vertices `triangles` use (the distinct indices).
std::size_t used_vertex_count(const std::vector<glm::uvec3>& triangles, std::size_t vertex_count);

}  // namespace trispline::core
