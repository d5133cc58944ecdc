// Benchmark meshes: OpenSubdiv Far bilinear refinement and a generated UV sphere. See ffd_bench.h.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "core/deform/ffd_bench.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// Primvar buffer element for Far::PrimvarRefinerReal<double>.
struct OsdPoint {
  glm::dvec3 p{0.0};
  void Clear(void* = nullptr) { p = glm::dvec3(0.0); }
  void AddWithWeight(const OsdPoint& src, double w) { p += w * src.p; }
};

}  // namespace

TriMesh subdivide_bilinear(const TriMesh& mesh, int level) {
  if (level < 0) throw std::invalid_argument("subdivide_bilinear: level must be >= 0");
  if (level == 0) return mesh;
  const int nv = static_cast<int>(mesh.positions.size());
  const int nf = static_cast<int>(mesh.triangles.size());
  std::vector<int> verts_per_face(static_cast<std::size_t>(nf), 3);
  std::vector<Far::Index> indices;
  indices.reserve(3 * static_cast<std::size_t>(nf));
  for (const auto& t : mesh.triangles) {
    indices.push_back(static_cast<Far::Index>(t.x));
    indices.push_back(static_cast<Far::Index>(t.y));
    indices.push_back(static_cast<Far::Index>(t.z));
  }
  Far::TopologyDescriptor desc;
  desc.numVertices = nv;
  desc.numFaces = nf;
  desc.numVertsPerFace = verts_per_face.data();
  desc.vertIndicesPerFace = indices.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(Sdc::SCHEME_BILINEAR, sdc)));
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

TriMesh make_uv_sphere(double radius, int rings, int segments) {
  if (rings < 2 || segments < 3) throw std::invalid_argument("make_uv_sphere: need rings >= 2 and segments >= 3");
  TriMesh m;
  const double pi = std::numbers::pi;
  m.positions.emplace_back(0.0, radius, 0.0);  // north pole
  for (int r = 1; r < rings; ++r) {
    const double th = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double ph = 2.0 * pi * s / segments;
      m.positions.emplace_back(radius * std::sin(th) * std::cos(ph), radius * std::cos(th),
                               -radius * std::sin(th) * std::sin(ph));
    }
  }
  m.positions.emplace_back(0.0, -radius, 0.0);  // south pole
  const unsigned south = static_cast<unsigned>(m.positions.size() - 1);
  auto ring = [&](int r, int s) { return static_cast<unsigned>(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(0u, ring(1, s), ring(1, s + 1));
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.triangles.emplace_back(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      m.triangles.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(ring(rings - 1, s), south, ring(rings - 1, s + 1));
  compute_vertex_normals(m);
  return m;
}

}  // namespace trispline::core
