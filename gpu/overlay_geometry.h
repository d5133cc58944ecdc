// trispline::gpu overlay geometry — CPU-built line/point/triangle lists for what the renderer draws over the
// shaded scene: FFD control lattices, placement contact samples, and the sketched stroke as a thick polyline.
// Pure functions (no GL), so they are tested without a context.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace trispline::gpu {

struct OverlayVertex {
  glm::vec3 position;  // world units (or pixels with z = 0 for screen-space lists)
  glm::vec4 color;     // display values, alpha
};

// Appends the lattice's control points to `points` and its polylines along u, v and w (as GL_LINES pairs:
// (l-1)·m·n + l·(m-1)·n + l·m·(n-1) segments) to `lines`.
void append_lattice(const core::TrivariateBSpline<glm::dvec3>& lattice, const glm::vec4& line_color,
                    const glm::vec4& point_color, std::vector<OverlayVertex>& lines,
                    std::vector<OverlayVertex>& points);

// Appends the contact samples (#(nu·nv) points: hit → `hit_color`, filled → `filled_color`) and the sampling
// grid's polylines along u and v (GL_LINES pairs) in `grid_color`.
void append_contact_surface(const core::PlacementRecord& placement, const glm::vec4& hit_color,
                            const glm::vec4& filled_color, const glm::vec4& grid_color,
                            std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& points);

// Triangle list (GL_TRIANGLES, pixel coordinates) of a polyline `px` (#S×2 viewport pixels) drawn `width_px`
// wide with round joins and caps (`segments` triangles per disc). Empty for < 1 point; a single point is a disc.
std::vector<glm::vec2> thick_polyline(const std::vector<glm::dvec2>& px, float width_px, int segments = 12);

}  // namespace trispline::gpu
