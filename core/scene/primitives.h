// trispline::core primitives — the meshes behind the `scene.primitive` command. Object space, Y up, right-handed,
// triangles CCW seen from outside (from +y for the open plane and terrain), unit vertex normals; no transform applied.
//
//   teapot    Newell's teapot (32 bicubic Bézier patches, tessellated through BSplineSurface), standing on y = 0,
//             height 1, centred in x and z; spout towards +x
//   plane     2 × 2 in the xz-plane at y = 0, 32 × 32 quads (so that it deforms), uvs in [0,1]²
//   sphere    radius 1, centred; UV sphere, 64 slices × 32 stacks, one vertex per pole (closed)
//   box       2 × 2 × 2, centred; 24 vertices (split per face: flat-shaded edges)
//   cylinder  radius 1, height 2 along y, centred; 64 segments, capped (caps and side split: sharp rims)
//   terrain   2 × 2 in xz, 128 × 128 quads, heights in [0, 0.3] (min 0 and max 0.3 exactly), smooth seeded hills;
//             uvs in [0,1]²
//
// Deterministic: every function gives bit-identical output for the same arguments on every platform with IEEE
// doubles (the terrain derives its random doubles from std::mt19937_64's raw 64-bit output, not from
// std::uniform_real_distribution, whose results are implementation-defined).
#pragma once

#include <cstdint>
#include <string>

#include "core/mesh/tri_mesh.h"
#include "core/spline/bspline_surface.h"

namespace trispline::core {

enum class PrimitiveKind { Teapot, Plane, Sphere, Box, Cylinder, Terrain };

// "teapot" | "plane" | "sphere" | "box" | "cylinder" | "terrain" (exact, lower case).
// Throws std::invalid_argument naming the valid kinds.
PrimitiveKind parse_primitive_kind(const std::string& name);
// Inverse of parse_primitive_kind.
std::string primitive_kind_name(PrimitiveKind kind);

// The primitive with its default resolution. `seed` only affects the terrain.
TriMesh make_primitive(PrimitiveKind kind, std::uint64_t seed = 0);

// Individual generators with their resolution parameters (all ≥ their minimum, else std::invalid_argument).
TriMesh make_plane(int divisions = 32);                 // divisions ≥ 1 quads per side
TriMesh make_sphere(int slices = 64, int stacks = 32);  // slices ≥ 3, stacks ≥ 2
TriMesh make_box();
TriMesh make_cylinder(int segments = 64);                       // segments ≥ 3
TriMesh make_terrain(std::uint64_t seed, int divisions = 128);  // divisions ≥ 2
// segments ≥ 2 samples per patch edge; #F = 32·2·s² − 8·s (the 8 lid/bottom patches lose the s triangles that
// collapse at their pole). Vertices shared by neighbouring patches are welded (within 1e-9 of the model's size).
TriMesh make_teapot(int segments = 10);

// Newell's teapot body (patches 4–11 of the 32: the upper and lower body, 8 bicubic Bézier patches) in the frame of
// make_teapot (y up, standing on y = 0 with height 1), du × dv pointing out of the teapot: DDM's spline base.
std::vector<BSplineSurface<glm::dvec3>> teapot_body_patches();

namespace detail {
// Newell's teapot control data (teapot_data.cpp): z up, Newell's units. Patch rows are v, columns u.
inline constexpr int kTeapotPatchCount = 32;
inline constexpr int kTeapotVertexCount = 290;
extern const int kTeapotPatches[kTeapotPatchCount][16];
extern const double kTeapotVertices[kTeapotVertexCount][3];
}  // namespace detail

}  // namespace trispline::core
