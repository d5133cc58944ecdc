// trispline::core DDM tiles — the geometry D that a deformation displacement map places over a base surface
// (seed ch. 5: the arbitrary detail D of §5.2, uploaded "in a canonical coordinate system", §5.3.1).
//
// Canonical tile space: x, y ∈ [0,1]² span one layout cell across the surface, w = z ≥ 0 is the height above it
// (tile units: a layer's `height` scales w into world units along the base surface's normal, seed Eq. 5.1–5.2).
// A tile may reach a little outside [0,1]² (neighbouring cells then overlap, as the seed's interlocking chains do).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"
#include "core/mesh/mesh_clip.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct DdmTile {
  std::string name;  // "thorn", "chain", "hex", "flower", "hair", or the source file's stem
  TriMesh mesh;      // #V × 3 positions (x, y, w) in tile space, unit normals #V × 3 (tile space), #F × 3; a tile
                     // from a textured file also keeps its own uvs (#V × 2) and face_material (#F)
  // The tile file's materials (texture-mapped tiles, seed §5.5, Fig. 5.12), indexed by mesh.face_material; null for
  // generated tiles and files without materials (the tiles then take the layer's colour).
  std::shared_ptr<const MaterialSet> materials;
};

// The materials of a layer's tiles as one set (what its evaluated mesh's face_material indexes).
struct DdmTileMaterials {
  std::shared_ptr<const MaterialSet> set;  // null when no tile carries materials
  std::vector<MaterialSlot> first_slot;    // per tile: the slot of its material 0 in `set`
};

// One set for `tiles`: null when none carries materials; the tiles' own set when they all share one (a single
// textured tile: the same pointer, so nothing is copied); else the sets one after another (images re-indexed), a
// tile without materials contributing a material in `untextured_color` (linear RGB [0,1]³: the layer's colour),
// metallic 0 and roughness 0.6, so that it looks as in an untextured layer. Throws
// std::invalid_argument over kMaxMaterialsPerMesh materials.
DdmTileMaterials ddm_tile_materials(const std::vector<DdmTile>& tiles,
                                    const glm::dvec3& untextured_color = glm::dvec3(1.0));

// Generated tiles for tests and scenes (closed 2-manifolds, outward normals, w ≥ 0, x, y within [0,1]):
//   "thorn"   a bent horn on a round foot, 24 segments × 26 rings (626 vertices, seed Fig. 5.6's 672);
//   "flower"  the thorn's mesh (same vertex count and triangles) shaped as a five-petal flower on a stem: the
//             metamorphosis partner of "thorn" (seed Eq. 5.3, Fig. 5.8);
//   "chain"   two interlocked stadium-shaped links, one lying and one standing, a tube of radius 0.06;
//   "hex"     a hexagonal slab filling the cell (vertices on the cell's border at x = 0, ½, 1), height 0.15, for the
//             hexagonal layout (seed Fig. 5.11);
//   "hair"    a tuft of 32 thin tapering strands leaning towards +x, 0.55–0.95 tall, 34 vertices each (1,088), for
//             hairy surfaces (seed Fig. 5.10, Table 5.1's horse).
// Throws std::invalid_argument for any other kind, naming the valid ones.
DdmTile make_ddm_tile(const std::string& kind);

// True for the kinds make_ddm_tile knows.
bool is_generated_ddm_tile(const std::string& kind);

// Canonical tile from any mesh (OBJ/PLY/glTF as loaded, any units): its bounding box's x and y extents map onto
// [0,1]² (each axis scaled on its own) and its z extent onto [0, h] with h = z-extent / max(x-extent, y-extent), so
// the tile keeps its proportions across the larger of its two spans; normals follow the same scaling (inverse
// transpose, renormalised) or are computed when missing. `materials` (the file's, may be null or empty) is kept with
// the mesh's uvs (or, when it has none, the tile's (x, y) as uvs: a projection from above) and face_material (all
// slot 0 when missing); without materials the tile keeps neither.
// Throws std::invalid_argument: no triangles, a non-finite position, a triangle index ≥ #V, a zero x or y extent.
DdmTile canonical_ddm_tile(const TriMesh& mesh, const std::string& name,
                           std::shared_ptr<const MaterialSet> materials = nullptr);

// The affine map canonical_ddm_tile applies to `mesh` (p ↦ (p − lo) · scale, componentwise). Throws as it does.
struct DdmTileFrame {
  glm::dvec3 lo{0.0}, scale{1.0};
};
DdmTileFrame canonical_ddm_tile_frame(const TriMesh& mesh, const std::string& name);

// `p` turned so that the file's axis `up_axis` (0 x, 1 y, 2 z) becomes the tile's w (z): a cyclic permutation of the
// coordinates, so no mirror (y up, as glTF files stand: (x, y, z) ↦ (z, x, y)). `mesh` turned in place, normals too.
glm::dvec3 ddm_tile_up(const glm::dvec3& p, int up_axis);
void ddm_tile_up(TriMesh& mesh, int up_axis);

// An articulated tile (seed §5.5, Fig. 5.13: robots walking over the teapot): the tile plays a glTF clip. Its rest
// mesh (the file's mesh, turned by up_axis) was made canonical with `frame`; every pose is turned and mapped by that
// same frame, so the tile keeps its size and place in its cell while it moves. The clip loops from scene time 0.
struct DdmTileClip {
  std::shared_ptr<const MeshClip> clip;
  int up_axis = 2;
  DdmTileFrame frame;
  // `rest` (the canonical rest tile: its triangles, uvs and materials kept) with the clip's positions and normals at
  // scene time `time_s`. Deterministic. Throws std::invalid_argument when the clip's vertex count is not the tile's,
  // or the pose is not finite.
  DdmTile pose(const DdmTile& rest, double time_s) const;
};

// Throws std::invalid_argument unless `a` and `b` have the same vertex count and the same triangles (the
// metamorphosis of seed Eq. 5.3 interpolates vertex by vertex). The message names both tiles and the first mismatch.
void require_same_ddm_topology(const DdmTile& a, const DdmTile& b);

}  // namespace trispline::core
