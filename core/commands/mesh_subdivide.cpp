#include "core/commands/mesh_subdivide.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/mesh/mesh_io.h"
#include "core/mesh/osd_topology.h"

namespace trispline::core {

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

constexpr int kMaxLevels = 4;
constexpr std::size_t kMaxTriangles = 8'000'000;

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
  std::vector<std::uint8_t> mat = mesh.face_material;
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
      std::vector<std::uint8_t> mat_next(child.GetNumFaces());
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

const ParamSchema<MeshSubdivideParams>& MeshSubdivideCommand::schema() {
  using P = MeshSubdivideParams;
  static const ParamSchema<P> s =
      ParamSchema<P>("mesh.subdivide",
                     "Subdivide an object's rest mesh uniformly (Loop, OpenSubdiv), before deforming it")
          .field("object", &P::object).required().help("An undeformed object without tile layers")
          .field("levels", &P::levels).range(1, kMaxLevels).help("Subdivision levels; each quadruples the triangles")
          .choice("scheme", &P::scheme, {"loop"}).help("Loop subdivision of the triangles (OpenSubdiv Far)");
  return s;
}

std::string MeshSubdivideCommand::label() const {
  return "Subdivide '" + p_.object + "' (Loop, " + std::to_string(p_.levels) + (p_.levels == 1 ? " level)" : " levels)");
}

std::optional<SceneObject> MeshSubdivideCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(p_.object);
  if (!object) throw CommandError("field 'object': no object named '" + p_.object + "'", "object");
  require_no_tile_layers(*object, "a new mesh");
  const char* deformed = object->ffd ? "an FFD lattice" : object->dffd ? "a DFFD split" : object->clip ? "a glTF clip"
                                                                                                      : nullptr;
  if (deformed)
    throw CommandError("field 'object': '" + p_.object + "' has " + deformed + " bound to its vertices; subdivide " +
                           "before deforming (mesh.subdivide first, then place.sketch / lattice.ring / dffd.* / " +
                           "anim.clip)", "object");
  const TriMesh& rest = *object->rest_mesh;
  const std::size_t tris = rest.triangle_count() << (2 * p_.levels);
  if (tris > kMaxTriangles)
    throw CommandError("field 'levels': " + std::to_string(p_.levels) + " levels would make " + std::to_string(tris) +
                           " triangles (at most " + std::to_string(kMaxTriangles) + ")", "levels");
  const auto t0 = std::chrono::steady_clock::now();
  TriMesh sub;
  try {
    sub = loop_subdivide(rest, p_.levels);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'object': ") + e.what(), "object");
  }
  SceneObject out = *object;
  out.rest_mesh = std::make_shared<const TriMesh>(std::move(sub));
  out.refresh();
  stats_ = {{"levels", p_.levels},
            {"vertices_before", rest.vertex_count()},
            {"vertices_after", out.rest_mesh->vertex_count()},
            {"triangles_before", rest.triangle_count()},
            {"triangles_after", out.rest_mesh->triangle_count()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
