// trispline::core — the seed's cube example (seed §2.4.2, Fig. 2.10): a 12-triangle cube deformed by a tri-cubic
// lattice and refined until its deformation error is within a tolerance. The seed does not give its lattice; these are
// the deformations trispline compares refinement rules on (tests, `trispline bench bounds`, docs/performance.md).
#pragma once

#include "core/ffd/ffd.h"

namespace trispline::core {

// The cube [-1,1]³ as 12 triangles over 8 shared vertices, CCW seen from outside, unit corner normals.
TriMesh seed_cube();

// `mesh` (#V × 3 world units) bound to an order-4 lattice of 5 controls per axis (2 cells) over its bounding box,
// bent into an arc of radius 2 about z (x ↦ angle x/2) and twisted about x by 0.5·x rad: a smooth bend + twist.
// Throws std::invalid_argument as embed_bounding_box does.
FfdBinding seed_cube_bend_twist(const TriMesh& mesh);

// The same identity lattice with its corner control point (4, 4, 4) pulled by (0.6, 0.6, 0.6) world units: a
// localised bump, the case the seed's Greville split point is made for.
FfdBinding seed_cube_corner_pull(const TriMesh& mesh);

}  // namespace trispline::core
