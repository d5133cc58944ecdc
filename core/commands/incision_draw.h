// `incision.draw` — a cut of chosen shape, depth and opening drawn on an object's surface (seed §6.4, Eq. 6.2,
// Fig. 6.5, 6.6, 6.8; core/incision/incision.h). Fields: declared in incision_draw.cpp (ParamSchema: incision_schema
// for the cut's shape), listed in docs/commands.md.
// The stroke is in viewport pixels of the line's "camera" (the editor's Incision tool writes the view it was drawn
// in), else of the last camera.set, like place.sketch; each pixel's ray is cast against the object alone (misses
// dropped).
// The cut is computed on the object's world mesh (T(rest)) and mapped back to object space (positions by T⁻¹,
// normals by the inverse transpose); vertices the cut does not move keep their rest values bit for bit.
// walls = true adds kMaterialInside faces (the object's inside colour) so the result has no boundary edges;
// walls = false leaves one new boundary loop per incision. Several incisions compose; undo restores bit for bit.
// report.json stats: hits, embedded_vertices, newton_fallbacks, cut_edges, split_faces, tips, wall_faces,
// vertices_before, vertices_after, ms.
// Errors beyond the declared ranges (CommandError, field named; the scene is unchanged): unknown object, or one with
// an FFD / DFFD / clip ("object"); a stroke that misses the surface or cuts no edge ("stroke"); no camera.set
// ("camera"); an opening so wide that the lattice folds ("opening").
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/incision/incision.h"
#include "core/scene/camera.h"

namespace trispline::core {

struct IncisionDrawParams {
  std::string object;
  std::vector<glm::dvec2> stroke;      // #S × 2 viewport pixels
  std::optional<Camera> camera;        // the view the stroke was drawn in; unset = the scene's camera
  IncisionParams incision;             // width and depth are required in a line
  std::optional<glm::ivec3> controls;  // (l, m, n) before knot insertion; unset = the defaults of IncisionParams
};

// The fields of incision.draw that shape the cut (width, depth, opening, walls, order, kernel, wall_rows).
const ParamSchema<IncisionParams>& incision_schema();

struct IncisionDrawCommand : ObjectSnapshotCommand<IncisionDrawCommand, IncisionDrawParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

}  // namespace trispline::core
