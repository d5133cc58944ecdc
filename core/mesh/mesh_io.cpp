#include "core/mesh/mesh_io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "core/mesh/assimp_io.h"
#include "core/mesh/file_check.h"
#include "core/mesh/gltf_io.h"
#include "core/mesh/path_quote.h"

namespace trispline::core {
namespace {

// Double-precision OpenMesh traits, so PLY/OBJ doubles survive a round trip.
struct DoubleTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using TexCoord2D = OpenMesh::Vec2d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

bool is_gltf_ext(const std::string& e) { return e == ".gltf" || e == ".glb"; }

// OpenMesh (the OBJ/PLY writer) prints complaints to its own log streams; we only use its return value.
struct SilenceOpenMesh {
  SilenceOpenMesh() {
    omerr().disable();
    omout().disable();
    omlog().disable();
  }
  ~SilenceOpenMesh() {
    omerr().enable();
    omout().enable();
    omlog().enable();
  }
};

TriMesh load_gltf(const std::filesystem::path& path) {
  const auto objects = read_gltf_objects(path);
  TriMesh out;
  bool all_normals = true, any_uvs = false;
  bool any_materials = false;
  for (const auto& obj : objects) {
    all_normals = all_normals && !obj.mesh.normals.empty();
    any_uvs = any_uvs || !obj.mesh.uvs.empty();
    any_materials = any_materials || !obj.mesh.face_material.empty();
  }
  for (const auto& obj : objects) {
    const auto base = static_cast<unsigned>(out.positions.size());
    out.positions.insert(out.positions.end(), obj.mesh.positions.begin(), obj.mesh.positions.end());
    if (all_normals) out.normals.insert(out.normals.end(), obj.mesh.normals.begin(), obj.mesh.normals.end());
    if (any_uvs) {
      out.uvs.insert(out.uvs.end(), obj.mesh.uvs.begin(), obj.mesh.uvs.end());
      out.uvs.resize(out.positions.size(), glm::dvec2(0.0));  // objects without TEXCOORD_0 get (0,0)
    }
    for (const auto& t : obj.mesh.triangles) out.triangles.push_back(t + glm::uvec3(base));
    if (any_materials) {  // cut surfaces (glTF "<id>.inside" primitives) keep their slot
      if (obj.mesh.face_material.empty())
        out.face_material.resize(out.triangles.size(), kMaterialSurface);
      else
        out.face_material.insert(out.face_material.end(), obj.mesh.face_material.begin(), obj.mesh.face_material.end());
    }
  }
  return out;
}

}  // namespace

TriMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options, MeshLoadReport* report) {
  const std::string ext = lower_extension(path);
  if (!is_assimp_extension(ext) && !is_gltf_ext(ext))
    throw MeshIoError(quoted(path) + ": unsupported extension '" + ext +
                      "' (supported: .obj .ply .off .stl .dae .fbx .gltf .glb)");
  MeshLoadReport local;
  MeshLoadReport& r = report ? *report : local;
  r = {};
  TriMesh m;
  if (is_gltf_ext(ext)) {
    r.loader = "tinygltf";
    m = load_gltf(path);
    r.faces = m.triangles.size();
  } else {
    m = std::move(read_assimp_file(path, ext, options, r, false).mesh);
  }
  validate_mesh(m, quoted(path));
  r.duplicate_faces = remove_duplicate_triangles(m);
  r.faces = m.triangles.size();
  if (m.normals.empty()) compute_vertex_normals(m);
  return m;
}

std::size_t remove_duplicate_triangles(TriMesh& mesh) {
  struct Key {
    unsigned a, b, c;
    bool operator==(const Key& o) const { return a == o.a && b == o.b && c == o.c; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = k.a;
      h = h * 0x9E3779B97F4A7C15ull ^ k.b;
      h = h * 0x9E3779B97F4A7C15ull ^ k.c;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_set<Key, KeyHash> seen;
  seen.reserve(mesh.triangles.size());
  const bool has_material = !mesh.face_material.empty();
  std::size_t kept = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const glm::uvec3 t = mesh.triangles[f];
    // the lexicographically smallest rotation: same face, same orientation → same key
    std::array<unsigned, 3> best{t[0], t[1], t[2]};
    for (int s = 1; s < 3; ++s) best = std::min(best, std::array<unsigned, 3>{t[s], t[(s + 1) % 3], t[(s + 2) % 3]});
    const Key key{best[0], best[1], best[2]};
    if (!seen.insert(key).second) continue;
    mesh.triangles[kept] = t;
    if (has_material) mesh.face_material[kept] = mesh.face_material[f];
    ++kept;
  }
  const std::size_t removed = mesh.triangles.size() - kept;
  mesh.triangles.resize(kept);
  if (has_material) mesh.face_material.resize(kept);
  return removed;
}

void save_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".ply")
    throw MeshIoError(quoted(path) + ": unsupported extension '" + ext + "' for saving (supported: .obj .ply)");
  validate_mesh(mesh, quoted(path));
  PolyMesh pm;
  OpenMesh::IO::Options opt = ext == ".ply" ? OpenMesh::IO::Options::Binary : OpenMesh::IO::Options::Default;
  const bool has_n = mesh.normals.size() == mesh.positions.size();
  const bool has_uv = mesh.uvs.size() == mesh.positions.size();
  if (has_n) {
    pm.request_vertex_normals();
    opt += OpenMesh::IO::Options::VertexNormal;
  }
  if (has_uv) {
    pm.request_vertex_texcoords2D();
    opt += OpenMesh::IO::Options::VertexTexCoord;
  }
  std::vector<PolyMesh::VertexHandle> vh;
  vh.reserve(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    vh.push_back(pm.add_vertex({p.x, p.y, p.z}));
    if (has_n) pm.set_normal(vh.back(), {mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z});
    if (has_uv) pm.set_texcoord2D(vh.back(), {mesh.uvs[i].x, 1.0 - mesh.uvs[i].y});  // v up in OBJ and PLY
  }
  // Faces OpenMesh rejects (non-manifold) are added on duplicated vertices by OpenMesh's importer, not here: write
  // through the low-level add_face and report failures instead of changing the vertex order silently.
  for (const auto& t : mesh.triangles) {
    const auto fh = pm.add_face(vh[t.x], vh[t.y], vh[t.z]);
    if (!fh.is_valid())
      throw MeshIoError(quoted(path) + ": cannot save a non-manifold or degenerate triangle through OpenMesh");
  }
  bool ok = false;
  {
    SilenceOpenMesh silence;
    ok = OpenMesh::IO::write_mesh(pm, path.string(), opt, 17);
  }
  if (!ok) throw MeshIoError(quoted(path) + ": cannot write file");
}

void validate_mesh(const TriMesh& mesh, const std::string& what) {
  if (mesh.positions.empty()) throw MeshIoError(what + ": empty mesh (no vertices)");
  if (mesh.triangles.empty()) throw MeshIoError(what + ": empty mesh (no triangles)");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw MeshIoError(what + ": non-finite vertex coordinate (NaN or inf) at vertex " + std::to_string(i));
  }
  const std::size_t nv = mesh.positions.size();
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    if (t.x >= nv || t.y >= nv || t.z >= nv)
      throw MeshIoError(what + ": vertex index out of range in triangle " + std::to_string(f) + " (" +
                        std::to_string(nv) + " vertices)");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != nv)
    throw MeshIoError(what + ": " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(nv) +
                      " vertices");
  if (!mesh.uvs.empty() && mesh.uvs.size() != nv)
    throw MeshIoError(what + ": " + std::to_string(mesh.uvs.size()) + " uvs for " + std::to_string(nv) + " vertices");
}

void compute_vertex_normals(TriMesh& mesh) {
  std::vector<glm::dvec3> acc(mesh.positions.size(), glm::dvec3(0.0));
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 &a = mesh.positions[t.x], &b = mesh.positions[t.y], &c = mesh.positions[t.z];
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2 × area: area weighting
    acc[t.x] += n;
    acc[t.y] += n;
    acc[t.z] += n;
  }
  for (auto& n : acc) {
    const double len = glm::length(n);
    n = len > 0 && std::isfinite(len) ? n / len : glm::dvec3(0, 1, 0);
  }
  mesh.normals = std::move(acc);
}

double signed_volume(const TriMesh& mesh) {
  double v = 0;
  for (const auto& t : mesh.triangles)
    v += glm::dot(mesh.positions[t.x], glm::cross(mesh.positions[t.y], mesh.positions[t.z]));
  return v / 6.0;
}

}  // namespace trispline::core
