// Far topology refiners over triangle meshes. See osd_topology.h.
#include "core/mesh/osd_topology.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <stdexcept>

namespace trispline::core::osd {

std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> triangle_refiner(
    int nv, const std::vector<int>& indices, OpenSubdiv::Sdc::SchemeType scheme,
    OpenSubdiv::Sdc::Options::VtxBoundaryInterpolation boundary) {
  namespace Far = OpenSubdiv::Far;
  const int nf = static_cast<int>(indices.size() / 3);
  const std::vector<int> verts_per_face(static_cast<std::size_t>(nf), 3);
  Far::TopologyDescriptor desc;
  desc.numVertices = nv;
  desc.numFaces = nf;
  desc.numVertsPerFace = verts_per_face.data();
  desc.vertIndicesPerFace = indices.data();
  OpenSubdiv::Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(boundary);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  return std::unique_ptr<Far::TopologyRefiner>(Factory::Create(desc, Factory::Options(scheme, sdc)));
}

std::vector<int> checked_triangle_indices(const TriMesh& mesh, const std::string& who) {
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  std::vector<int> indices(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[f][k] >= nv)
        throw std::invalid_argument(who + ": triangle " + std::to_string(f) + " has an index ≥ #V");
      indices[3 * f + k] = static_cast<int>(mesh.triangles[f][k]);
    }
  return indices;
}

}  // namespace trispline::core::osd
