// trispline::core iso-surface meshes of a VolumeSpline: D(x) = iso as a triangle mesh in world millimetres.
//
//   extract_iso_mesh  sample D on a grid, OpenVDB's volumeToMesh, then every vertex projected onto the spline's
//                     surface D = iso by Newton steps ("on-spline") with exact normals from ∇D
//   write_iso_mesh    the mesh to .glb / .obj / .ply through core/mesh's writers
//
// Orientation: with `material_above` (the default) the material is where D > iso — bone in CT — and normals point
// out of it, towards decreasing D; triangles are counter-clockwise seen from that side (whatever the handedness of
// index_to_world). The seed meshes its iso-surfaces by marching cubes for display under the silhouettes (§7.4,
// Fig. 7.10); here the mesh lies on the spline itself, so it and the silhouettes (silhouettes.h) agree.
#pragma once

#include <cstddef>
#include <filesystem>

#include "core/mesh/tri_mesh.h"
#include "core/volume/singletons.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

struct IsoMeshOptions {
  // Grid samples per index unit and axis (1…4): 1 samples D at the control points' positions, 2 twice as fine (8×
  // the voxels). Vertices: about one per crossed grid cell.
  int samples_per_voxel = 1;
  // OpenVDB's adaptivity in [0, 1]: 0 = one vertex per crossed cell (closed, manifold); larger merges flat regions
  // into fewer, larger polygons.
  double adaptivity = 0.0;
  // true: the material is where D > iso (CT bone, MR tissue brighter than its surroundings): normals point towards
  // decreasing D. false: where D < iso (a signed distance field, dark structures): normals towards increasing D.
  bool material_above = true;
  // Where material reaches the domain box [0, n−1]³ the mesh is closed by planar caps on the box's faces (their
  // vertices lie on the face, not on D = iso). false leaves those openings as boundary loops on the faces.
  bool close_at_boundary = true;
  // Projection of every vertex onto D = iso: Newton steps along ∇D (each the shortest in world millimetres), and where
  // they stall (∇D small or turning) regula falsi towards a corner of the vertex's grid cell on the other side of iso.
  // false keeps OpenVDB's linearly interpolated positions, with normals still from ∇D there.
  bool project_to_spline = true;
  int max_newton_steps = 12;  // per vertex (0…100) before the bracketed fallback; 0: the fallback alone
  // Refusals, checked before the work they guard: the grid's sampled voxels (before sampling) and the triangles
  // the sampled grid makes (from its sign-changing edges, before meshing).
  std::size_t max_sampled_voxels = 400'000'000;  // ≈ 1.6 GB of float samples
  std::size_t max_triangles = 20'000'000;
};

// Figures of one extraction.
struct IsoMeshStats {
  std::size_t sampled_voxels = 0;  // grid voxels evaluated and stored (active voxels of the OpenVDB grid)
  std::size_t inside_tiles = 0;    // 8³ blocks wholly inside the material, stored as one value each
  std::size_t crossing_edges = 0;  // grid edges whose ends lie on either side of iso (= quads at adaptivity 0)
  std::size_t grid_bytes = 0;      // memory of the OpenVDB grid
  std::size_t vertices = 0, triangles = 0;
  std::size_t cap_vertices = 0;  // vertices on the domain box (caps and their rims)
  std::size_t unconverged = 0;   // vertices whose Newton projection stopped above the tolerance
  double max_residual = 0.0;     // max |D − iso| / (control_max − control_min) over the projected vertices
  double sample_ms = 0.0, mesh_ms = 0.0, project_ms = 0.0;  // wall-clock per stage
};

// The iso-surface D = iso of `spline` as a triangle mesh (OpenVDB tools::volumeToMesh on D sampled into a sparse
// FloatGrid, quads split along their shorter diagonal). Returns:
//   positions  #V × 3  world millimetres (spline.index_to_world()); with project_to_spline every vertex not on a cap
//                      satisfies |D − iso| ≤ 1e-6·(control_max − control_min) (counted in stats.unconverged if not)
//   normals    #V × 3  unit, −∇D/|∇D| in world (material_above; +∇D otherwise); a cap's interior vertices get the box
//                      face's normal; a vertex where ∇D vanishes gets its area-weighted face normal
//   triangles  #F × 3  counter-clockwise seen from outside the material
// Only 8³ blocks of grid voxels whose conservative value bounds (the convex hull of their control points) straddle
// iso are sampled (tbb-parallel); blocks wholly inside the material are single tiles, the rest is background.
// Throws std::invalid_argument: iso not finite or not strictly inside (control_min, control_max), options out of
// range, no grid sample above (material_above) / below iso, more sampled voxels than opt.max_sampled_voxels, or more
// triangles than opt.max_triangles. Throws OperationCancelled through `progress` (reported in [0, 1]).
TriMesh extract_iso_mesh(const VolumeSpline& spline, double iso, const IsoMeshOptions& opt = {},
                         const ProgressSink* progress = nullptr, IsoMeshStats* stats = nullptr);

// Writes `mesh` by extension: .glb (write_glb, one node named by the file's stem), .obj or .ply (save_mesh, with
// normals). Throws MeshIoError on another extension, an invalid mesh or a failed write.
void write_iso_mesh(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace trispline::core
