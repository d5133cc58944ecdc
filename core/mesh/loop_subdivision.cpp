// Loop subdivision. See loop_subdivision.h. Source: Loop 1987; OpenSubdiv Far (TopologyRefiner, PrimvarRefiner).
#include "core/mesh/loop_subdivision.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/mesh_io.h"
#include "core/mesh/osd_topology.h"

namespace trispline::core {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

using Point3 = osd::Primvar<glm::dvec3>;
using Point2 = osd::Primvar<glm::dvec2>;

}  // namespace

TriMesh loop_subdivide(const TriMesh& mesh, int levels) {
  if (levels < 0) throw std::invalid_argument("loop_subdivide: levels must be ≥ 0, got " + std::to_string(levels));
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  if (!mesh.uvs.empty() && mesh.uvs.size() != nv)
    throw std::invalid_argument("loop_subdivide: uvs must be empty or #V");
  if (!mesh.face_material.empty() && mesh.face_material.size() != nf)
    throw std::invalid_argument("loop_subdivide: face_material must be empty or #F");
  const std::vector<int> indices = osd::checked_triangle_indices(mesh, "loop_subdivide");
  if (levels == 0 || nf == 0) return mesh;

  const std::unique_ptr<Far::TopologyRefiner> refiner = osd::triangle_refiner(
      static_cast<int>(nv), indices, Sdc::SCHEME_LOOP, Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  if (!refiner) throw std::invalid_argument("loop_subdivide: OpenSubdiv rejected the mesh topology");
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = false;
  refiner->RefineUniform(uniform);

  // Level by level: positions (Loop rules), uvs (linear), face materials (inherited).
  const Far::PrimvarRefinerReal<double> primvar(*refiner);
  std::vector<Point3> pos(nv);
  for (std::size_t v = 0; v < nv; ++v) pos[v].p = mesh.positions[v];
  std::vector<Point2> uv(mesh.uvs.size());
  for (std::size_t v = 0; v < uv.size(); ++v) uv[v].p = mesh.uvs[v];
  std::vector<MaterialSlot> mat = mesh.face_material;
  for (int l = 1; l <= levels; ++l) {
    const Far::TopologyLevel& child = refiner->GetLevel(l);
    std::vector<Point3> pos_next(child.GetNumVertices());
    primvar.Interpolate(l, pos, pos_next);
    pos = std::move(pos_next);
    if (!uv.empty()) {
      std::vector<Point2> uv_next(child.GetNumVertices());
      primvar.InterpolateVarying(l, uv, uv_next);
      uv = std::move(uv_next);
    }
    if (!mat.empty()) {
      std::vector<MaterialSlot> mat_next(child.GetNumFaces());
      primvar.InterpolateFaceUniform(l, mat, mat_next);
      mat = std::move(mat_next);
    }
  }

  const Far::TopologyLevel& last = refiner->GetLevel(levels);
  TriMesh out;
  out.positions.resize(pos.size());
  for (std::size_t v = 0; v < pos.size(); ++v) out.positions[v] = pos[v].p;
  out.uvs.resize(uv.size());
  for (std::size_t v = 0; v < uv.size(); ++v) out.uvs[v] = uv[v].p;
  out.triangles.resize(last.GetNumFaces());
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Far::ConstIndexArray fv = last.GetFaceVertices(f);
    out.triangles[f] = glm::uvec3(fv[0], fv[1], fv[2]);
  }
  out.face_material = std::move(mat);
  compute_vertex_normals(out);
  return out;
}

}  // namespace trispline::core
