// trispline::core uniform bilinear refinement of a triangle mesh through OpenSubdiv Far: a mesh of many more vertices
// and the same shape (the FFD benchmark turns the 34,835-vertex bunny into 835,994 vertices at level 2).
// The Loop subdivision of `mesh.subdivide` is core/commands/mesh_subdivide.h; the DDM's Loop limit surface is
// core/ddm/ddm_base.h.
#pragma once

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Uniform refinement with OpenSubdiv Far (bilinear scheme, Far::PrimvarRefiner for positions); quads are split
// into two triangles (a,b,c), (a,c,d); normals recomputed (area-weighted), uvs dropped. level 0 returns a copy.
// Throws std::invalid_argument when level < 0, std::runtime_error when OpenSubdiv rejects the topology.
TriMesh subdivide_bilinear(const TriMesh& mesh, int level);

}  // namespace trispline::core
