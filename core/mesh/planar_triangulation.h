// trispline::core::triangulate_nested_loops — triangles filling closed planar loops by the even–odd rule: a point
// is inside when it lies within an odd number of loops (outlines, holes, islands in holes). CGAL's constrained
// Delaunay triangulation (CGAL 2D Triangulations manual, "polygon with holes"). Used by the DFFD caps (seed §6.3.2)
// and the text outlines of scene.text.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <glm/vec2.hpp>
#include <vector>

namespace trispline::core {

// `loops`: closed vertex-index sequences (the last vertex joins the first); `point_of(v)`: vertex v's 2-D position.
// Returns the inside triangles, counter-clockwise in that plane, each with its smallest index first and the list
// sorted (independent of CGAL's storage: the same input gives the same triangles). Points at one 2-D position are one
// vertex (the smallest index); triangles touching a point CGAL made where two constraints cross (self-intersecting
// loops) are left out. Deterministic: points are inserted in CGAL's spatial order (fixed-seed shuffle).
std::vector<std::array<std::uint32_t, 3>> triangulate_nested_loops(
    const std::vector<std::vector<std::uint32_t>>& loops, const std::function<glm::dvec2(std::uint32_t)>& point_of);

}  // namespace trispline::core
