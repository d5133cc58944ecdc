// Uniform bilinear refinement through OpenSubdiv Far. See bilinear_subdivision.h.
#include "core/mesh/bilinear_subdivision.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <memory>
#include <stdexcept>

#include "core/mesh/mesh_io.h"
#include "core/mesh/osd_topology.h"

namespace trispline::core {

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using OsdPoint = osd::Primvar<glm::dvec3>;

}  // namespace

TriMesh subdivide_bilinear(const TriMesh& mesh, int level) {
  if (level < 0) throw std::invalid_argument("subdivide_bilinear: level must be >= 0");
  if (level == 0) return mesh;
  const int nv = static_cast<int>(mesh.positions.size());
  std::vector<int> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    indices.push_back(static_cast<Far::Index>(t.x));
    indices.push_back(static_cast<Far::Index>(t.y));
    indices.push_back(static_cast<Far::Index>(t.z));
  }
  const std::unique_ptr<Far::TopologyRefiner> refiner =
      osd::triangle_refiner(nv, indices, Sdc::SCHEME_BILINEAR, Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  if (!refiner) throw std::runtime_error("subdivide_bilinear: OpenSubdiv could not build the topology");
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(level));

  std::vector<OsdPoint> buffer(static_cast<std::size_t>(refiner->GetNumVerticesTotal()));
  for (int i = 0; i < nv; ++i) buffer[i].p = mesh.positions[i];
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  OsdPoint* src = buffer.data();
  for (int lv = 1; lv <= level; ++lv) {
    OsdPoint* dst = src + refiner->GetLevel(lv - 1).GetNumVertices();
    primvar.Interpolate(lv, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner->GetLevel(level);
  TriMesh out;
  out.positions.resize(static_cast<std::size_t>(last.GetNumVertices()));
  for (int i = 0; i < last.GetNumVertices(); ++i) out.positions[i] = src[i].p;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Far::ConstIndexArray fv = last.GetFaceVertices(f);
    for (int k = 1; k + 1 < fv.size(); ++k)  // fan: quads → (a,b,c), (a,c,d)
      out.triangles.emplace_back(static_cast<unsigned>(fv[0]), static_cast<unsigned>(fv[k]),
                                 static_cast<unsigned>(fv[k + 1]));
  }
  compute_vertex_normals(out);
  return out;
}

}  // namespace trispline::core
