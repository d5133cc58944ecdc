// trispline::core::DdmLayer — one layer of tiles painted or filled over an object (seed ch. 5): the tile, how its
// instances are laid out on the object's base surface, and their evaluated mesh. Held by SceneObject::ddm_layers
// (immutable, shared between undo states); made by the ddm.* commands (core/commands/ddm_commands.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/ddm/ddm_map.h"
#include "core/ddm/ddm_tile.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Which surface of the object the tiles sit on.
enum class DdmBaseKind {
  limit,        // the Loop limit surface of the object's rest mesh, three charts per triangle (DdmSubdivBase)
  teapot_body,  // the 8 Bézier body patches of the teapot primitive (DdmSplineBase over teapot_body_patches())
};
const char* ddm_base_name(DdmBaseKind k);  // "limit" | "teapot_body"

struct DdmLayer {
  std::string name;          // the layer's name, unique per object
  std::string tile_source;   // "thorn" | "chain" | "hex" | "flower" | the tile file as logged
  DdmTile tile;              // canonical tile space (ddm_tile.h)
  DdmBaseKind base = DdmBaseKind::limit;
  DdmLayout layout = DdmLayout::rect;
  glm::ivec2 counts{1, 1};   // cells per chart (n along u, m along v)
  double height = 0.1;       // world units per tile unit of w, along the base normal
  std::vector<DdmInstance> instances;  // the cells that hold a tile
  std::shared_ptr<const TriMesh> mesh;  // ddm_evaluate of the instances, object space (#instances × #tile vertices)
};

}  // namespace trispline::core
