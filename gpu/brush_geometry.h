// trispline::gpu brush geometry — the pressing tool's brush (editor/tools/press_tool.h) as the renderer draws it:
// a translucent sphere (seed §2.4.1's pressing sphere) at the cursor's hit on the object, and the sphere centres
// sampled along the drag. Pure functions (no GL), so they are tested without a context.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "gpu/overlay_geometry.h"

namespace trispline::gpu {

struct BrushSphere {
  glm::dvec3 centre{0.0};                      // world units
  double radius = 0.1;                         // world units, > 0
  glm::vec4 color{0.35f, 0.75f, 1.0f, 0.30f};  // display values; alpha at normal incidence (the rim is denser)
};

// Appends the sphere as a GL_TRIANGLES list (#(6·slices·(stacks−1)) vertices at most, CCW seen from outside, so
// back faces can be culled). Colours are shaded for a viewer at `eye` (world units): brighter facing it, alpha
// growing towards the silhouette so the surface under the brush stays readable.
void append_brush_sphere(const BrushSphere& sphere, const glm::vec3& eye, std::vector<OverlayVertex>& triangles,
                         int slices = 32, int stacks = 16);

}  // namespace trispline::gpu
