// trispline::core DDM chart sizes — how large every chart of a base surface is in the world, so a layout can give each
// chart as many cells as make its tiles a chosen world size (ddm_counts_for_size) instead of the same counts on every
// chart (seed §5.3.1's charts differ in size: a limit base's follow its triangles, a UV atlas's its islands).
//
// A size is (mean world length along u, mean world length along v) of a chart parametrised over [0,1]² — world
// (object) units per chart.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/ddm/ddm_base.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Any base: the mean of |S_u| and of |S_v| over `samples` × `samples` cell-centred points of `chart` (deterministic).
// Throws as base.eval (std::out_of_range for a chart out of range).
glm::dvec2 ddm_chart_size(const DdmBase& base, int chart, int samples = 8);

// The charts of DdmSubdivBase(mesh) (3 per triangle, #F · 3 entries), measured on the flat corner quads of the
// triangles (mean length of the quad's two edges along u, and of its two along v): cheap (no limit surface), and the
// limit surface lies within a few percent of it on meshes whose triangles are small against their curvature.
// Throws std::invalid_argument ("base: …"): a triangle index ≥ #V.
std::vector<glm::dvec2> ddm_limit_chart_sizes(const TriMesh& mesh);

// A mesh with texture coordinates as one chart (ddm_rasterize_uv_maps): (s, s) with s = √(Σ world area / Σ uv area)
// over its triangles — exact for an atlas of even texel density (ddm_auto_uv packs its charts so), the mean scale
// otherwise. Throws std::invalid_argument ("base: …"): no uvs (#uv ≠ #V), no uv area.
glm::dvec2 ddm_uv_chart_size(const TriMesh& mesh);

}  // namespace trispline::core
