// OpenSubdiv Far over triangle meshes: the one place a Far topology refiner is made from a TriMesh's triangles, for
// uniform bilinear refinement (bilinear_subdivision.h), Loop subdivision (mesh.subdivide) and the Loop limit surface
// of a triangle-mesh tile base (core/ddm).
#pragma once

#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>
#include <opensubdiv/sdc/types.h>

#include <memory>
#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace trispline::core::osd {

// A Far topology refiner over #F triangles. indices: 3·#F vertex indices in [0, nv) (the caller checks them);
// scheme: Sdc::SCHEME_LOOP or SCHEME_BILINEAR; boundary: how boundary vertices are interpolated. Returns null when
// OpenSubdiv rejects the topology (the caller says why, in its own words).
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> triangle_refiner(
    int nv, const std::vector<int>& indices, OpenSubdiv::Sdc::SchemeType scheme,
    OpenSubdiv::Sdc::Options::VtxBoundaryInterpolation boundary);

// The 3·#F vertex indices of mesh's triangles, as Far takes them. Throws std::invalid_argument
// "<who>: triangle F has an index ≥ #V" at the first index out of range.
std::vector<int> checked_triangle_indices(const TriMesh& mesh, const std::string& who);

// Primvar element for Far::PrimvarRefinerReal<double> (its Clear / AddWithWeight protocol); V = glm::dvec2 / dvec3.
template <class V>
struct Primvar {
  V p{0.0};
  void Clear(void* = nullptr) { p = V(0.0); }
  void AddWithWeight(const Primvar& s, double w) { p += w * s.p; }
};

}  // namespace trispline::core::osd
