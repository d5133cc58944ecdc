// trispline::core UV spheres — the one sphere generator: the scene's "sphere" primitive (core/scene/primitives.h
// make_sphere), the FFD benchmark's stand-in for a missing mesh and the tests' spheres.
#pragma once

#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Which way the longitude φ turns, seen from +y. Both windings are CCW seen from outside.
//   toward_minus_z — x = r sinθ cosφ, z = −r sinθ sinφ (the benchmark's and the tests' sphere);
//   toward_plus_z  — z = +r sinθ sinφ (the scene primitive).
// The two are mirror images in z. Both stay because the meshes they make are pinned bit for bit (the shipped
// scenes' scene.glb, the tests' figures): one convention for both would change one of them.
enum class SpherePhi { toward_minus_z, toward_plus_z };

// How the normals are made: area_weighted = compute_vertex_normals (mesh_io.h); radial = position ÷ radius.
enum class SphereNormals { area_weighted, radial };

// Triangulated UV sphere of `radius` (world units) centred at the origin, one vertex per pole (closed):
//   positions  #V = 2 + (rings − 1)·segments: the north pole (0, r, 0), then rings i = 1 .. rings − 1 at
//              θ = π·i/rings, each of `segments` vertices at φ = 2π·j/segments, then the south pole (0, −r, 0);
//   triangles  #F = 2·segments·(rings − 1): the north cap, the bands ring by ring, the south cap.
// rings ≥ 2 latitude bands and segments ≥ 3 longitude bands; throws std::invalid_argument otherwise.
TriMesh make_uv_sphere(double radius, int rings, int segments, SpherePhi phi = SpherePhi::toward_minus_z,
                       SphereNormals normals = SphereNormals::area_weighted);

}  // namespace trispline::core
