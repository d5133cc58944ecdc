// `mesh.subdivide` — uniform Loop subdivision of an object's rest mesh (OpenSubdiv Far, Loop 1987). Fields: declared
// in mesh_subdivide.cpp (ParamSchema), listed in docs/commands.md.
// Every level splits each triangle in four, so #F' = #F · 4^levels (at most 8,000,000: else the command is refused).
// Works in object space on rest_mesh, before any deformation: objects with an FFD lattice (`ffd`), a DFFD rig (`dffd`)
// or a glTF clip (`clip`) are refused, since the lattice parameters / clip targets are per vertex of the old mesh
// (subdivide first, then place or cut).
// Positions follow the Loop rules (smooth interior; boundaries as cubic B-spline curves with corners, i.e. boundary
// vertices with one face, kept: Sdc VTX_BOUNDARY_EDGE_AND_CORNER);
// uvs are interpolated linearly (vertex-varying, PrimvarRefiner::InterpolateVarying: the texture is not
// distorted); face_material is inherited by the four children of each triangle; normals are recomputed
// (compute_vertex_normals). The topology is taken as it is: vertices that the file duplicated (uv seams, flat-shaded
// edges such as the box primitive's) stay duplicated, so such edges are boundaries of Loop subdivision there.
// Deterministic. Undo restores the object bit for bit.
// report.json: levels, vertices_before, vertices_after, triangles_before, triangles_after, ms.
// Errors beyond the declared ranges (CommandError, field named): unknown object, an object with ffd / dffd / clip, a
// mesh OpenSubdiv rejects ("object"); a result over 8,000,000 triangles ("levels").
#pragma once

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/mesh/loop_subdivision.h"

namespace trispline::core {

struct MeshSubdivideParams {
  std::string object;
  int levels = 1;
  std::string scheme = "loop";
};

struct MeshSubdivideCommand : ObjectSnapshotCommand<MeshSubdivideCommand, MeshSubdivideParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
