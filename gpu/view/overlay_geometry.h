// trispline::gpu overlay geometry — CPU-built line/point/triangle lists for what the renderer draws over the
// shaded scene: control lattices, DFFD discontinuity planes, placement contact samples, the contact surface
// S(u,v) = F(u,v,0) of a lattice (tessellated), translucent spheres, and screen strokes as thick polylines.
// Pure functions (no GL), so they are tested without a context.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/dffd/dffd.h"
#include "core/scene/scene.h"
#include "gpu/view/view_options.h"

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

// Appends the two control planes of every discontinuity in `discs` (seed §6.3.1 Def. 6): the control points of
// F⁻ (index d.minus_plane along d.axis) to `minus_points` in `minus_color` and those of F⁺ (d.plus_plane) to
// `plus_points` in `plus_color`, and each plane's polylines along its two other axes (GL_LINES pairs, in the
// plane's colour) to `lines`. Points in lattice storage order (the lower of the two other axes fastest). A
// discontinuity whose axis or plane indices do not fit the lattice is left out.
void append_discontinuity_planes(const core::TrivariateBSpline<glm::dvec3>& lattice,
                                 const std::vector<core::Discontinuity>& discs, const glm::vec4& minus_color,
                                 const glm::vec4& plus_color, std::vector<OverlayVertex>& lines,
                                 std::vector<OverlayVertex>& minus_points, std::vector<OverlayVertex>& plus_points);

// Appends the contact samples (#(nu·nv) points: hit → `hit_color`, filled → `filled_color`) and the sampling
// grid's polylines along u and v (GL_LINES pairs) in `grid_color`.
void append_contact_surface(const core::PlacementRecord& placement, const glm::vec4& hit_color,
                            const glm::vec4& filled_color, const glm::vec4& grid_color,
                            std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& points);

// The contact surface S(u,v) = F(u,v,w0) of a lattice (seed Definition 4; w0 = start of the w domain, 0 for the
// clamped lattices placement builds), sampled on a regular parameter grid.
struct ContactSurfaceTessellation {
  int vertices_u = 0, vertices_v = 0;  // grid size: cells_u + 1 along u (the stroke), cells_v + 1 across it
  // positions #(vertices_u·vertices_v) × 3 = S(u,v), world units, u fastest (index a + vertices_u·b);
  // uvs       same count, the (u,v) of each vertex, uniformly spaced over the u and v knot domains (ends included);
  // normals   same count, unit ∂S/∂u × ∂S/∂v ((0,1,0) where degenerate);
  // triangles 2·cells_u·cells_v, two per grid cell.
  core::TriMesh mesh;
  std::size_t index(int a, int b) const { return std::size_t(a) + std::size_t(vertices_u) * std::size_t(b); }
};

// Tessellates S(u,v) = F(u,v,w0) on a cells_u × cells_v grid. Throws std::invalid_argument if a count is < 1.
ContactSurfaceTessellation tessellate_contact_surface(const core::TrivariateBSpline<glm::dvec3>& lattice,
                                                      int cells_u = 48, int cells_v = 16);

// Appends iso-parameter lines of `t` (GL_LINES pairs along the grid edges): every `every_u`-th line of constant
// u and every `every_v`-th line of constant v, the boundary lines always.
void append_contact_iso_lines(const ContactSurfaceTessellation& t, int every_u, int every_v, const glm::vec4& color,
                              std::vector<OverlayVertex>& lines);

// Triangle list (GL_TRIANGLES, pixel coordinates) of a polyline `px` (#S×2 viewport pixels) drawn `width_px`
// wide with round joins and caps (`segments` triangles per disc). Empty for < 1 point; a single point is a disc.
std::vector<glm::vec2> thick_polyline(const std::vector<glm::dvec2>& px, float width_px, int segments = 12);

// Appends the sphere as a GL_TRIANGLES list (#(6·slices·(stacks−1)) vertices at most, CCW seen from outside, so
// back faces can be culled). Colours are shaded for a viewer at `eye` (world units): brighter facing it, alpha
// growing towards the silhouette so the surface under the sphere stays readable.
void append_sphere(const SphereOverlay& sphere, const glm::vec3& eye, std::vector<OverlayVertex>& triangles,
                   int slices = 32, int stacks = 16);

}  // namespace trispline::gpu
