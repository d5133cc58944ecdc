// Uniform Loop subdivision of a triangle mesh through OpenSubdiv Far (Loop 1987).
#pragma once

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Uniform Loop subdivision of `mesh` (#V × 3 positions, #F triangles; uvs and face_material optional) by `levels`
// ≥ 0 (0 returns a copy). Result: #F·4^levels triangles; the first #V vertices are the input's vertices moved by
// the Loop vertex rule, in the same order (Far's default child order: children of vertices first, then of edges);
// uvs linear, face_material inherited, normals recomputed.
// Throws std::invalid_argument: levels < 0, a triangle index ≥ #V, uvs / face_material of the wrong size, or
// topology OpenSubdiv cannot refine.
TriMesh loop_subdivide(const TriMesh& mesh, int levels);

}  // namespace trispline::core
