// trispline::core automatic UV charts — texture coordinates for a mesh that has none, so it can take the UV base of
// DDM tiles (seed §5.3.1, §5.4.1: the base drawn into texture space). The surface is cut into charts that are
// topological disks with a bounded spread of normals; each chart is flattened by CGAL's least-squares conformal map
// (Surface_mesh_parameterization::LSCM_parameterizer_3, free border); charts are scaled to the same texel density
// (uv area ∝ world area) and packed into [0,1]², so a tile size in world units gives tiles of even world size.
//
// Deterministic: charts grow from faces in index order, breadth first in triangle-adjacency order; CGAL's solver is
// single-threaded; no randomness.
#pragma once

#include <cstddef>

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct DdmAutoUvStats {
  std::size_t charts = 0;  // after splitting every chart that was not a disk or that flipped
  std::size_t splits = 0;  // charts halved because they were not disks, CGAL failed, or a triangle flipped
  double area_distortion = 1;  // max over triangles of σ/σ̄ divided by min over triangles of σ/σ̄ (σ = uv / world area)
  double area_distortion_p95 = 1;  // the same between the 2.5th and 97.5th percentiles (area weighted)
  double ms = 0;
};

// `mesh` with texture coordinates: vertices split along chart seams (#V' ≥ #V, positions and normals copied — the
// normals are `mesh`'s own, or area-weighted vertex normals of `mesh`, so they agree across seams), triangles in
// `mesh`'s order, uvs (#V' × 2) in [0,1]², every uv triangle counter-clockwise (positive area). `max_normal_deg` bounds
// the angle between a chart's faces' normals and its first face's (degrees, in (0, 90]).
// Throws std::invalid_argument ("base: …"): no triangles, an index ≥ #V, a non-finite position, an edge with more than
// two faces, max_normal_deg out of range.
TriMesh ddm_auto_uv(const TriMesh& mesh, DdmAutoUvStats* stats = nullptr, double max_normal_deg = 60.0);

}  // namespace trispline::core
